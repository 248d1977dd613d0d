// The imaging sonar (cpp/unexmin/sensors/sonar/imaging_sonar_sensor.h) against closed forms: a sphere at a known
// range and bearing in its bin and beam, the walls of a box of cold fresh water 1500 / c farther (the echoes timed at
// its sound speed), the acoustic shadow of a box on a flat floor by similar triangles, the echo
// level against the sonar equation's spreading and absorption at two ranges, seeded speckle, the noise floor's codes
// against an exponential power's, pings built only on demand, the same image for any number of caster threads,
// parameter errors.
#include "expect_error.h"
#include "sonar_image_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace unexmin {
namespace test {
namespace {

using sensors::sonar::ImagingSonarSensor;

const Eigen::Vector3d kAt(0, 0, -50);  // the robot, deep below the surface

ImagingSonarSensor& sonar(SonarWorld& w) {
  return w.sensor<ImagingSonarSensor>("sonar");
}

/// One ping (the sensor at 10 Hz: the first sample at t = 0.1 s).
const sensors::sonar::PolarImage& ping(SonarWorld& w) {
  w.samples(sonar(w), 1);
  return sonar(w).last();
}

TEST(ImagingSonar, ASphereLandsInTheBinOfItsNearestPointAndTheBeamOfItsBearing) {
  // 65 rays per beam (0.31 deg apart, the middle one level). The sphere's centre on the axis of beam 100 at 12 m.
  const std::map<std::string, std::string> params = {{"noise", "none"}, {"rays_per_beam", "65"}};
  const double D = 12.0, rho = 0.3;
  auto probe = sonarRig({}, kAt, Eigen::Vector3d::Zero(), "imaging_sonar", 10.0, params);
  const std::size_t k0 = 100;
  const double bearing = sonar(*probe).azimuth(k0);
  EXPECT_NEAR(bearing, 65.0 * kDegree - 100.5 * 130.0 * kDegree / 512.0, 1e-12);  // fov_h/2 - (k + 1/2) fov_h / beams
  const Eigen::Vector3d centre = kAt + D * Eigen::Vector3d(std::cos(bearing), std::sin(bearing), 0.0);
  auto w =
      sonarRig({{"sphere", icosphere(centre, rho, 4)}}, kAt, Eigen::Vector3d::Zero(), "imaging_sonar", 10.0, params);
  const ImagingSonarSensor& s = sonar(*w);
  const auto& image = ping(*w);
  ASSERT_EQ(image.beams, 512u);
  ASSERT_EQ(image.bins, 500u);
  // Every echo within the sphere's angular radius asin(rho / D) and between its nearest point and its silhouette
  // (one bin, and one ray's footprint r de beyond it where the rim's rays spread).
  const double half_angle = std::asin(rho / D);
  const double far = std::sqrt(D * D - rho * rho) + D * 20.0 * kDegree / 65.0;
  std::size_t nearest = image.bins, first_beam = image.beams, last_beam = 0;
  for (std::size_t i = 0; i < image.bins; ++i) {
    for (std::size_t k = 0; k < image.beams; ++k) {
      if (image.at(i, k) == 0)
        continue;
      nearest = std::min(nearest, i);
      first_beam = std::min(first_beam, k);
      last_beam = std::max(last_beam, k);
      EXPECT_LE(std::abs(s.azimuth(k) - bearing), half_angle + 130.0 * kDegree / 512.0) << "beam " << k;
      EXPECT_LE(s.binCenter(i), far + s.rangeResolution()) << "bin " << i;
    }
  }
  // The nearest echo: the head-on ray of beam k0 at D - rho; the echo's beams symmetric about the bearing.
  EXPECT_EQ(static_cast<int>(nearest), s.receiver().echo().bin(D - rho));
  EXPECT_GE(static_cast<int>(first_beam), static_cast<int>(k0) - 7);  // asin(0.3 / 12) = 5.6 beams
  EXPECT_NEAR(0.5 * static_cast<double>(first_beam + last_beam), static_cast<double>(k0), 0.5);
  // The brightest pixel: near head-on, in the bin of the nearest point, within two beams of the bearing.
  const auto brightest = std::max_element(image.codes.begin(), image.codes.end()) - image.codes.begin();
  EXPECT_NEAR(static_cast<double>(static_cast<std::size_t>(brightest) % image.beams), static_cast<double>(k0), 2.0);
  EXPECT_NEAR(static_cast<double>(brightest / image.beams), s.receiver().echo().bin(D - rho), 1.0);
}

TEST(ImagingSonar, TheShadowBehindABoxOnTheFloorHasTheLengthOfSimilarTriangles) {
  // The sonar 2 m above a flat floor, pitched 15 deg down; a box 0.5 m high, 0.2 m deep and 2 m wide whose near face is
  // 8 m ahead. Many rays per beam, so that the footprints are short.
  const double H = 2.0, d = 8.0, t = 0.2, h = 0.5;
  const double floor_z = kAt.z() - H;
  const Geometry object = box(Eigen::Vector3d(d, -1.0, floor_z), Eigen::Vector3d(d + t, 1.0, floor_z + h));
  auto w = sonarRig({{"floor", floorBelow(kAt, H)}, {"object", object}}, kAt, Eigen::Vector3d(0, 15.0 * kDegree, 0),
                    "imaging_sonar", 10.0, {{"noise", "none"}, {"rays_per_beam", "128"}});
  const ImagingSonarSensor& s = sonar(*w);
  const auto& image = ping(*w);
  const Shadow expected = boxShadow(H, d, t, h);
  for (const std::size_t k : {255u, 256u}) {  // the two beams either side of the axis: in the vertical plane
    std::vector<std::uint8_t> beam(image.bins);
    for (std::size_t i = 0; i < image.bins; ++i)
      beam[i] = image.at(i, k);
    const auto gap = longestGap(beam);
    ASSERT_GE(gap.first, 0) << "beam " << k << ": no shadow";
    // Tolerances: one bin, and the footprint of the first floor ray behind the box (half of it before its range).
    const double grazing = std::asin(H / expected.end);
    const double footprint = expected.end * (20.0 * kDegree / 128.0) / std::tan(grazing);
    const double last_echo = s.binCenter(gap.first - 1), first_echo = s.binCenter(gap.second + 1);
    EXPECT_NEAR(last_echo, expected.start, 1.5 * s.rangeResolution()) << "beam " << k;
    EXPECT_NEAR(first_echo, expected.end, 0.5 * footprint + 1.5 * s.rangeResolution()) << "beam " << k;
    EXPECT_NEAR(first_echo - last_echo, expected.end - expected.start, 0.5 * footprint + 3.0 * s.rangeResolution());
  }
}

/// Input level of bin i of a code q: the receiver's chain undone, display_min + q step - G - TVG(r_i) [dB re 1 uPa].
double inputLevel(const ImagingSonarSensor& s, std::size_t i, int q) {
  const auto& e = s.receiver().echo();
  return e.params().display_min + q * e.step() - e.gainDb() - e.tvg(s.binCenter(i));
}

/// The echo level of beam k: the power of its bins summed, as their codes say [dB re 1 uPa].
double beamLevel(const ImagingSonarSensor& s, const sensors::sonar::PolarImage& image, std::size_t k) {
  double power = 0.0;
  for (std::size_t i = 0; i < image.bins; ++i)
    if (image.at(i, k) > 0)
      power += std::pow(10.0, inputLevel(s, i, image.at(i, k)) / 10.0);
  return 10.0 * std::log10(power);
}

TEST(ImagingSonar, TheEchoLevelFollowsTheSpreadingAndAbsorptionOfTheSonarEquation) {
  // The sonar at the centre of spheres of radius 4 m and 12 m: every ray head-on at R. Each beam's rays share its
  // solid angle: EL(R) = SL + BS0 + 10 log10(Omega) - 20 log10(R) - 2 alpha R.
  const double alpha = 0.5;  // [dB/m]: absorption as large as the spreading here
  const std::map<std::string, std::string> params = {
      {"noise", "none"}, {"absorption", "0.5"}, {"range_max", "15"}, {"gain", "0"}, {"tvg_spreading", "10"}};
  double level[2];
  const double radius[2] = {4.0, 12.0};
  for (int n = 0; n < 2; ++n) {
    auto w = sonarRig({{"shell", icosphere(kAt, radius[n], 4)}}, kAt, Eigen::Vector3d::Zero(), "imaging_sonar", 10.0,
                      params);
    const ImagingSonarSensor& s = sonar(*w);
    const auto& image = ping(*w);
    const double omega = 130.0 * kDegree / 512.0 * 2.0 * std::sin(10.0 * kDegree);
    const double expected =
        210.0 - 20.0 + 10.0 * std::log10(omega) - 20.0 * std::log10(radius[n]) - 2.0 * alpha * radius[n];
    for (const std::size_t k : {0u, 200u, 511u}) {
      EXPECT_NEAR(beamLevel(s, image, k), expected, 0.6) << "R " << radius[n] << " beam " << k;
    }
    level[n] = beamLevel(s, image, 256);
  }
  // Between the two: 20 log10(12 / 4) = 9.54 dB of spreading and 2 alpha 8 m = 8 dB of absorption.
  EXPECT_NEAR(level[0] - level[1], 20.0 * std::log10(3.0) + 2.0 * alpha * 8.0, 0.6);
}

TEST(ImagingSonar, SeededSpeckleRepeatsWithTheSeedAndChangesWithIt) {
  const auto image = [](std::uint64_t seed) {
    auto w = sonarRig({{"shell", icosphere(kAt, 6.0, 3)}}, kAt, Eigen::Vector3d::Zero(), "imaging_sonar", 10.0,
                      {{"rays_per_beam", "4"}}, seed);
    w->samples(sonar(*w), 2);
    return sonar(*w).last().codes;
  };
  const auto a = image(7), b = image(7), c = image(8);
  EXPECT_TRUE(a == b);
  EXPECT_FALSE(a == c);
  // Speckle: the echoes of the shell (one bin per beam, the same mean power) differ from beam to beam.
  auto w = sonarRig({{"shell", icosphere(kAt, 6.0, 3)}}, kAt, Eigen::Vector3d::Zero(), "imaging_sonar", 10.0,
                    {{"rays_per_beam", "4"}, {"noise_floor", "false"}});
  const auto& p = ping(*w);
  const std::size_t bin = static_cast<std::size_t>(sonar(*w).receiver().echo().bin(6.0 - 0.01));
  int low = 0, high = 0;
  std::vector<int> codes;
  for (std::size_t k = 0; k < p.beams; ++k)
    codes.push_back(std::max(p.at(bin, k), p.at(bin + 1, k)));
  const int median = [&] {
    std::vector<int> c = codes;
    std::nth_element(c.begin(), c.begin() + c.size() / 2, c.end());
    return c[c.size() / 2];
  }();
  // An exponential power: 10 log10 of it is below its median by more than 10 dB in 1 - exp(-0.0693) = 6.7 % of the
  // beams (P(E < ln 2 / 10)), above by more than 5 dB in exp(-ln 2 10^0.5) = 11.2 % (P(E > 2.19 ln 2)).
  const double step = sonar(*w).receiver().echo().step();
  for (const int q : codes) {
    low += (median - q) * step > 10.0;
    high += (q - median) * step > 5.0;
  }
  const double n = static_cast<double>(codes.size());
  EXPECT_NEAR(low / n, 0.067, 4.0 * std::sqrt(0.067 * 0.933 / n));
  EXPECT_NEAR(high / n, 0.112, 4.0 * std::sqrt(0.112 * 0.888 / n));
}

TEST(ImagingSonar, TheNoiseAloneShowsEachCodeWithTheProbabilityOfAnExponentialPower) {
  // The receiver with no echo: the noise power E x 10^(noise_level / 10) (E exponential, mean 1) reaches code q in
  // bin i with probability exp(-codePower(q, i) / noise power); the codes of 400 beams counted over the bins, within
  // 4 sigma of the sum of those probabilities.
  auto w = sonarRig({{"shell", icosphere(kAt, 6.0, 3)}}, kAt, Eigen::Vector3d::Zero(), "imaging_sonar", 10.0,
                    {{"rays_per_beam", "4"}});
  const sensors::sonar::BeamReceiver& r = sonar(*w).receiver();
  const double noise = std::pow(10.0, r.noise().noise_level / 10.0);
  const std::size_t n = sonar(*w).bins();
  const int beams = 400;
  const sensors::CounterRandom random(3);
  std::vector<std::uint8_t> codes(n);
  std::vector<double> energy;
  const std::vector<int> levels = {1, 3, 10, 30};
  std::vector<double> count(levels.size(), 0.0);
  for (int k = 0; k < beams; ++k) {
    energy.assign(n, 0.0);
    r.receive(energy, random.stream(static_cast<std::uint64_t>(k)), codes.data(), 1);
    for (std::size_t l = 0; l < levels.size(); ++l)
      for (std::size_t i = 0; i < n; ++i)
        count[l] += codes[i] >= levels[l];
  }
  for (std::size_t l = 0; l < levels.size(); ++l) {
    double mean = 0.0, variance = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double p = std::exp(-r.echo().codePower(levels[l], i) / noise);
      mean += beams * p;
      variance += beams * p * (1.0 - p);
    }
    EXPECT_GT(mean, 10.0) << "code " << levels[l];
    EXPECT_NEAR(count[l], mean, 4.0 * std::sqrt(variance) + 1.0) << "code " << levels[l];
  }
}

TEST(ImagingSonar, APingNotWantedIsNotBuiltAndTheNextDoesNotDependOnIt) {
  const auto second = [](bool first_wanted) {
    auto w = sonarRig({{"shell", icosphere(kAt, 6.0, 3)}}, kAt, Eigen::Vector3d::Zero(), "imaging_sonar", 10.0,
                      {{"rays_per_beam", "4"}}, 5);
    bool wanted = first_wanted;
    sonar(*w).setDemand([&wanted] { return wanted; });
    w->samples(sonar(*w), 1);
    EXPECT_EQ(sonar(*w).last().built, first_wanted);
    EXPECT_EQ(sonar(*w).last().codes.empty(), !first_wanted);
    wanted = true;
    w->samples(sonar(*w), 1);
    EXPECT_TRUE(sonar(*w).last().built);
    return sonar(*w).last().codes;
  };
  const auto a = second(true), b = second(false);
  EXPECT_EQ(a.size(), 500u * 512u);
  EXPECT_TRUE(a == b);
}

TEST(ImagingSonar, TheImageDoesNotDependOnTheCastersThreads) {
  // The beams' receivers run in groups on the caster's threads, each beam with its own stream of the ping: one thread
  // or three give the same image, noise and speckle included.
  const auto image = [](int threads) {
    auto w = sonarRig({{"shell", icosphere(kAt, 20.0, 3)}}, kAt, Eigen::Vector3d::Zero(), "imaging_sonar", 10.0,
                      {{"rays_per_beam", "4"}}, 9, threads);
    EXPECT_EQ(w->caster->threads(), threads);
    w->samples(sonar(*w), 2);
    return sonar(*w).last().codes;
  };
  const auto one = image(1), three = image(3);
  EXPECT_EQ(one.size(), 500u * 512u);
  EXPECT_TRUE(one == three);
  EXPECT_GT(std::count_if(one.begin(), one.end(), [](std::uint8_t q) { return q > 0; }), 10000);  // noise beyond 8 m
}

TEST(ImagingSonar, InColdFreshWaterASonarSetToFifteenHundredPlacesEveryWallLong) {
  // The 4 m box (walls at +-2 m) filled with fresh water at 8 degC (sound at ~1441 m/s there), the sonar level at its
  // centre, 300 bins over 0.1..3 m (9.7 mm): a sonar that turns echo times into ranges at 1500 m/s puts every beam's
  // first echo at 1500 / c times the nearest wall of its rays (about 4 %: 8 to 12 bins farther); set to the water's
  // own speed, at the wall. Beam k's rays: azimuth a_k = fov_h/2 - (k + 1/2) fov_h / beams, elevations e_j = -fov_v/2
  // + (j + 1/2) fov_v / rays_per_beam, direction (cos e cos a, cos e sin a, sin e) (the defaults 512, 130 deg, 16,
  // 20 deg).
  sim::WorldConfig box = sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/test_box.world");
  fillWithFreshWater(box, 8.0);
  const double c = freshWaterSoundSpeed(box, 8.0, box.robots.at(0).pose.translation());
  ASSERT_NEAR(c, 1439.1 + 0.0163 * 100.0, 0.3);  // Chen & Millero's pure water plus ~0.016 m/s per dbar
  for (const double assumed : {1500.0, c}) {
    std::map<std::string, std::string> params = {{"noise", "none"}, {"range_max", "3"}, {"nbins", "300"}};
    if (assumed != 1500.0)
      params["sound_speed"] = num(assumed);  // else the default
    SonarWorld w(box,
                 sensorUrdf(SphereSpec(), mountLink("T/sonar_link", Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()),
                            sensorXml("sonar", "imaging_sonar", "T/sonar_link", 10.0, params)));
    const ImagingSonarSensor& s = sonar(w);
    const auto& image = ping(w);
    const Eigen::Isometry3d pose = w.robot().state().pose;  // the sonar link's
    ASSERT_NEAR(freshWaterSoundSpeed(box, 8.0, pose.translation()), c, 0.01);
    ASSERT_NEAR(s.rangeResolution(), 2.9 / 300, 1e-12);
    int long_by_5_bins = 0;
    for (std::size_t k = 0; k < image.beams; ++k) {
      const double a = 65.0 * kDegree - (k + 0.5) * 130.0 * kDegree / 512.0;
      double truth = INFINITY;
      for (int j = 0; j < 16; ++j) {
        const double e = -10.0 * kDegree + (j + 0.5) * 20.0 * kDegree / 16.0;
        const Eigen::Vector3d d =
            pose.linear() * Eigen::Vector3d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
        for (int axis = 0; axis < 3; ++axis)
          if (std::abs(d[axis]) > 1e-12)
            truth = std::min(truth, ((d[axis] > 0 ? 2.0 : -2.0) - pose.translation()[axis]) / d[axis]);
      }
      std::size_t first = 0;
      while (first < image.bins && image.at(first, k) == 0)
        ++first;
      ASSERT_LT(first, image.bins) << "beam " << k << ": no echo";
      EXPECT_NEAR(s.binCenter(first), truth * assumed / c, s.rangeResolution())
          << "sound_speed " << assumed << " beam " << k << " truth " << truth << " m";
      long_by_5_bins += s.binCenter(first) - truth > 5.0 * s.rangeResolution();
    }
    EXPECT_EQ(long_by_5_bins, assumed == 1500.0 ? 512 : 0);  // a model that ignores the water's speed fails
  }
}

TEST(ImagingSonar, BadParametersNameTheSensorAndTheParameter) {
  const auto build = [](double rate, const std::map<std::string, std::string>& params) {
    sonarRig({}, kAt, Eigen::Vector3d::Zero(), "imaging_sonar", rate, params);
  };
  std::string m = thrownMessage<ConfigError>([&] { build(30.0, {}); });  // 1500 / (2 x 30 m) = 25 Hz at most
  EXPECT_TRUE(contains(m, "sensor 'sonar'") && contains(m, "'rate'") && contains(m, "25")) << m;
  m = thrownMessage<ConfigError>([&] { build(10.0, {{"fov_h", "4"}}); });
  EXPECT_TRUE(contains(m, "'fov_h'")) << m;
  m = thrownMessage<ConfigError>([&] { build(10.0, {{"beams", "12.5"}}); });
  EXPECT_TRUE(contains(m, "'beams'") && contains(m, "whole")) << m;
  m = thrownMessage<ConfigError>([&] { build(10.0, {{"beam", "12"}}); });
  EXPECT_TRUE(contains(m, "beam")) << m;
}

}  // namespace
}  // namespace test
}  // namespace unexmin

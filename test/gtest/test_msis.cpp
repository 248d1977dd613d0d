// MSIS model (cpp/unexmin/sensors/sonar/msis_sensor.h, echo_model.h) against closed-form answers computed here: bin
// lines inside a sphere centred on the head and in a 4 m box (also of cold fresh water, the echoes timed at its
// sound speed), the cos^n law on a plate tilted at known angles, the
// head's step schedule, each noise model on and off, seeds, a 360 deg sweep in the shipped tank (walls and
// anchor), and start-up errors naming the parameter.
#include <unexmin/sensors/sonar/msis_sensor.h>
#include "sonar_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>

namespace unexmin {
namespace test {
namespace {

using sensors::sonar::EchoLevel;
using sensors::sonar::MsisSensor;

constexpr double kDeg = M_PI / 180.0;
// The documented sonar equation (echo_model.h, docs/sonars.md) with the MSIS defaults, evaluated here:
// SL 200 dB, BS0 -20 dB, alpha 0.1 dB/m, TVG 20 log10 r + 2 alpha r, code 0 at 125 dB, 80 dB over 255 codes.
const double kOmega = 3 * kDeg * 2 * std::sin(35 * kDeg / 2);  // [sr] the default beam
/// Echo level of one ray of a fan of `rays` over `omega` [sr] at range r, cos(incidence) c, exponent n [dB].
double documentedLevel(double r, double c, double n, std::size_t rays, double omega) {
  return 200.0 - 40 * std::log10(r) - 2 * 0.1 * r - 20.0 + 10 * n * std::log10(c) +
         10 * std::log10(r * r * omega / static_cast<double>(rays) / c);
}
double documentedTvg(double r) {
  return 20 * std::log10(r) + 2 * 0.1 * r;
}
/// Intensity (code / 255) of an output level [dB re 1 uPa].
double documentedCode(double level) {
  return std::clamp(std::round((level - 125.0) / 80.0 * 255.0), 0.0, 255.0) / 255.0;
}
const Eigen::Vector3d kRobot(0, 0, -50);  // [m] robot in the mesh worlds
const Eigen::Vector3d kHead(0, 0, 0.36);  // [m] head in the base frame (msisLinks defaults)

std::map<std::string, std::string> clean(std::map<std::string, std::string> extra = {}) {
  std::map<std::string, std::string> p = {
      {"preset", "thesis_tank"}, {"noise", "none"}, {"step", num(0.9 * kDeg)}, {"joint", "T/msis_head_joint"}};
  for (const auto& kv : extra)
    p[kv.first] = kv.second;
  return p;
}

std::string msisUrdf(const std::map<std::string, std::string>& params, double rate = 25.0,
                     const std::string& links = msisLinks()) {
  return sensorUrdf(SphereSpec(), links, sensorXml("msis", "msis", "T/msis_head_link", rate, params));
}

/// Sphere of radius R centred on the head.
sim::WorldConfig sphereWorld(double R, const std::vector<std::pair<std::string, Geometry>>& extra = {}) {
  std::vector<std::pair<std::string, Geometry>> meshes = {{"msis_sphere", icosphere(kRobot + kHead, R, 5)}};
  meshes.insert(meshes.end(), extra.begin(), extra.end());
  return meshWorld(meshes, kRobot);
}

std::size_t argmax(const std::vector<float>& v) {
  return std::max_element(v.begin(), v.end()) - v.begin();
}

/// First bin with an echo (intensity > 0), or -1.
int firstEcho(const std::vector<float>& v) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (v[i] > 0.0f)
      return static_cast<int>(i);
  return -1;
}

double wrap(double a) {
  return std::atan2(std::sin(a), std::cos(a));
}

TEST(Msis, EveryLineOfATurnPeaksAtTheSphereRadiusAndTheHeadStepsByTheMechanicalStep) {
  const double R = 2.0;
  SonarWorld w(sphereWorld(R), msisUrdf(clean()));
  auto& msis = w.sensor<MsisSensor>("msis");
  const auto& echo = msis.echo();
  ASSERT_NEAR(echo.binWidth(), (3.0 - 0.3) / 400, 1e-12);  // thesis_tank: range_min 0.3 (default), 3 m, 400 bins
  const int expected = echo.bin(R);
  const std::size_t turn = 400;  // 360 / 0.9
  for (std::size_t k = 0; k < turn; ++k) {
    w.samples(msis, 1);
    const auto& line = msis.last();
    ASSERT_EQ(line.intensity.size(), 400u);
    EXPECT_NEAR(wrap(line.angle - (-M_PI + k * 0.9 * kDeg)), 0.0, 1e-9) << "ping " << k;
    EXPECT_LE(std::abs(static_cast<int>(argmax(line.intensity)) - expected), 1) << "ping " << k;
    // Every ray hit the sphere at R: nothing anywhere else on the line.
    for (std::size_t b = 0; b < line.intensity.size(); ++b)
      if (std::abs(static_cast<int>(b) - expected) > 1) {
        ASSERT_EQ(line.intensity[b], 0.0f) << "ping " << k << " bin " << b;
      }
  }
  // Head-on, one range: the whole beam's solid angle at R (documentedLevel), gain 0.2 x 40 dB, TVG at the bin.
  const double level = documentedLevel(R, 1.0, 2.0, 1, kOmega) + 8.0 + documentedTvg(echo.binCenter(expected));
  const auto& v = msis.last().intensity;
  EXPECT_NEAR(v[argmax(v)], documentedCode(level), 1.01 / 255) << "level " << level << " dB";
}

TEST(Msis, IntensityFollowsSpreadingAbsorptionAndGainWithinOneCode) {
  // gain 0 and 0.8 ("high"): the peak bin's code is the sonar equation of the whole fan at R, within one code.
  for (const auto& [gain, db] :
       std::vector<std::pair<std::string, double>>{{"0", 0.0}, {"high", 32.0}, {"0.5", 20.0}}) {
    for (double R : {0.75, 1.1, 1.8, 2.6}) {  // the hull (0.3 m, 0.36 m below the head) clear of the sphere
      SonarWorld w(sphereWorld(R), msisUrdf(clean({{"gain", gain}})));
      auto& msis = w.sensor<MsisSensor>("msis");
      w.samples(msis, 1);
      const auto& v = msis.last().intensity;
      const std::size_t peak = argmax(v);
      ASSERT_LE(std::abs(static_cast<int>(peak) - msis.echo().bin(R)), 1) << "R = " << R;
      const double level = documentedLevel(R, 1.0, 2.0, 1, kOmega) + db + documentedTvg(msis.echo().binCenter(peak));
      EXPECT_NEAR(v[peak], documentedCode(level), 1.01 / 255) << "gain " << gain << " R = " << R << " level " << level;
    }
  }
}

/// A flat square plate (two triangles) of half-size `half` [m] centred on `centre` with unit normal `n`.
Geometry plate(const Eigen::Vector3d& centre, const Eigen::Vector3d& n, double half) {
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  Geometry g;
  for (const auto& [a, b] : std::vector<std::pair<double, double>>{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
    g.vertices.push_back(centre + half * (a * u + b * v));
  g.indices = {0, 1, 2, 0, 2, 3};
  return g;
}

/// Normal of a plate turned `tilt` [rad] about z from facing the head's +x (the head looking along world +x).
Eigen::Vector3d tiltedNormal(double tilt) {
  return Eigen::Vector3d(-std::cos(tilt), std::sin(tilt), 0.0);
}

TEST(Msis, OneRayOnAPlateTiltedByAKnownAngleFollowsTheCosineLaw) {
  // A single ray along the head's +x (hpr = vpr = 1, head angle 0) meets a plate 1.5 m ahead turned by `tilt`
  // about z: incidence = tilt, so the line is one bin at the documented level of one ray (gain 0) within one code
  // (0.31 dB). With n + 1 instead of n the 60 deg echo is 3 dB (10 codes) weaker.
  const double R = 1.5;
  for (double n : {2.0, 1.3}) {
    for (double tilt_deg : {0.0, 35.0, 60.0}) {
      const double tilt = tilt_deg * kDeg;
      const Eigen::Vector3d normal = tiltedNormal(tilt);
      const Eigen::Vector3d centre = kRobot + kHead + Eigen::Vector3d(R, 0, 0);
      SonarWorld w(
          meshWorld({{"tilted_plate", plate(centre, normal, 1.5)}}, kRobot),
          msisUrdf(clean(
              {{"gain", "0"}, {"hpr", "1"}, {"vpr", "1"}, {"sector_left", "0"}, {"backscatter_exponent", num(n)}})));
      auto& msis = w.sensor<MsisSensor>("msis");
      w.samples(msis, 1);
      ASSERT_EQ(msis.last().angle, 0.0);
      // The ray from the head at the ping (the robot hardly moves in the one step before it).
      const Eigen::Isometry3d& pose = w.robot().state().pose;
      const Eigen::Vector3d o = pose * kHead, d = pose.linear() * Eigen::Vector3d::UnitX();
      const double r = (centre - o).dot(normal) / d.dot(normal), cos_theta = std::abs(d.dot(normal));
      ASSERT_NEAR(r, R, 1e-3);
      ASSERT_NEAR(cos_theta, std::cos(tilt), 1e-4);
      const int bin = static_cast<int>(std::floor((r - 0.3) / ((3.0 - 0.3) / 400)));  // range_min 0.3, 3 m, 400 bins
      const double bin_centre = 0.3 + (bin + 0.5) * (3.0 - 0.3) / 400;
      const double expected = documentedCode(documentedLevel(r, cos_theta, n, 1, kOmega) + documentedTvg(bin_centre));
      const auto& line = msis.last().intensity;
      ASSERT_EQ(argmax(line), static_cast<std::size_t>(bin)) << "n " << n << " tilt " << tilt_deg;
      EXPECT_NEAR(line[bin], expected, 1.01 / 255) << "n " << n << " tilt " << tilt_deg << " deg";
      EXPECT_EQ(std::accumulate(line.begin(), line.end(), 0.0), line[bin]);  // nothing elsewhere
    }
  }
}

/// The line the documented model gives for the default fan (msis_sensor.h) from the head at `o` with
/// orientation `R` on the plane through `centre` with unit normal `normal` facing the head: every ray's range
/// and incidence from the plane, its power summed in its bin, then gain G [dB], TVG and the codes.
std::vector<double> documentedPlaneLine(const Eigen::Vector3d& o, const Eigen::Matrix3d& R,
                                        const Eigen::Vector3d& centre, const Eigen::Vector3d& normal, double range_max,
                                        int nbins, double gain_db) {
  const int hpr = 5, vpr = 70;
  const double bw_h = 3 * kDeg, bw_v = 35 * kDeg, w = (range_max - 0.3) / nbins;
  std::vector<double> power(nbins, 0.0);
  for (int i = 0; i < hpr; ++i) {
    for (int j = 0; j < vpr; ++j) {
      const double h = -bw_h / 2 + (i + 0.5) * bw_h / hpr, v = -bw_v / 2 + (j + 0.5) * bw_v / vpr;
      const Eigen::Vector3d d = R * Eigen::Vector3d(std::cos(v) * std::cos(h), std::cos(v) * std::sin(h), std::sin(v));
      const double r = (centre - o).dot(normal) / d.dot(normal);
      const int b = static_cast<int>(std::floor((r - 0.3) / w));
      if (b < 0 || b >= nbins)
        continue;
      power[b] += std::pow(10.0, documentedLevel(r, std::abs(d.dot(normal)), 2.0, hpr * vpr, kOmega) / 10);
    }
  }
  std::vector<double> line(nbins, 0.0);
  for (int b = 0; b < nbins; ++b)
    if (power[b] > 0)
      line[b] = documentedCode(10 * std::log10(power[b]) + gain_db + documentedTvg(0.3 + (b + 0.5) * w));
  return line;
}

TEST(Msis, TheWholeFanOnATiltedPlateSumsTheDocumentedEchoOfEveryRay) {
  // The default fan (5 x 70 rays over 3 x 35 deg) on a plate 1.2 m ahead turned 50 deg about z: every ray has
  // its own range and incidence. Every bin's code = the documented power sum of its rays (within one code).
  const double R = 1.2, tilt = 50 * kDeg;
  const Eigen::Vector3d normal = tiltedNormal(tilt), centre = kRobot + kHead + Eigen::Vector3d(R, 0, 0);
  SonarWorld w(meshWorld({{"tilted_plate", plate(centre, normal, 2.0)}}, kRobot),
               msisUrdf(clean({{"gain", "0"}, {"sector_left", "0"}})));
  auto& msis = w.sensor<MsisSensor>("msis");
  w.samples(msis, 1);
  ASSERT_EQ(msis.last().angle, 0.0);
  const Eigen::Isometry3d& pose = w.robot().state().pose;
  const std::vector<double> expected = documentedPlaneLine(pose * kHead, pose.linear(), centre, normal, 3.0, 400, 0.0);
  const auto& line = msis.last().intensity;
  int echoes = 0;
  for (int b = 0; b < 400; ++b) {
    EXPECT_NEAR(line[b], expected[b], 1.01 / 255) << "bin " << b;
    echoes += expected[b] > 0;
  }
  EXPECT_GT(echoes, 10);  // the tilted plate spreads the fan over many bins
}

TEST(Msis, AFlatWallFrom1To20MetresFollowsTheSonarEquationWithinOneCodeAfterTvg) {
  // A wall facing the head at 1, 2, 5, 10 and 20 m (range window 0.3..21 m, 400 bins, gain "low" = 8 dB): every
  // bin's code = the documented sonar equation of the fan's rays on the plane (within one code, 0.31 dB). The TVG
  // (20 log r + 2 alpha r) keeps the wall near one level; without it the 20 m wall would be 32 dB (100 codes) down.
  for (double D : {1.0, 2.0, 5.0, 10.0, 20.0}) {
    const Eigen::Vector3d normal(-1, 0, 0), centre = kRobot + kHead + Eigen::Vector3d(D, 0, 0);
    SonarWorld w(meshWorld({{"wall", plate(centre, normal, 12.0)}}, kRobot),
                 msisUrdf(clean({{"gain", "low"}, {"sector_left", "0"}, {"range_max", "21"}, {"nbins", "400"}})));
    auto& msis = w.sensor<MsisSensor>("msis");
    w.samples(msis, 1);
    const Eigen::Isometry3d& pose = w.robot().state().pose;
    const std::vector<double> expected =
        documentedPlaneLine(pose * kHead, pose.linear(), centre, normal, 21.0, 400, 8.0);
    const auto& line = msis.last().intensity;
    for (int b = 0; b < 400; ++b)
      EXPECT_NEAR(line[b], expected[b], 1.01 / 255) << "D " << D << " bin " << b;
    const double peak = *std::max_element(line.begin(), line.end());
    EXPECT_GT(peak, 0.3) << "D " << D;  // well inside the 8-bit window: neither lost nor saturated
    EXPECT_LT(peak, 0.9) << "D " << D;
  }
}

TEST(Msis, SectorScanTurnsBackAtTheLimits) {
  const double left = -10 * kDeg, right = 7 * kDeg, step = 3.6 * kDeg;
  SonarWorld w(
      sphereWorld(2.0),
      msisUrdf(clean(
          {{"continuous", "false"}, {"sector_left", num(left)}, {"sector_right", num(right)}, {"step", num(step)}})));
  auto& msis = w.sensor<MsisSensor>("msis");
  // Steps of 3.6 deg; the last step before a limit stops at it, then the head turns back.
  const std::vector<double> deg = {-10, -6.4, -2.8, 0.8, 4.4, 7, 3.4, -0.2, -3.8, -7.4, -10, -6.4};
  for (double d : deg) {
    w.samples(msis, 1);
    EXPECT_NEAR(msis.last().angle, d * kDeg, 1e-9);
  }
}

TEST(Msis, BoxWallsAtEveryHeadAngle) {
  // test_box.world: a closed 4 m cube centred on the origin (walls at +-2 m); the robot at the centre.
  const sim::WorldConfig box = sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/test_box.world");
  SonarWorld w(box,
               sensorUrdf(SphereSpec(), msisLinks(), sensorXml("msis", "msis", "T/msis_head_link", 25.0, clean())));
  auto& msis = w.sensor<MsisSensor>("msis");
  const auto& echo = msis.echo();
  for (std::size_t k = 0; k < 400; ++k) {
    w.samples(msis, 1);
    const auto& line = msis.last();
    const Eigen::Isometry3d head = w.robot().state().pose * msis.headPose(line.angle);
    // First echo: the nearest wall over the fan's rays (ray-plane distances).
    double nearest = INFINITY;
    for (const auto& d0 : msis.fan()) {
      const Eigen::Vector3d d = head.linear() * d0, p = head.translation();
      for (int a = 0; a < 3; ++a)
        if (std::abs(d[a]) > 1e-12)
          nearest = std::min(nearest, ((d[a] > 0 ? 2.0 : -2.0) - p[a]) / d[a]);
    }
    ASSERT_LT(nearest, 3.0);
    EXPECT_LE(std::abs(firstEcho(line.intensity) - echo.bin(nearest)), 1) << "ping " << k << " angle " << line.angle;
    // Facing a wall (every 90 deg): the line peaks at the perpendicular distance.
    if (k % 100 == 0) {
      const double perpendicular = 2.0 - std::abs(head.translation()[k % 200 == 0 ? 0 : 1]);
      EXPECT_LE(std::abs(static_cast<int>(argmax(line.intensity)) - echo.bin(perpendicular)), 1) << "ping " << k;
    }
  }
}

TEST(Msis, InColdFreshWaterAHeadSetToFifteenHundredPlacesEveryWallLong) {
  // The 4 m box filled with fresh water at 8 degC (sound at ~1441 m/s there): a head that turns echo times into
  // ranges at 1500 m/s bins each wall at 1500 / c times its distance (about 4 % farther: 12 bins at 2 m); set to the
  // water's own speed, at the distance. A full turn; the first echo against the nearest wall of the fan's rays.
  sim::WorldConfig box = sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/test_box.world");
  fillWithFreshWater(box, 8.0);
  const double c = freshWaterSoundSpeed(box, 8.0, box.robots.at(0).pose.translation() + kHead);
  ASSERT_NEAR(c, 1439.1 + 0.0163 * 99.6, 0.3);  // Chen & Millero's pure water plus ~0.016 m/s per dbar
  for (const double assumed : {1500.0, c}) {
    // 1500 m/s: the default
    SonarWorld w(box, msisUrdf(clean(assumed == 1500.0 ? std::map<std::string, std::string>{}
                                                       : std::map<std::string, std::string>{{"sound_speed", num(c)}})));
    auto& msis = w.sensor<MsisSensor>("msis");
    const auto& echo = msis.echo();
    int long_by_10_bins = 0;
    for (std::size_t k = 0; k < 400; ++k) {
      w.samples(msis, 1);
      const auto& line = msis.last();
      const Eigen::Isometry3d head = w.robot().state().pose * msis.headPose(line.angle);
      ASSERT_NEAR(freshWaterSoundSpeed(box, 8.0, head.translation()), c, 0.01);
      double nearest = INFINITY;
      for (const auto& d0 : msis.fan()) {
        const Eigen::Vector3d d = head.linear() * d0, p = head.translation();
        for (int a = 0; a < 3; ++a)
          if (std::abs(d[a]) > 1e-12)
            nearest = std::min(nearest, ((d[a] > 0 ? 2.0 : -2.0) - p[a]) / d[a]);
      }
      const int first = firstEcho(line.intensity);
      EXPECT_LE(std::abs(first - echo.bin(nearest * assumed / c)), 1)
          << "sound_speed " << assumed << " ping " << k << " truth " << nearest << " m";
      long_by_10_bins += first - echo.bin(nearest) >= 10;
    }
    if (assumed == 1500.0) {
      EXPECT_EQ(long_by_10_bins, 400);  // far beyond a bin: a model that ignores the water's speed fails
    } else {
      EXPECT_EQ(long_by_10_bins, 0);
    }
  }
}

TEST(Msis, GaussianRangeNoiseSpreadsTheEchoWithItsStandardDeviation) {
  const double R = 2.0, sigma = 0.05;
  SonarWorld w(sphereWorld(R), msisUrdf(clean({{"noise", "gaussian"}, {"gain", "0"}, {"range_noise", num(sigma)}})));
  auto& msis = w.sensor<MsisSensor>("msis");
  const auto& echo = msis.echo();
  double s0 = 0, s1 = 0, s2 = 0;
  for (int k = 0; k < 50; ++k) {
    w.samples(msis, 1);
    const auto& v = msis.last().intensity;
    for (std::size_t b = 0; b < v.size(); ++b) {
      // Back from the code to the bin's power, divided by one head-on ray's power at r: rays per bin.
      if (v[b] <= 0.0f)
        continue;
      const double r = echo.binCenter(b);
      const double level = echo.params().display_min + v[b] * echo.params().display_span;
      const double weight = echo.inputPower(level, r) / echo.strength(sensors::sonar::Echo{r, 1.0}, msis.raysPerPing());
      s0 += weight;
      s1 += weight * r;
      s2 += weight * r * r;
    }
  }
  const double mean = s1 / s0, sd = std::sqrt(s2 / s0 - mean * mean);
  EXPECT_NEAR(mean, R, 0.003);
  // sqrt(sigma^2 + w^2 / 12): the binning adds the bin's uniform variance. 17 500 rays: +-2 %.
  EXPECT_NEAR(sd, std::sqrt(sigma * sigma + echo.binWidth() * echo.binWidth() / 12), 0.05 * sigma);
}

TEST(Msis, SaltAndPepperReplacesTheGivenShareOfBinsWithSpikesNearTheNoiseLevel) {
  // Noise level 135 dB (its spikes show from range_min on), spikes up to 10 dB above it; no noise floor.
  const double R = 2.0, p = 0.1, noise = 135.0, salt = 10.0;
  SonarWorld w(
      sphereWorld(R),
      msisUrdf(clean(
          {{"noise", "gaussian"}, {"salt_pepper", num(p)}, {"noise_level", num(noise)}, {"salt_level", num(salt)}})));
  auto& msis = w.sensor<MsisSensor>("msis");
  const auto& echo = msis.echo();
  const int peak = echo.bin(R);
  std::size_t empty = 0, salted = 0, lines = 200, peppered = 0;
  double highest = 0.0, lowest = 1e9;  // spike level minus noise level [dB]
  for (std::size_t k = 0; k < lines; ++k) {
    w.samples(msis, 1);
    const auto& v = msis.last().intensity;
    for (int b = 0; b < static_cast<int>(v.size()); ++b) {
      if (std::abs(b - peak) <= 1)
        continue;
      ++empty;  // without noise: 0
      if (v[b] <= 0.0f)
        continue;
      ++salted;
      // Output level back to the input: the spike's level above the noise level, +- half a code.
      const double in =
          echo.params().display_min + v[b] * echo.params().display_span - 8.0 - documentedTvg(echo.binCenter(b));
      highest = std::max(highest, in - noise);
      lowest = std::min(lowest, in - noise);
    }
    peppered += v[peak] == 0.0f;  // the echo bin was pepper
  }
  // Salt: p/2 of the bins; binomial, 4 sigma.
  const double n_salt = empty * p / 2.0;
  EXPECT_NEAR(salted, n_salt, 4.0 * std::sqrt(n_salt * (1 - p / 2)));
  const double n_pepper = lines * p / 2.0;
  EXPECT_NEAR(peppered, n_pepper, 4.0 * std::sqrt(n_pepper * (1 - p / 2)));
  // The spikes lie between the noise level and salt_level above it (not up to saturation).
  EXPECT_GT(lowest, -0.2);
  EXPECT_LT(highest, salt + 0.2);
  EXPECT_GT(highest, salt - 1.0);
}

TEST(Msis, AcousticShadowSilencesEverythingBehindAStrongEcho) {
  // A plate 1 m ahead of the head (+x at head angle 0) covering the upper half of the fan; the lower half
  // reaches the sphere at 2 m.
  const Eigen::Vector3d h = kRobot + kHead;
  const auto world =
      sphereWorld(2.0, {{"plate", box(h + Eigen::Vector3d(1.0, -0.5, 0.0), h + Eigen::Vector3d(1.02, 0.5, 0.6))}});
  const auto params = [](const std::string& shadow) {
    return clean({{"noise", "gaussian"},
                  {"shadow", shadow},
                  {"sector_left", "0"},
                  {"shadow_threshold", "0.6"},
                  {"gain", "medium"}});
  };
  SonarWorld off(world, msisUrdf(params("false")));
  SonarWorld on(world, msisUrdf(params("true")));
  auto& a = off.sensor<MsisSensor>("msis");
  auto& b = on.sensor<MsisSensor>("msis");
  off.samples(a, 1);
  on.samples(b, 1);
  const auto& echo = a.echo();
  const int plate = echo.bin(1.0), wall = echo.bin(2.0);
  // Without the shadow: both echoes (the plate strong).
  EXPECT_GE(*std::max_element(a.last().intensity.begin() + plate - 1, a.last().intensity.begin() + plate + 2), 0.6f);
  EXPECT_GT(*std::max_element(a.last().intensity.begin() + wall - 1, a.last().intensity.begin() + wall + 2), 0.05f);
  // With it: the same up to the plate's echo, nothing and the shadow level after it.
  const int strong = static_cast<int>(
      std::find_if(b.last().intensity.begin(), b.last().intensity.end(), [](float i) { return i >= 0.6f; }) -
      b.last().intensity.begin());
  EXPECT_LE(std::abs(strong - plate), 1);
  for (int i = 0; i <= strong; ++i)
    EXPECT_EQ(a.last().intensity[i], b.last().intensity[i]) << i;
  for (int i = strong + 1; i < 400; ++i) {
    EXPECT_EQ(b.last().intensity[i], 0.0f) << i;
    EXPECT_EQ(b.last().level[i], EchoLevel::shadow) << i;
  }
}

TEST(Msis, GroundArtifactsFillTheGapsBetweenSparseRaysAndKeepTheEnergy) {
  // Head pitched 60 deg down over a floor 1.5 m below it, 8 rays across 35 deg: hits centimetres apart.
  const std::string links = msisLinks(Eigen::Vector3d(0, 0, 0.3), Eigen::Vector3d(0, 60 * kDeg, 0));
  const auto world = meshWorld(
      {{"floor", box(kRobot + Eigen::Vector3d(-10, -10, -1.2), kRobot + Eigen::Vector3d(10, 10, -1.14))}}, kRobot);
  const auto params = [](const std::string& artifacts) {
    return clean({{"noise", "gaussian"},
                  {"artifacts", artifacts},
                  {"gain", "0"},
                  {"hpr", "1"},
                  {"vpr", "8"},
                  {"sector_left", "0"},
                  {"artifacts_gap", "0.5"}});
  };
  SonarWorld off(world, msisUrdf(params("false"), 25.0, links));
  SonarWorld on(world, msisUrdf(params("true"), 25.0, links));
  auto& a = off.sensor<MsisSensor>("msis");
  auto& b = on.sensor<MsisSensor>("msis");
  off.samples(a, 1);
  on.samples(b, 1);
  const auto gaps = [](const std::vector<float>& v) {
    int first = -1, last = -1, zero = 0;
    for (int i = 0; i < static_cast<int>(v.size()); ++i)
      if (v[i] > 0.0f)
        last = i, first = first < 0 ? i : first;
    for (int i = first; i <= last; ++i)
      zero += v[i] == 0.0f;
    return std::make_pair(last - first, zero);
  };
  const auto [span_off, zero_off] = gaps(a.last().intensity);
  const auto [span_on, zero_on] = gaps(b.last().intensity);
  EXPECT_GT(span_off, 40);                     // the floor echoes spread over tens of bins...
  EXPECT_GT(zero_off, span_off / 2);           // ...as isolated spikes with gaps between them
  EXPECT_EQ(zero_on, 0);                       // filled
  EXPECT_LE(std::abs(span_on - span_off), 1);  // between the same first and last hits
  // The power, back from the codes (+- half a code, 3.7 %, each bin), is moved, not made.
  const auto power = [](const MsisSensor& m) {
    const auto& echo = m.echo();
    double sum = 0.0;
    for (std::size_t i = 0; i < m.last().intensity.size(); ++i) {
      const float v = m.last().intensity[i];
      if (v > 0.0f)
        sum += echo.inputPower(echo.params().display_min + v * echo.params().display_span, echo.binCenter(i));
    }
    return sum;
  };
  EXPECT_NEAR(power(b), power(a), 0.04 * power(a));
}

TEST(Msis, SameSeedSameScansOtherSeedOtherScansNoiseNoneIsClean) {
  const auto noisy = clean({{"noise", "gaussian"}, {"range_noise", "0.02"}, {"salt_pepper", "0.01"}});
  const auto run = [&](const std::map<std::string, std::string>& params, std::uint64_t seed) {
    SonarWorld w(sphereWorld(2.0), msisUrdf(params), seed);
    auto& msis = w.sensor<MsisSensor>("msis");
    std::vector<float> all;
    for (int k = 0; k < 5; ++k) {
      w.samples(msis, 1);
      all.insert(all.end(), msis.last().intensity.begin(), msis.last().intensity.end());
    }
    return all;
  };
  EXPECT_EQ(run(noisy, 7), run(noisy, 7));
  EXPECT_NE(run(noisy, 7), run(noisy, 8));
  auto none = noisy;
  none["noise"] = "none";
  EXPECT_EQ(run(none, 7), run(clean(), 7));
}

TEST(Msis, FullSweepInTheTankTracesTheWallsAndSeesTheAnchor) {
  // worlds/tank.world: walls at x = +-3, y = +-2 (interior), floor z = -3, anchor hanging at (0, 0) from
  // z = -1.8 to -2.39. The UX-1's mount (hull elevation 65 deg, head 6 cm up); robot 1.2 m from the anchor,
  // so its top is within the 35 deg beam.
  const double el = 65 * kDeg;
  const std::string links = msisLinks(Eigen::Vector3d(0.3 * std::cos(el), 0, 0.3 * std::sin(el)));
  sim::WorldConfig tank = sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/tank.world");
  tank.robots.resize(1);
  tank.robots[0].pose = sim::poseFromXyzRpy(Eigen::Vector3d(-1.2, 0.0, -2.0), Eigen::Vector3d::Zero());
  SonarWorld w(tank, sensorUrdf(SphereSpec(), links, sensorXml("msis", "msis", "T/msis_head_link", 25.0, clean())));
  auto& msis = w.sensor<MsisSensor>("msis");
  const auto& echo = msis.echo();
  int walls = 0, anchor = 0;
  for (std::size_t k = 0; k < 400; ++k) {
    w.samples(msis, 1);
    const auto& line = msis.last();
    const Eigen::Isometry3d head = w.robot().state().pose * msis.headPose(line.angle);
    const Eigen::Vector3d p = head.translation();
    const Eigen::Vector3d axis = head.linear().col(0);
    const double to_anchor = std::abs(wrap(std::atan2(-p.y(), -p.x()) - std::atan2(axis.y(), axis.x())));
    const int first = firstEcho(line.intensity);
    if (to_anchor < 8 * kDeg) {  // towards the anchor: an echo at its distance (the far wall is 4.2 m away)
      ASSERT_GE(first, 0) << "ping " << k;
      const double r = echo.binCenter(first);
      EXPECT_GT(r, std::hypot(p.x(), p.y()) - 0.3) << "ping " << k;
      EXPECT_LT(r, std::hypot(p.x(), p.y()) + 0.3) << "ping " << k;
      ++anchor;
      continue;
    }
    if (to_anchor < 30 * kDeg)
      continue;                 // the anchor's edges
    double nearest = INFINITY;  // walls and floor over the fan's rays
    for (const auto& d0 : msis.fan()) {
      const Eigen::Vector3d d = head.linear() * d0;
      const double lim[3][2] = {{-3, 3}, {-2, 2}, {-3, 1e9}};
      for (int a = 0; a < 3; ++a)
        if (std::abs(d[a]) > 1e-12)
          nearest = std::min(nearest, ((d[a] > 0 ? lim[a][1] : lim[a][0]) - p[a]) / d[a]);
    }
    if (nearest < 2.95) {
      EXPECT_LE(std::abs(first - echo.bin(nearest)), 1) << "ping " << k;
      ++walls;
    } else if (nearest > 3.05) {
      EXPECT_EQ(first, -1) << "ping " << k << ": nothing within 3 m";
    }
  }
  EXPECT_GE(anchor, 10);  // 16 deg of 0.9 deg steps: ~17 pings
  EXPECT_GT(walls, 200);
}

/// The shipped UX-1's MSIS parameters (urdf/properties.xacro): thesis_tank preset, every noise model on.
std::map<std::string, std::string> ux1(std::map<std::string, std::string> extra = {}) {
  std::map<std::string, std::string> p = {{"preset", "thesis_tank"},
                                          {"joint", "T/msis_head_joint"},
                                          {"step", num(0.9 * kDeg)},
                                          {"noise", "gaussian"},
                                          {"gain", "0.2"},
                                          {"range_noise", "0.0075"},
                                          {"salt_pepper", "0.002"},
                                          {"salt_level", "10"},
                                          {"shadow", "true"},
                                          {"shadow_threshold", "0.6"},
                                          {"artifacts", "true"},
                                          {"artifacts_gap", "0.5"},
                                          {"speckle", "true"},
                                          {"noise_floor", "true"},
                                          {"noise_level", "117"},
                                          {"multipath", "true"},
                                          {"surface_reflection", "0.9"},
                                          {"surface_backscatter", "-30"}};
  for (const auto& kv : extra)
    p[kv.first] = kv.second;
  return p;
}

/// The UX-1's MSIS mount: base on the hull at 65 deg elevation, head 6 cm up.
std::string ux1Links() {
  const double el = 65 * kDeg;
  return msisLinks(Eigen::Vector3d(0.3 * std::cos(el), 0, 0.3 * std::sin(el)));
}

TEST(Msis, TheStrongestBinOfAPingLiesOnAWallOrTheAnchorInTheTankAt1MetreDepth) {
  // The usual MSIS wall detector (the strongest bin of each ping) on a full 360 deg turn of the shipped UX-1's
  // MSIS (every noise model and the surface multipath on) from UX_1's place in worlds/tank.world, 1 m deep.
  // A ping counts when some ray of its fan meets a wall or the floor within 3 m (ray-plane distances computed
  // here: walls x = +-3, y = +-2, floor z = -3) or the anchor's bounding box (0.45 x 0.5 x 0.59 m hanging at
  // (0, 0) from 1.8 m depth; ray-box slabs). The detector is right when its bin is within 2 bins of the range at
  // which a ray meets a wall or the floor, or of the range a ray spends inside the anchor's box. Required: >= 95 %.
  // (From here the anchor's top is 33 deg below the head, outside the 35 deg beam: the pings towards it see
  // nothing within 3 m and do not count.)
  // The same 2 m deep, 1.2 m from the anchor (its top within the beam): the anchor's pings count too.
  for (const auto& [xyz, yaw] : std::vector<std::pair<Eigen::Vector3d, double>>{
           {Eigen::Vector3d(-1.7, -0.85, -1.0), 0.46365}, {Eigen::Vector3d(-1.2, 0.0, -2.0), 0.0}}) {
    sim::WorldConfig tank = sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/tank.world");
    tank.robots.resize(1);
    tank.robots[0].pose = sim::poseFromXyzRpy(xyz, Eigen::Vector3d(0, 0, yaw));
    SonarWorld w(tank, sensorUrdf(SphereSpec(), ux1Links(), sensorXml("msis", "msis", "T/msis_head_link", 25.0, ux1())),
                 5);
    auto& msis = w.sensor<MsisSensor>("msis");
    const auto& echo = msis.echo();
    int counted = 0, right = 0;
    for (std::size_t k = 0; k < 400; ++k) {
      w.samples(msis, 1);
      const auto& line = msis.last();
      const Eigen::Isometry3d head = w.robot().state().pose * msis.headPose(line.angle);
      const Eigen::Vector3d p = head.translation();
      const int strongest = static_cast<int>(argmax(line.intensity));
      std::vector<std::pair<int, int>> bins;  // bin intervals where the fan's rays meet a wall, the floor or the anchor
      for (const auto& d0 : msis.fan()) {
        const Eigen::Vector3d d = head.linear() * d0;
        const double lim[3][2] = {{-3, 3}, {-2, 2}, {-3, 1e9}};
        double nearest = INFINITY;
        for (int a = 0; a < 3; ++a)
          if (std::abs(d[a]) > 1e-12)
            nearest = std::min(nearest, ((d[a] > 0 ? lim[a][1] : lim[a][0]) - p[a]) / d[a]);
        if (nearest < 3.0)
          bins.emplace_back(echo.bin(nearest), echo.bin(nearest));
        // The anchor's bounding box (worlds/meshes/anchor.stl at (0, 0, -1.8)): the ray's entry..exit (slabs).
        const double box[3][2] = {{-0.2245, 0.2245}, {-0.25, 0.25}, {-2.39, -1.8}};
        double t_in = 0.0, t_out = nearest;
        for (int a = 0; a < 3 && t_in <= t_out; ++a) {
          if (std::abs(d[a]) < 1e-12) {
            if (p[a] < box[a][0] || p[a] > box[a][1])
              t_in = INFINITY;
            continue;
          }
          const double t0 = (box[a][0] - p[a]) / d[a], t1 = (box[a][1] - p[a]) / d[a];
          t_in = std::max(t_in, std::min(t0, t1));
          t_out = std::min(t_out, std::max(t0, t1));
        }
        if (t_in <= t_out && t_in < 3.0)
          bins.emplace_back(echo.bin(t_in), t_out < 3.0 ? echo.bin(t_out) : 399);
      }
      if (bins.empty())
        continue;
      ++counted;
      bool ok = false;
      for (const auto& [lo, hi] : bins)
        ok = ok || (strongest >= lo - 2 && strongest <= hi + 2);
      right += ok;
    }
    ASSERT_GT(counted, 200);  // most pings see a wall within 3 m
    EXPECT_GE(right, 0.95 * counted) << right << " of " << counted << " pings";
    std::printf("[ MSIS ] %.1f m deep: strongest bin on a wall or the anchor in %d of %d pings (%.1f %%)\n", -xyz.z(),
                right, counted, 100.0 * right / counted);
  }
}

TEST(Msis, SurfaceMultipathGhostsAtTheMirrorRangeNearTheSurfaceAndNoneDeeper) {
  // The head at 0.4 m depth looking along +x at a box target whose face is 2.5 m ahead and 0.1..0.3 m deep: the
  // direct echo comes from the rays meeting the face (2.3..6.9 deg up), the ghost from the rays that meet the
  // surface and, mirrored, the face: at the range of the face's mirror image (2.55..2.6 m, 11..16 deg up), both
  // computed here from the documented fan. At 2 m depth (robot and target 1.6 m deeper, the same geometry
  // relative to each other) no ray of the 35 deg beam reaches the surface within 3 m: the direct echo is the same
  // code for code, the ghost gone. noise none; surface backscatter off (-100 dB) to see the ghost alone.
  const auto params = clean({{"sector_left", "0"}, {"surface_backscatter", "-100"}, {"gain", "medium"}});
  const double ahead = 2.5;
  std::vector<float> lines[2];
  std::vector<int> direct_bins, ghost_bins;
  for (int deep = 0; deep < 2; ++deep) {
    const double head_depth = deep ? 2.0 : 0.4;
    const Eigen::Vector3d robot(0, 0, -head_depth - kHead.z());
    const Eigen::Vector3d head = robot + kHead;
    SonarWorld w(meshWorld({{"target", plateTarget(head, ahead, head_depth - 0.2)}}, robot), msisUrdf(params));
    auto& msis = w.sensor<MsisSensor>("msis");
    w.samples(msis, 1);
    ASSERT_EQ(msis.last().angle, 0.0);
    lines[deep] = msis.last().intensity;
    if (deep)
      continue;
    // Expected ranges at 0.4 m: every ray of the fan against the face x = ahead (0.1..0.3 m deep, |y| <= 0.3)
    // directly, and after the mirror at z = 0.
    const Eigen::Isometry3d& pose = w.robot().state().pose;
    const Eigen::Vector3d o = pose * kHead;
    for (const auto& d0 : msis.fan()) {
      const Eigen::Vector3d d = pose.linear() * d0;
      const double face = head.x() + ahead;
      const double t = (face - o.x()) / d.x();
      const Eigen::Vector3d q = o + t * d;
      if (q.z() >= -0.3 && q.z() <= -0.1 && std::abs(q.y()) <= 0.3)
        direct_bins.push_back(msis.echo().bin(t));
      if (d.z() <= 0)
        continue;
      const double s = -o.z() / d.z();  // to the surface
      if (s >= t)
        continue;                         // meets the face's plane first
      const double z_reflected = -q.z();  // the straight ray's height above the surface, mirrored below it
      if (z_reflected >= -0.3 && z_reflected <= -0.1 && std::abs(q.y()) <= 0.3)
        ghost_bins.push_back(msis.echo().bin(t));
    }
  }
  ASSERT_FALSE(direct_bins.empty());
  ASSERT_FALSE(ghost_bins.empty());
  const auto [dmin, dmax] = std::minmax_element(direct_bins.begin(), direct_bins.end());
  const auto [gmin, gmax] = std::minmax_element(ghost_bins.begin(), ghost_bins.end());
  ASSERT_GT(*gmin, *dmax + 2);  // the ghost lies beyond the direct echo
  const auto& near = lines[0];
  const auto& deep = lines[1];
  // Near the surface: the ghost's bins carry an echo, nothing outside the two expected intervals (+- 1 bin).
  const float ghost = *std::max_element(near.begin() + *gmin, near.begin() + *gmax + 1);
  EXPECT_GT(ghost, 0.2f);
  for (int b = 0; b < static_cast<int>(near.size()); ++b) {
    const bool expected = (b >= *dmin - 1 && b <= *dmax + 1) || (b >= *gmin - 1 && b <= *gmax + 1);
    if (!expected) {
      EXPECT_EQ(near[b], 0.0f) << "bin " << b << " at 0.4 m";
    }
  }
  // 2 m deep: the direct echo the same, code for code; the ghost gone.
  for (int b = *dmin - 1; b <= *dmax + 1; ++b)
    EXPECT_EQ(deep[b], near[b]) << "bin " << b;
  for (int b = 0; b < static_cast<int>(deep.size()); ++b)
    if (b < *dmin - 1 || b > *dmax + 1) {
      EXPECT_EQ(deep[b], 0.0f) << "bin " << b << " at 2 m";
    }
}

TEST(Msis, TheSurfaceItselfEchoesFromWhereTheTopRaysMeetIt) {
  // Open water, the head 0.4 m deep looking along +x, nothing else: the only echo is the surface's own
  // backscatter, starting at the range where the fan's top ray (elevation 17.5 - 0.25 deg) meets it:
  // 0.4 / sin(17.25 deg) = 1.35 m; deeper than 3 sin(17.25 deg) = 0.89 m nothing reaches it.
  for (double depth : {0.4, 1.0}) {
    const Eigen::Vector3d robot(0, 0, -depth - kHead.z());
    SonarWorld w(meshWorld({}, robot), msisUrdf(clean({{"sector_left", "0"}, {"gain", "high"}})));
    auto& msis = w.sensor<MsisSensor>("msis");
    w.samples(msis, 1);
    const double top = 17.5 * kDeg - 0.25 * kDeg;
    const double o_z = (w.robot().state().pose * kHead).z();
    const int first = firstEcho(msis.last().intensity);
    if (depth > 3 * std::sin(top)) {
      EXPECT_EQ(first, -1) << "depth " << depth;
      continue;
    }
    EXPECT_LE(std::abs(first - msis.echo().bin(-o_z / std::sin(top))), 2) << "depth " << depth;
  }
}

TEST(Msis, BadParametersNameTheSensorAndTheParameter) {
  const auto expectError = [](const std::map<std::string, std::string>& p, const std::string& what,
                              double rate = 25.0) {
    try {
      SonarWorld w(sphereWorld(2.0), msisUrdf(p, rate));
      FAIL() << "no error for " << what;
    } catch (const ConfigError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("sensor 'msis'"), std::string::npos) << m;
      EXPECT_NE(m.find("'" + what + "'"), std::string::npos) << m;
    }
  };
  expectError(clean({{"step", num(1.0 * kDeg)}}), "step");
  expectError(clean({{"nbins", "0"}}), "nbins");
  expectError(clean({{"range_max", "0.1"}}), "range_max");
  expectError(clean({{"preset", "tank"}}), "preset");
  expectError(clean({{"gain", "loud"}}), "gain");
  expectError(clean({{"spreading_exponent", "2"}}), "spreading_exponent");  // replaced by the sonar equation
  expectError(clean({{"surface_reflection", "1.5"}}), "surface_reflection");
  expectError(clean({{"noise_floor", "maybe"}}), "noise_floor");
  expectError(clean({{"beam_with_h", "0.1"}}), "beam_with_h");
  expectError(clean({{"joint", "T/t0_joint"}}), "joint");
  expectError(clean(), "rate", 300.0);  // 1500 / (2 x 3 m) = 250 pings/s at most
}

}  // namespace
}  // namespace test
}  // namespace unexmin

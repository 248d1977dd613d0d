// MSIS model (cpp/sonar/msis_sensor.h, echo_model.h) against closed-form answers computed here: bin lines
// inside a sphere centred on the head and in a 4 m box, the cos^n law on a plate tilted at known angles, the
// head's step schedule, each noise model on and off, seeds, a 360 deg sweep in the shipped tank (walls and
// anchor), and start-up errors naming the parameter.
#include <unexmin/sensors/sonar/msis_sensor.h>
#include "sonar_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace unexmin {
namespace test {
namespace {

using sonar::EchoLevel;
using sonar::MsisSensor;

constexpr double kDeg = M_PI / 180.0;
const Eigen::Vector3d kRobot(0, 0, -50);        // [m] robot in the mesh worlds
const Eigen::Vector3d kHead(0, 0, 0.36);        // [m] head in the base frame (msisLinks defaults)

std::map<std::string, std::string> clean(std::map<std::string, std::string> extra = {})
{
  std::map<std::string, std::string> p = {{"preset", "thesis_tank"}, {"noise", "none"}, {"step", num(0.9 * kDeg)},
                                          {"joint", "T/msis_head_joint"}};
  for (const auto& kv : extra) p[kv.first] = kv.second;
  return p;
}

std::string msisUrdf(const std::map<std::string, std::string>& params, double rate = 25.0,
                     const std::string& links = msisLinks())
{
  return sensorUrdf(SphereSpec(), links, sensorXml("msis", "msis", "T/msis_head_link", rate, params));
}

/// Sphere of radius R centred on the head.
sim::WorldConfig sphereWorld(double R, const std::vector<std::pair<std::string, Geometry>>& extra = {})
{
  std::vector<std::pair<std::string, Geometry>> meshes = {{"msis_sphere", icosphere(kRobot + kHead, R, 5)}};
  meshes.insert(meshes.end(), extra.begin(), extra.end());
  return meshWorld(meshes, kRobot);
}

std::size_t argmax(const std::vector<float>& v) { return std::max_element(v.begin(), v.end()) - v.begin(); }

/// First bin with an echo (intensity > 0), or -1.
int firstEcho(const std::vector<float>& v)
{
  for (std::size_t i = 0; i < v.size(); ++i)
    if (v[i] > 0.0f) return static_cast<int>(i);
  return -1;
}

double wrap(double a) { return std::atan2(std::sin(a), std::cos(a)); }

TEST(Msis, EveryLineOfATurnPeaksAtTheSphereRadiusAndTheHeadStepsByTheMechanicalStep)
{
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
  // Head-on, one range: I = min(1, A * cos(0)^2 * (1 / R)^2 * 10^(-2 * 0.1 * R / 10)), A = 10^(40 * 0.2 / 10).
  const double I = std::min(1.0, std::pow(10.0, 0.8) / (R * R) * std::pow(10.0, -0.02 * R));
  double sum = 0.0;
  for (float v : msis.last().intensity) sum += v;
  EXPECT_NEAR(sum, I, 1e-3);
}

TEST(Msis, IntensityFollowsSpreadingAbsorptionAndGain)
{
  // gain 0 (A = 1), so nothing saturates: the line's sum is the echo of the whole fan at R.
  for (double R : {1.1, 1.8, 2.6}) {  // >= 1 m: 1 / R^2 <= 1, no saturation
    SonarWorld w(sphereWorld(R), msisUrdf(clean({{"gain", "0"}})));
    auto& msis = w.sensor<MsisSensor>("msis");
    w.samples(msis, 1);
    const auto& v = msis.last().intensity;
    const double sum = std::accumulate(v.begin(), v.end(), 0.0);
    EXPECT_NEAR(sum, 1.0 / (R * R) * std::pow(10.0, -0.02 * R), 2e-3 * sum) << "R = " << R;
  }
}

/// A flat square plate (two triangles) of half-size `half` [m] centred on `centre` with unit normal `n`.
Geometry plate(const Eigen::Vector3d& centre, const Eigen::Vector3d& n, double half)
{
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  Geometry g;
  for (const auto& [a, b] : std::vector<std::pair<double, double>>{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
    g.vertices.push_back(centre + half * (a * u + b * v));
  g.indices = {0, 1, 2, 0, 2, 3};
  return g;
}

/// Normal of a plate turned `tilt` [rad] about z from facing the head's +x (the head looking along world +x).
Eigen::Vector3d tiltedNormal(double tilt) { return Eigen::Vector3d(-std::cos(tilt), std::sin(tilt), 0.0); }

/// Expected echo strength of one ray from the documented formula (echo_model.h), gain 0 and the defaults
/// s = 2, r_ref = 1 m, alpha = 0.1 dB/m: w cos(theta)^n (1 / r)^2 10^(-2 alpha r / 10).
double documentedStrength(double r, double cos_theta, double n, std::size_t rays)
{
  return std::pow(cos_theta, n) / (r * r) * std::pow(10.0, -2.0 * 0.1 * r / 10.0) / static_cast<double>(rays);
}

TEST(Msis, OneRayOnAPlateTiltedByAKnownAngleFollowsTheCosineLaw)
{
  // A single ray along the head's +x (hpr = vpr = 1, head angle 0) meets a plate 1.5 m ahead turned by `tilt`
  // about z: incidence = tilt, so the line is one bin of cos(tilt)^n (1 / r)^2 10^(-0.02 r) (gain 0, A = 1).
  // With n + 1 instead of n the 60 deg echo halves; the tolerance is 1e-4 relative.
  const double R = 1.5;
  for (double n : {2.0, 1.3}) {
    for (double tilt_deg : {0.0, 35.0, 60.0}) {
      const double tilt = tilt_deg * kDeg;
      const Eigen::Vector3d normal = tiltedNormal(tilt);
      const Eigen::Vector3d centre = kRobot + kHead + Eigen::Vector3d(R, 0, 0);
      SonarWorld w(meshWorld({{"tilted_plate", plate(centre, normal, 1.5)}}, kRobot),
                   msisUrdf(clean({{"gain", "0"}, {"hpr", "1"}, {"vpr", "1"}, {"sector_left", "0"},
                                   {"backscatter_exponent", num(n)}})));
      auto& msis = w.sensor<MsisSensor>("msis");
      w.samples(msis, 1);
      ASSERT_EQ(msis.last().angle, 0.0);
      // The ray from the head at the ping (the robot hardly moves in the one step before it).
      const Eigen::Isometry3d& pose = w.robot().state().pose;
      const Eigen::Vector3d o = pose * kHead, d = pose.linear() * Eigen::Vector3d::UnitX();
      const double r = (centre - o).dot(normal) / d.dot(normal), cos_theta = std::abs(d.dot(normal));
      ASSERT_NEAR(r, R, 1e-3);
      ASSERT_NEAR(cos_theta, std::cos(tilt), 1e-4);
      const double expected = documentedStrength(r, cos_theta, n, 1);
      const int bin = static_cast<int>(std::floor((r - 0.3) / ((3.0 - 0.3) / 400)));  // range_min 0.3, 3 m, 400 bins
      const auto& line = msis.last().intensity;
      ASSERT_EQ(argmax(line), static_cast<std::size_t>(bin)) << "n " << n << " tilt " << tilt_deg;
      EXPECT_NEAR(line[bin], expected, 1e-4 * expected) << "n " << n << " tilt " << tilt_deg << " deg";
      EXPECT_EQ(std::accumulate(line.begin(), line.end(), 0.0), line[bin]);  // nothing elsewhere
    }
  }
}

TEST(Msis, TheWholeFanOnATiltedPlateSumsTheDocumentedEchoOfEveryRay)
{
  // The default fan (5 x 70 rays over 3 x 35 deg) on a plate 1.2 m ahead turned 50 deg about z: every ray has
  // its own range and incidence. The line's sum is the sum over the rays of w cos(theta)^2 L(r), each ray's
  // direction from the documented fan (msis_sensor.h) and its r, theta from the plane, computed here.
  const double R = 1.2, tilt = 50 * kDeg;
  const Eigen::Vector3d normal = tiltedNormal(tilt), centre = kRobot + kHead + Eigen::Vector3d(R, 0, 0);
  SonarWorld w(meshWorld({{"tilted_plate", plate(centre, normal, 2.0)}}, kRobot),
               msisUrdf(clean({{"gain", "0"}, {"sector_left", "0"}})));
  auto& msis = w.sensor<MsisSensor>("msis");
  w.samples(msis, 1);
  ASSERT_EQ(msis.last().angle, 0.0);
  const Eigen::Isometry3d& pose = w.robot().state().pose;
  const Eigen::Vector3d o = pose * kHead;
  const int hpr = 5, vpr = 70;
  const double bw_h = 3 * kDeg, bw_v = 35 * kDeg;
  double expected = 0.0, head_on = 0.0;
  for (int i = 0; i < hpr; ++i) {
    for (int j = 0; j < vpr; ++j) {
      const double h = -bw_h / 2 + (i + 0.5) * bw_h / hpr, v = -bw_v / 2 + (j + 0.5) * bw_v / vpr;
      const Eigen::Vector3d d = pose.linear() * Eigen::Vector3d(std::cos(v) * std::cos(h), std::cos(v) * std::sin(h), std::sin(v));
      const double r = (centre - o).dot(normal) / d.dot(normal);
      ASSERT_GT(r, 0.3);
      ASSERT_LT(r, 3.0);
      expected += documentedStrength(r, std::abs(d.dot(normal)), 2.0, hpr * vpr);
      head_on += documentedStrength(r, 1.0, 2.0, hpr * vpr);
    }
  }
  ASSERT_LT(expected, 0.7 * head_on);  // the incidence matters (cos^2 50 deg = 0.41)
  const auto& line = msis.last().intensity;
  EXPECT_NEAR(std::accumulate(line.begin(), line.end(), 0.0), expected, 1e-3 * expected);
}

TEST(Msis, SectorScanTurnsBackAtTheLimits)
{
  const double left = -10 * kDeg, right = 7 * kDeg, step = 3.6 * kDeg;
  SonarWorld w(sphereWorld(2.0), msisUrdf(clean({{"continuous", "false"}, {"sector_left", num(left)},
                                                  {"sector_right", num(right)}, {"step", num(step)}})));
  auto& msis = w.sensor<MsisSensor>("msis");
  // Steps of 3.6 deg; the last step before a limit stops at it, then the head turns back.
  const std::vector<double> deg = {-10, -6.4, -2.8, 0.8, 4.4, 7, 3.4, -0.2, -3.8, -7.4, -10, -6.4};
  for (double d : deg) {
    w.samples(msis, 1);
    EXPECT_NEAR(msis.last().angle, d * kDeg, 1e-9);
  }
}

TEST(Msis, BoxWallsAtEveryHeadAngle)
{
  // test_box.world: a closed 4 m cube centred on the origin (walls at +-2 m); the robot at the centre.
  const sim::WorldConfig box = sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/test_box.world");
  SonarWorld w(box, sensorUrdf(SphereSpec(), msisLinks(), sensorXml("msis", "msis", "T/msis_head_link", 25.0, clean())));
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
        if (std::abs(d[a]) > 1e-12) nearest = std::min(nearest, ((d[a] > 0 ? 2.0 : -2.0) - p[a]) / d[a]);
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

TEST(Msis, GaussianRangeNoiseSpreadsTheEchoWithItsStandardDeviation)
{
  const double R = 2.0, sigma = 0.05;
  SonarWorld w(sphereWorld(R), msisUrdf(clean({{"noise", "gaussian"}, {"gain", "0"}, {"range_noise", num(sigma)}})));
  auto& msis = w.sensor<MsisSensor>("msis");
  const auto& echo = msis.echo();
  double s0 = 0, s1 = 0, s2 = 0;
  for (int k = 0; k < 50; ++k) {
    w.samples(msis, 1);
    const auto& v = msis.last().intensity;
    for (std::size_t b = 0; b < v.size(); ++b) {
      // Undo the strength's 1/r^2 so every ray weighs the same.
      const double r = echo.binCenter(b), weight = v[b] / echo.loss(r);
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

TEST(Msis, SaltAndPepperReplacesTheGivenShareOfBins)
{
  const double R = 2.0, p = 0.1;
  SonarWorld w(sphereWorld(R), msisUrdf(clean({{"noise", "gaussian"}, {"salt_pepper", num(p)}})));
  auto& msis = w.sensor<MsisSensor>("msis");
  const int peak = msis.echo().bin(R);
  std::size_t empty = 0, salted = 0, lines = 200, peppered = 0;
  for (std::size_t k = 0; k < lines; ++k) {
    w.samples(msis, 1);
    const auto& v = msis.last().intensity;
    for (int b = 0; b < static_cast<int>(v.size()); ++b) {
      if (std::abs(b - peak) <= 1) continue;
      ++empty;                   // without noise: 0
      salted += v[b] > 0.0f;     // a salt draw (uniform intensity, > 0 almost surely)
    }
    peppered += v[peak] == 0.0f;  // the echo bin was pepper
  }
  // Salt: p/2 of the bins; binomial, 4 sigma.
  const double n_salt = empty * p / 2.0;
  EXPECT_NEAR(salted, n_salt, 4.0 * std::sqrt(n_salt * (1 - p / 2)));
  const double n_pepper = lines * p / 2.0;
  EXPECT_NEAR(peppered, n_pepper, 4.0 * std::sqrt(n_pepper * (1 - p / 2)));
}

TEST(Msis, AcousticShadowSilencesEverythingBehindAStrongEcho)
{
  // A plate 1 m ahead of the head (+x at head angle 0) covering the upper half of the fan; the lower half
  // reaches the sphere at 2 m.
  const Eigen::Vector3d h = kRobot + kHead;
  const auto world = sphereWorld(2.0, {{"plate", box(h + Eigen::Vector3d(1.0, -0.5, 0.0), h + Eigen::Vector3d(1.02, 0.5, 0.6))}});
  const auto params = [](const std::string& shadow) {
    return clean({{"noise", "gaussian"}, {"shadow", shadow}, {"sector_left", "0"}, {"shadow_threshold", "0.6"}});
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
  const int strong = static_cast<int>(std::find_if(b.last().intensity.begin(), b.last().intensity.end(),
                                                   [](float i) { return i >= 0.6f; }) - b.last().intensity.begin());
  EXPECT_LE(std::abs(strong - plate), 1);
  for (int i = 0; i <= strong; ++i) EXPECT_EQ(a.last().intensity[i], b.last().intensity[i]) << i;
  for (int i = strong + 1; i < 400; ++i) {
    EXPECT_EQ(b.last().intensity[i], 0.0f) << i;
    EXPECT_EQ(b.last().level[i], EchoLevel::shadow) << i;
  }
}

TEST(Msis, GroundArtifactsFillTheGapsBetweenSparseRaysAndKeepTheEnergy)
{
  // Head pitched 60 deg down over a floor 1.5 m below it, 8 rays across 35 deg: hits centimetres apart.
  const std::string links = msisLinks(Eigen::Vector3d(0, 0, 0.3), Eigen::Vector3d(0, 60 * kDeg, 0));
  const auto world = meshWorld({{"floor", box(kRobot + Eigen::Vector3d(-10, -10, -1.2), kRobot + Eigen::Vector3d(10, 10, -1.14))}}, kRobot);
  const auto params = [](const std::string& artifacts) {
    return clean({{"noise", "gaussian"}, {"artifacts", artifacts}, {"gain", "0"}, {"hpr", "1"}, {"vpr", "8"},
                  {"sector_left", "0"}, {"artifacts_gap", "0.5"}});
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
      if (v[i] > 0.0f) last = i, first = first < 0 ? i : first;
    for (int i = first; i <= last; ++i) zero += v[i] == 0.0f;
    return std::make_pair(last - first, zero);
  };
  const auto [span_off, zero_off] = gaps(a.last().intensity);
  const auto [span_on, zero_on] = gaps(b.last().intensity);
  EXPECT_GT(span_off, 40);                    // the floor echoes spread over tens of bins...
  EXPECT_GT(zero_off, span_off / 2);          // ...as isolated spikes with gaps between them
  EXPECT_EQ(zero_on, 0);                      // filled
  EXPECT_LE(std::abs(span_on - span_off), 1);  // between the same first and last hits
  const double sum_off = std::accumulate(a.last().intensity.begin(), a.last().intensity.end(), 0.0);
  const double sum_on = std::accumulate(b.last().intensity.begin(), b.last().intensity.end(), 0.0);
  EXPECT_NEAR(sum_on, sum_off, 1e-4 * sum_off);  // moved, not made
}

TEST(Msis, SameSeedSameScansOtherSeedOtherScansNoiseNoneIsClean)
{
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

TEST(Msis, FullSweepInTheTankTracesTheWallsAndSeesTheAnchor)
{
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
    if (to_anchor < 30 * kDeg) continue;  // the anchor's edges
    double nearest = INFINITY;  // walls and floor over the fan's rays
    for (const auto& d0 : msis.fan()) {
      const Eigen::Vector3d d = head.linear() * d0;
      const double lim[3][2] = {{-3, 3}, {-2, 2}, {-3, 1e9}};
      for (int a = 0; a < 3; ++a)
        if (std::abs(d[a]) > 1e-12) nearest = std::min(nearest, ((d[a] > 0 ? lim[a][1] : lim[a][0]) - p[a]) / d[a]);
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

TEST(Msis, BadParametersNameTheSensorAndTheParameter)
{
  const auto expectError = [](const std::map<std::string, std::string>& p, const std::string& what, double rate = 25.0) {
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
  expectError(clean({{"beam_with_h", "0.1"}}), "beam_with_h");
  expectError(clean({{"joint", "T/t0_joint"}}), "joint");
  expectError(clean(), "rate", 300.0);  // 1500 / (2 x 3 m) = 250 pings/s at most
}

}  // namespace
}  // namespace test
}  // namespace unexmin

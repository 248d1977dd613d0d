// M3 multibeam model (cpp/sonar/m3_sensor.h) in the 4 m test box (worlds/test_box.world, walls at +-2 m):
// every beam's range against the analytic distance to the walls (+-1 cm), the REP-117 markers beyond
// range_max and inside range_min, Gaussian range noise, seeds, the 40 Hz schedule and start-up errors.
#include <unexmin/sensors/sonar/m3_sensor.h>
#include "sonar_fixture.h"

#include <gtest/gtest.h>

#include <cmath>

namespace unexmin {
namespace test {
namespace {

using sonar::M3Sensor;

constexpr double kDeg = M_PI / 180.0;
const Eigen::Vector3d kMount(0.3, 0.0, -0.05);           // [m] M3 link in the base frame
const Eigen::Vector3d kMountRpy(0.0, 0.0, 20.0 * kDeg);  // [rad] fan turned 20 deg to the left

std::string m3Urdf(std::map<std::string, std::string> params, double rate = 40.0)
{
  params.emplace("noise", "none");
  return sensorUrdf(SphereSpec(), mountLink("T/m3_link", kMount, kMountRpy), sensorXml("m3", "m3", "T/m3_link", rate, params));
}

sim::WorldConfig testBox() { return sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/test_box.world"); }

/// First-return distance of beam k: the nearest wall (+-2 m) over the beam's rays.
double analytic(const M3Sensor& m3, const Eigen::Isometry3d& sonar, std::size_t k)
{
  double nearest = INFINITY;
  for (int j = 0; j < m3.raysPerBeam(); ++j) {
    const Eigen::Vector3d d = sonar.linear() * m3.rayDirection(k, j), p = sonar.translation();
    for (int a = 0; a < 3; ++a)
      if (std::abs(d[a]) > 1e-12) nearest = std::min(nearest, ((d[a] > 0 ? 2.0 : -2.0) - p[a]) / d[a]);
  }
  return nearest;
}

Eigen::Isometry3d sonarPose(SonarWorld& w) { return w.robot().state().pose * sim::poseFromXyzRpy(kMount, kMountRpy); }

TEST(M3, EveryBeamMeasuresTheAnalyticDistanceToTheBoxWalls)
{
  SonarWorld w(testBox(), m3Urdf({}));
  auto& m3 = w.sensor<M3Sensor>("m3");
  const Eigen::Isometry3d pose = sim::poseFromXyzRpy(Eigen::Vector3d(-0.4, 0.3, 0.2), Eigen::Vector3d(0.1, -0.15, 0.3));
  w.place(pose);
  w.samples(m3, 1);
  ASSERT_EQ(m3.last().ranges.size(), 256u);
  EXPECT_NEAR(m3.angleIncrement(), 120.0 * kDeg / 255, 1e-12);
  const Eigen::Isometry3d sonar = sonarPose(w);
  for (std::size_t k = 0; k < 256; ++k) {
    const double expected = analytic(m3, sonar, k);
    ASSERT_LT(expected, 150.0);
    EXPECT_NEAR(m3.last().ranges[k], expected, 0.01) << "beam " << k;
    // Quantised to the 1 cm resolution.
    EXPECT_NEAR(m3.last().ranges[k] / 0.01, std::round(m3.last().ranges[k] / 0.01), 1e-3) << "beam " << k;
    EXPECT_GT(m3.last().intensities[k], 0.0f);
  }
}

TEST(M3, BeamsBeyondRangeMaxReportNoReturnAndInsideRangeMinTooClose)
{
  const double range_min = 1.9, range_max = 2.4;
  SonarWorld w(testBox(), m3Urdf({{"range_min", num(range_min)}, {"range_max", num(range_max)}}));
  auto& m3 = w.sensor<M3Sensor>("m3");
  w.samples(m3, 1);
  const Eigen::Isometry3d sonar = sonarPose(w);
  int inf = 0, too_close = 0, ranged = 0;
  for (std::size_t k = 0; k < 256; ++k) {
    const double expected = analytic(m3, sonar, k);
    const float r = m3.last().ranges[k];
    if (expected > range_max + 0.01) {
      EXPECT_TRUE(std::isinf(r) && r > 0) << "beam " << k << ": " << r;  // REP-117: +inf, no return
      EXPECT_EQ(m3.last().intensities[k], 0.0f);
      ++inf;
    } else if (expected < range_min - 0.01) {
      EXPECT_TRUE(std::isinf(r) && r < 0) << "beam " << k << ": " << r;  // REP-117: -inf, too close
      ++too_close;
    } else if (expected > range_min + 0.01 && expected < range_max - 0.01) {
      EXPECT_NEAR(r, expected, 0.01) << "beam " << k;
      ++ranged;
    }
  }
  EXPECT_GT(inf, 10);
  EXPECT_GT(too_close, 10);
  EXPECT_GT(ranged, 10);
}

TEST(M3, GaussianRangeNoiseHasItsStandardDeviationAndRepeatsWithTheSeed)
{
  const double sigma = 0.05;
  const auto residuals = [&](std::uint64_t seed, const std::string& noise) {
    SonarWorld w(testBox(), m3Urdf({{"noise", noise}, {"range_noise", num(sigma)}}), seed);
    auto& m3 = w.sensor<M3Sensor>("m3");
    std::vector<double> out;
    for (int ping = 0; ping < 20; ++ping) {
      w.samples(m3, 1);
      const Eigen::Isometry3d sonar = sonarPose(w);
      for (std::size_t k = 0; k < 256; ++k) out.push_back(m3.last().ranges[k] - analytic(m3, sonar, k));
    }
    return out;
  };
  const auto a = residuals(3, "gaussian");
  double s1 = 0, s2 = 0;
  for (double r : a) s1 += r, s2 += r * r;
  const double n = static_cast<double>(a.size()), mean = s1 / n, sd = std::sqrt(s2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 4.0 * sigma / std::sqrt(n));
  // sqrt(sigma^2 + res^2 / 12) with the 1 cm rounding; 5120 samples: +-1 % (1 sigma).
  EXPECT_NEAR(sd, std::sqrt(sigma * sigma + 0.01 * 0.01 / 12), 0.05 * sigma);
  EXPECT_EQ(a, residuals(3, "gaussian"));
  EXPECT_NE(a, residuals(4, "gaussian"));
  for (double r : residuals(3, "none")) ASSERT_LE(std::abs(r), 0.01);  // noise = none: clean
}

TEST(M3, PingsAtFortyHertzOfSimulationTime)
{
  SonarWorld w(testBox(), m3Urdf({}));
  auto& m3 = w.sensor<M3Sensor>("m3");
  for (int k = 1; k <= 80; ++k) {
    w.samples(m3, 1);
    EXPECT_GE(m3.last().time, k / 40.0 - 1e-9);
    EXPECT_LT(m3.last().time, k / 40.0 + 0.002 - 1e-9);
  }
  EXPECT_NEAR(w.world->time(), 2.0, 1e-9);
}

TEST(M3, BadParametersNameTheSensorAndTheParameter)
{
  for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
           {"beams", "0"}, {"beams", "2.5"}, {"range_max", "0.1"}, {"fov_h", "7"}, {"range_resolution", "0"},
           {"rays_per_beam", "0"}, {"noise", "white"}, {"ranges_max", "3"}}) {
    try {
      SonarWorld w(testBox(), m3Urdf({{key, value}}));
      ADD_FAILURE() << "no error for " << key << " = " << value;
    } catch (const ConfigError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("sensor 'm3'"), std::string::npos) << m;
      EXPECT_NE(m.find("'" + key + "'"), std::string::npos) << m;
    }
  }
}

}  // namespace
}  // namespace test
}  // namespace unexmin

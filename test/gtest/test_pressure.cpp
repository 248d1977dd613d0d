// Pressure model (cpp/unexmin/sensors/pressure_sensor.h): atmospheric + rho g depth at the sensor link,
// within the configured noise; atmospheric above the surface; full-scale clamp; start-up errors.
#include <unexmin/sensors/pressure_sensor.h>
#include "sensor_fixture.h"

#include <gtest/gtest.h>

#include <cmath>

namespace unexmin {
namespace test {
namespace {

std::string pressureUrdf(const SphereSpec& s, const Eigen::Vector3d& xyz, double rate,
                         const std::map<std::string, std::string>& params) {
  return sensorUrdf(s, mountLink("T/pressure_link", xyz, Eigen::Vector3d::Zero()),
                    sensorXml("pressure", "pressure", "T/pressure_link", rate, params));
}

TEST(Pressure, ReadsAtmosphericPlusRhoGDepthWithinNoise) {
  SphereSpec s;
  s.rho = 1025.0;  // sea water: the sensor must use the world's density
  s.mass = s.rho * s.volume();
  sim::WorldConfig config = openWater(s, Eigen::Vector3d(0, 0, -37.0));
  config.gravity = 9.80665;
  config.atmospheric_pressure = 100500.0;
  config.surface_z = 2.0;  // the free surface is not at z = 0
  const Eigen::Vector3d mount(0.1, 0.0, -0.2);
  const double sigma = 100.0;  // [Pa]
  SensorWorld w(config, pressureUrdf(s, mount, 10.0, {{"pressure_noise", num(sigma)}}), 4);
  auto& p = w.sensor<sensors::PressureSensor>("pressure");
  const double depth = 2.0 - (-37.0 + mount.z());
  const double expected = 100500.0 + 1025.0 * 9.80665 * depth;
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  for (int i = 0; i < 50000; ++i) {  // 100 s: 1000 samples at 10 Hz
    w.step();
    if (!w.suite->fresh(0))
      continue;
    EXPECT_NEAR(p.last().pressure, expected, 5.0 * sigma);
    sum += p.last().pressure;
    sum2 += p.last().pressure * p.last().pressure;
    ++n;
  }
  ASSERT_EQ(n, 1000);
  const double mean = sum / n;
  EXPECT_NEAR(mean, expected, 3.0 * sigma / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(sum2 / n - mean * mean), sigma, 0.1 * sigma);
  EXPECT_DOUBLE_EQ(p.last().variance, sigma * sigma);
  // The hull did not move: the expectation is the pose the test set.
  EXPECT_NEAR(w.robot().state().pose.translation().z(), -37.0, 1e-6);
}

TEST(Pressure, AboveTheSurfaceReadsAtmospheric) {
  const SphereSpec s;
  SensorWorld w(openWater(s, Eigen::Vector3d(0, 0, 3.0)),
                pressureUrdf(s, Eigen::Vector3d::Zero(), 500.0, {{"noise", "none"}}));
  w.step();
  EXPECT_DOUBLE_EQ(w.sensor<sensors::PressureSensor>("pressure").last().pressure, 101325.0);
}

TEST(Pressure, ClampsToFullScale) {
  const SphereSpec s;
  SensorWorld w(openWater(s, Eigen::Vector3d(0, 0, -100.0)),
                pressureUrdf(s, Eigen::Vector3d::Zero(), 500.0, {{"noise", "none"}, {"pressure_range", "5e5"}}));
  w.step();
  EXPECT_DOUBLE_EQ(w.sensor<sensors::PressureSensor>("pressure").last().pressure, 5e5);  // true: 1.08e6 Pa
}

TEST(Pressure, MalformedParametersStopStartUpNamingSensorAndParameter) {
  const SphereSpec s;
  try {
    SensorWorld w(openWater(s), pressureUrdf(s, Eigen::Vector3d::Zero(), 10.0, {{"pressure_noise", "-3"}}));
    FAIL() << "a negative noise was accepted";
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("sensor 'pressure'"), std::string::npos) << m;
    EXPECT_NE(m.find("'pressure_noise' = -3"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace test
}  // namespace unexmin

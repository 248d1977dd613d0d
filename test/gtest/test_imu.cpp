// IMU model (cpp/unexmin/sensors/imu_sensor.h) against closed-form answers: gravity at rest, a known yaw
// rate, lever-arm accelerations under a known torque, the world's magnetic field, the Allan deviation
// of the configured white noise, seeded repeatability and start-up errors.
#include <unexmin/sensors/imu_sensor.h>
#include "sensor_fixture.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

namespace unexmin {
namespace test {
namespace {

constexpr double kRate = 500.0;  // [Hz] = the physics rate of the tests (dt = 2 ms)

// KVH 1775 class figures, written here (not read from the xacro) so the test owns its inputs.
constexpr double kGyroDensity = 3.49e-6;   // [rad/s/sqrt(Hz)] 0.012 deg/sqrt(h)
constexpr double kGyroWalk = 7.7e-9;       // [rad/s/sqrt(s)]
constexpr double kGyroTurnOn = 9.7e-6;     // [rad/s] 2 deg/h
constexpr double kAccelDensity = 1.18e-3;  // [m/s^2/sqrt(Hz)] 0.12 mg/sqrt(Hz)
constexpr double kAccelWalk = 1.55e-5;     // [m/s^2/sqrt(s)]
constexpr double kAccelTurnOn = 9.8e-3;    // [m/s^2] 1 mg
constexpr double kMagDensity = 0.12;       // [mG/sqrt(Hz)]

std::map<std::string, std::string> noisyParams() {
  return {{"noise", "gaussian"},
          {"gyro_noise_density", num(kGyroDensity)},
          {"gyro_bias_random_walk", num(kGyroWalk)},
          {"gyro_turn_on_bias", num(kGyroTurnOn)},
          {"accel_noise_density", num(kAccelDensity)},
          {"accel_bias_random_walk", num(kAccelWalk)},
          {"accel_turn_on_bias", num(kAccelTurnOn)},
          {"mag_noise_density", num(kMagDensity)},
          {"temperature", "30"},
          {"temperature_noise", "0.1"}};
}

std::string imuUrdf(const SphereSpec& s, const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy,
                    const std::map<std::string, std::string>& params, double rate = kRate) {
  return sensorUrdf(s, mountLink("T/imu_link", xyz, rpy), sensorXml("imu", "imu", "T/imu_link", rate, params));
}

/// 1 sigma of the mean of n samples of one axis: white part over sqrt(n), turn-on bias, and the
/// bias random walk accumulated over the record (T = n / rate) [unit of the axis].
double meanSigma(double density, double walk, double turn_on, int n) {
  const double white = density * std::sqrt(kRate);
  return std::sqrt(white * white / n + turn_on * turn_on + walk * walk * n / kRate);
}

TEST(Imu, AtRestMeasuresGravityUpInItsOwnFrameWithinThreeSigma) {
  const SphereSpec s;
  const Eigen::Vector3d rpy(0.3, -0.2, 1.0);  // a tilted mount: gravity must come out in the IMU frame
  SensorWorld w(openWater(s), imuUrdf(s, Eigen::Vector3d(0.1, 0.05, -0.1), rpy, noisyParams()), 7);
  auto& imu = w.sensor<sensors::ImuSensor>("imu");
  const int n = 2000;
  Eigen::Vector3d f_sum = Eigen::Vector3d::Zero(), w_sum = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    w.step();
    ASSERT_DOUBLE_EQ(imu.sampleTime(), w.world->time());  // a sample every step at 500 Hz
    f_sum += imu.last().specific_force;
    w_sum += imu.last().angular_velocity;
  }
  // The hull stays level and at rest (neutral, CG below CB).
  EXPECT_LT(w.robot().state().linear_velocity.norm(), 1e-9);
  const Eigen::Matrix3d R_mount = sim::poseFromXyzRpy(Eigen::Vector3d::Zero(), rpy).linear();
  const double g = openWater(s).gravity;  // [m/s^2]
  const Eigen::Vector3d expected_f = R_mount.transpose() * Eigen::Vector3d(0, 0, g);
  const double f_tol = 3.0 * meanSigma(kAccelDensity, kAccelWalk, kAccelTurnOn, n);
  const double w_tol = 3.0 * meanSigma(kGyroDensity, kGyroWalk, kGyroTurnOn, n);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(f_sum[a] / n, expected_f[a], f_tol) << "axis " << a;
    EXPECT_NEAR(w_sum[a] / n, 0.0, w_tol) << "axis " << a;
  }
  // The reported covariance is the per-sample white noise.
  EXPECT_NEAR(imu.last().accel_variance, kAccelDensity * kAccelDensity * kRate, 1e-12);
  EXPECT_NEAR(imu.last().temperature, 30.0, 0.5);
}

TEST(Imu, YawingRobotReadsItsRateAndTheCentripetalLeverArm) {
  const SphereSpec s = undampedSphere();
  const Eigen::Vector3d r(0.25, 0.0, 0.0);  // [m] IMU ahead of the centre
  SensorWorld w(openWater(s), imuUrdf(s, r, Eigen::Vector3d::Zero(), {{"noise", "none"}}));
  const double rate = 0.4;  // [rad/s]
  w.place(w.robot().state().pose, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, rate));
  auto& imu = w.sensor<sensors::ImuSensor>("imu");
  for (int i = 0; i < 250; ++i)
    w.step();
  // Rotating frame: the IMU point circles the centre, specific force -w^2 r (towards the centre) + g up.
  // Bullet integrates in single precision: relative 1e-5 is its resolution here.
  EXPECT_NEAR(imu.last().angular_velocity.z(), rate, 1e-5 * rate);
  EXPECT_NEAR(imu.last().angular_velocity.head<2>().norm(), 0.0, 1e-6);
  EXPECT_NEAR(imu.last().specific_force.x(), -rate * rate * r.x(), 1e-6);
  EXPECT_NEAR(imu.last().specific_force.y(), 0.0, 1e-6);
  EXPECT_NEAR(imu.last().specific_force.z(), 9.81, 1e-6);
}

TEST(Imu, YawRateWithNoiseWithinThreeSigma) {
  const SphereSpec s = undampedSphere();
  SensorWorld w(openWater(s), imuUrdf(s, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), noisyParams()), 3);
  const double rate = -0.25;  // [rad/s]
  w.place(w.robot().state().pose, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, rate));
  auto& imu = w.sensor<sensors::ImuSensor>("imu");
  const int n = 1000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    w.step();
    sum += imu.last().angular_velocity.z();
  }
  EXPECT_NEAR(sum / n, rate, 3.0 * meanSigma(kGyroDensity, kGyroWalk, kGyroTurnOn, n));
  // A single sample too, against its own 1 sigma (white + biases).
  const double one = std::hypot(kGyroDensity * std::sqrt(kRate), kGyroTurnOn);
  EXPECT_NEAR(imu.last().angular_velocity.z(), rate, 3.0 * std::hypot(one, kGyroWalk * std::sqrt(n / kRate)));
}

TEST(Imu, TorqueGivesTangentialAndCentripetalSpecificForce) {
  const SphereSpec s = undampedSphere();
  const Eigen::Vector3d r(0.2, 0.0, 0.0);
  SensorWorld w(openWater(s), imuUrdf(s, r, Eigen::Vector3d::Zero(), {{"noise", "none"}}));
  auto& imu = w.sensor<sensors::ImuSensor>("imu");
  const double torque = 2.0;                  // [N m] about z
  const double alpha = torque / s.inertia();  // [rad/s^2]: no rotational added mass on a sphere
  const int n = 300;
  for (int i = 0; i < n; ++i) {
    w.robot().body()->applyTorque(btVector3(0, 0, torque));
    w.step();
  }
  const double omega = alpha * n * w.world->dt();
  EXPECT_NEAR(imu.last().angular_velocity.z(), omega, 1e-5 * omega);                // single-precision engine
  EXPECT_NEAR(imu.last().specific_force.y(), alpha * r.x(), 1e-4 * alpha * r.x());  // alpha x r
  EXPECT_NEAR(imu.last().specific_force.x(), -omega * omega * r.x(), 1e-3 * omega * omega * r.x());  // w x (w x r)
  EXPECT_NEAR(imu.last().specific_force.z(), 9.81, 1e-9);
}

TEST(Imu, MagnetometerReadsTheWorldFieldInTheImuFrame) {
  const SphereSpec s;
  sim::WorldConfig config = openWater(s);
  config.magnetic_field = Eigen::Vector3d(150.0, -40.0, -480.0);  // [mG]
  SensorWorld w(config, imuUrdf(s, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), {{"noise", "none"}}));
  const double yaw = 1.1;
  w.place(sim::poseFromXyzRpy(Eigen::Vector3d(0, 0, -100), Eigen::Vector3d(0, 0, yaw)));
  w.step();
  const Eigen::Vector3d expected = Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()) * config.magnetic_field;
  // Single-precision attitude: 1e-3 mG of 500 mG.
  EXPECT_LT((w.sensor<sensors::ImuSensor>("imu").last().magnetic_field - expected).norm(), 1e-3);
}

TEST(Imu, MagneticFieldComesFromTheWorldFile) {
  // A copy of the test box world with a field of its own, written by the test beside a copy of its mesh (a world
  // file names its meshes inside its own folder).
  const std::string path = testTempDir() + "magnetic.world";
  std::filesystem::copy_file(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/meshes/test_box.stl",
                             testTempDir() + "magnetic_box.stl", std::filesystem::copy_options::overwrite_existing);
  auto write = [&](const std::string& field) {
    std::ofstream out(path);
    out << "name: magnetic\n"
        << field << "meshes:\n  - {name: box, file: magnetic_box.stl}\nrobots:\n  - {name: UX_1, xyz: [0, 0, 0]}\n";
  };
  write("magnetic_field: [100.0, 200.0, -400.0]\n");
  const sim::WorldConfig config = sim::loadWorldConfig(path);
  EXPECT_EQ(config.magnetic_field, Eigen::Vector3d(100.0, 200.0, -400.0));
  const SphereSpec s;
  SensorWorld w(config, imuUrdf(s, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), {{"noise", "none"}}));
  w.step();
  EXPECT_LT((w.sensor<sensors::ImuSensor>("imu").last().magnetic_field - config.magnetic_field).norm(), 1e-3);

  write("magnetic_field: [100.0, 200.0]\n");
  try {
    sim::loadWorldConfig(path);
    FAIL() << "a 2-vector field was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("'magnetic_field' must be a list of 3 numbers"), std::string::npos)
        << e.what();
  }
  write("");
  EXPECT_EQ(sim::loadWorldConfig(path).magnetic_field, sim::WorldConfig().magnetic_field);  // optional
}

TEST(Imu, PressureAtTheImuOriginIsHydrostatic) {
  const SphereSpec s;
  const Eigen::Vector3d r(0.0, 0.0, -0.15);
  SensorWorld w(openWater(s, Eigen::Vector3d(0, 0, -20)), imuUrdf(s, r, Eigen::Vector3d::Zero(), {{"noise", "none"}}));
  w.step();
  const double depth = 20.0 + 0.15;
  EXPECT_NEAR(w.sensor<sensors::ImuSensor>("imu").last().pressure, 101325.0 + s.rho * 9.81 * depth, 1e-3);
}

/// Overlapping Allan deviation at cluster time m / rate of a record of rate samples [unit].
double allanDeviation(const std::vector<double>& y, std::size_t m, double rate) {
  std::vector<double> theta(y.size() + 1, 0.0);  // integral of y [unit s]
  for (std::size_t i = 0; i < y.size(); ++i)
    theta[i + 1] = theta[i] + y[i] / rate;
  const double tau = static_cast<double>(m) / rate;
  double sum = 0.0;
  const std::size_t n = theta.size();
  for (std::size_t k = 0; k + 2 * m < n; ++k) {
    const double d = theta[k + 2 * m] - 2.0 * theta[k + m] + theta[k];
    sum += d * d;
  }
  return std::sqrt(sum / (2.0 * tau * tau * static_cast<double>(n - 2 * m)));
}

TEST(Imu, AllanDeviationAtOneSecondMatchesTheConfiguredWhiteNoise) {
  const SphereSpec s;
  SensorWorld w(openWater(s), imuUrdf(s, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), noisyParams()), 11);
  auto& imu = w.sensor<sensors::ImuSensor>("imu");
  const std::size_t n = 400 * static_cast<std::size_t>(kRate);  // 400 s of record
  std::vector<double> gyro_x(n), accel_z(n);
  for (std::size_t i = 0; i < n; ++i) {
    w.step();
    gyro_x[i] = imu.last().angular_velocity.x();
    accel_z[i] = imu.last().specific_force.z();
  }
  const auto m = static_cast<std::size_t>(kRate);  // tau = 1 s
  // sigma(tau)^2 = N^2 / tau + K^2 tau / 3 (white noise + rate random walk), tau = 1 s.
  const double gyro_expected = std::sqrt(kGyroDensity * kGyroDensity + kGyroWalk * kGyroWalk / 3.0);
  const double accel_expected = std::sqrt(kAccelDensity * kAccelDensity + kAccelWalk * kAccelWalk / 3.0);
  EXPECT_NEAR(allanDeviation(gyro_x, m, kRate), gyro_expected, 0.10 * gyro_expected);
  EXPECT_NEAR(allanDeviation(accel_z, m, kRate), accel_expected, 0.10 * accel_expected);
}

TEST(Imu, SameSeedRepeatsAndOtherSeedsOrNamesDiffer) {
  const SphereSpec s;
  const std::string urdf = imuUrdf(s, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), noisyParams());
  auto record = [&](std::uint64_t seed, const std::string& u) {
    SensorWorld w(openWater(s), u, seed);
    std::vector<double> out;
    for (int i = 0; i < 20; ++i) {
      w.step();
      out.push_back(w.sensor<sensors::ImuSensor>(w.suite->sensor(0).name()).last().specific_force.x());
    }
    // A reset with the same seed repeats the record from turn-on.
    w.world->reset(seed);
    w.suite->reset(seed);
    w.step();
    EXPECT_EQ(w.suite->sensor(0).sampleCount(), 1u);
    EXPECT_DOUBLE_EQ(dynamic_cast<sensors::ImuSensor&>(w.suite->sensor(0)).last().specific_force.x(), out[0]);
    return out;
  };
  const auto a = record(5, urdf);
  EXPECT_EQ(a, record(5, urdf));
  EXPECT_NE(a, record(6, urdf));
  std::string renamed = urdf;
  renamed.replace(renamed.find("name='imu'"), 10, "name='imu2'");
  EXPECT_NE(a, record(5, renamed));
}

/// The ConfigError message of building `urdf`'s sensors (empty when none is thrown).
std::string startupError(const std::string& urdf) {
  try {
    SensorWorld w(openWater(SphereSpec()), urdf);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(Imu, MalformedParametersStopStartUpNamingSensorAndParameter) {
  const SphereSpec s;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  std::string e = startupError(imuUrdf(s, zero, zero, {{"noise", "pink"}}));
  EXPECT_NE(e.find("sensor 'imu'"), std::string::npos) << e;
  EXPECT_NE(e.find("'noise'"), std::string::npos) << e;
  EXPECT_NE(e.find("gaussian|none"), std::string::npos) << e;

  e = startupError(imuUrdf(s, zero, zero, {{"gyro_noise_density", "-1e-6"}}));
  EXPECT_NE(e.find("sensor 'imu'"), std::string::npos) << e;
  EXPECT_NE(e.find("'gyro_noise_density'"), std::string::npos) << e;

  e = startupError(imuUrdf(s, zero, zero, {{"gyro_noise_densty", "1e-6"}}));  // a typo
  EXPECT_NE(e.find("unknown parameter 'gyro_noise_densty'"), std::string::npos) << e;

  e = startupError(imuUrdf(s, zero, zero, {}, 1000.0));  // faster than the 500 Hz physics
  EXPECT_NE(e.find("sensor 'imu'"), std::string::npos) << e;
  EXPECT_NE(e.find("rate"), std::string::npos) << e;

  // A negative rate is refused by the description parser, naming the sensor and the attribute.
  e = startupError(imuUrdf(s, zero, zero, {}, -500.0));
  EXPECT_NE(e.find("<sensor name='imu'>@rate"), std::string::npos) << e;
}

}  // namespace
}  // namespace test
}  // namespace unexmin

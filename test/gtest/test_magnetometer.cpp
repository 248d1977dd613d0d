// Fluxgate magnetometer (cpp/unexmin/sensors/science/magnetometer_sensor.h) and the robot's own field
// (<magnetic>, sim::RobotMagnetics) against closed forms computed here: the Earth's field rotated into the sensor
// frame, a sphere of ore beside the robot (its dipole), hard and soft iron and a thruster's current, the IMU reading
// the same total field in mG, the white noise, the resolution, the schedule, a world file's map form of the field, a
// hard-iron calibration by an ellipsoid fit over many attitudes, and every parameter error.
#include <unexmin/geo/magnetics.h>
#include <unexmin/sensors/science/magnetometer_sensor.h>
#include "sensor_fixture.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <Eigen/QR>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <vector>

namespace unexmin {
namespace test {
namespace {

using sensors::science::MagnetometerSensor;
constexpr double kPi = 3.14159265358979323846;

const Eigen::Vector3d kMount(0.1, -0.05, 0.2);  // [m] in the base link
const Eigen::Vector3d kMountRpy(0.3, -0.2, 1.0);

/// The test sphere with a magnetometer (and an IMU on the same link) and the <magnetic> element `magnetic`.
std::string magUrdf(const SphereSpec& s, const std::map<std::string, std::string>& params,
                    const std::string& magnetic = "", double rate = 50.0, const Eigen::Vector3d& rpy = kMountRpy) {
  return sensorUrdf(s, mountLink("T/mag_link", kMount, rpy),
                    sensorXml("magnetometer", "magnetometer", "T/mag_link", rate, params) +
                        sensorXml("imu", "imu", "T/mag_link", 500.0, {{"noise", "none"}}) + magnetic);
}

const std::map<std::string, std::string> kIdeal = {{"noise", "none"}, {"resolution", "0"}};

Eigen::Matrix3d rpyMatrix(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

TEST(Magnetometer, ReadsTheEarthFieldInTheSensorFrame) {
  const SphereSpec s;
  sim::WorldConfig config = openWater(s);
  config.magnetic_field = Eigen::Vector3d(150.0, -40.0, -480.0);  // [mG]
  SensorWorld w(config, magUrdf(s, kIdeal));
  auto& mag = w.sensor<MagnetometerSensor>("magnetometer");
  const Eigen::Vector3d rpy(0.4, -0.3, 1.1);
  w.place(sim::poseFromXyzRpy(Eigen::Vector3d(0, 0, -100), rpy));
  w.samples(mag, 1);
  const Eigen::Matrix3d R = w.robot().state().pose.linear();  // the attitude after the step (single precision)
  const Eigen::Vector3d expected = (R * rpyMatrix(kMountRpy)).transpose() * config.magnetic_field * 100.0;  // [nT]
  EXPECT_LT((mag.last().field - expected).norm(), 1e-6 * expected.norm());
  EXPECT_LT((R - rpyMatrix(rpy)).norm(), 5e-3);  // it is the attitude placed (it turns a little in 20 ms)
  // the IMU on the same link reads the same field in mG
  EXPECT_LT((w.sensor<sensors::ImuSensor>("imu").last().magnetic_field * 100.0 - mag.last().field).norm(), 1e-6);
  EXPECT_DOUBLE_EQ(mag.sampleTime(), 0.02);  // 50 Hz: the sample at k / rate
}

TEST(Magnetometer, ASphereOfOreBesideTheRobotAddsItsDipole) {
  const SphereSpec s;
  sim::WorldConfig config = openWater(s);                   // the robot at (0, 0, -100)
  const Eigen::Vector3d F = config.magnetic_field * 100.0;  // [nT]
  geo::Rock host, ore;
  ore.susceptibility = 0.2;
  geo::Body body;
  body.name = "magnetite";
  body.kind = geo::BodyKind::ellipsoid;
  body.pose.translation() = Eigen::Vector3d(0, 0, -101.5);  // 1.5 m below the robot's spawn at z = -100
  body.size = Eigen::Vector3d::Constant(0.8);
  body.rock = ore;
  config.geology = std::make_shared<geo::Geology>(host, std::vector<geo::Body>{body});
  SensorWorld w(config, magUrdf(s, kIdeal, "", 50.0, Eigen::Vector3d::Zero()));
  auto& mag = w.sensor<MagnetometerSensor>("magnetometer");
  w.place(sim::poseFromXyzRpy(Eigen::Vector3d(0, 0, -100), Eigen::Vector3d::Zero()));
  w.samples(mag, 1);
  const sim::RobotState& st = w.robot().state();
  const Eigen::Vector3d p = st.pose * kMount;  // the sensor's origin
  const double chi = 0.2, a = 0.8;
  const Eigen::Vector3d m = 4.0 / 3.0 * kPi * a * a * a * 3 * chi / (3 + chi) * F * 1e-9 / (4e-7 * kPi);
  const Eigen::Vector3d r = p - body.pose.translation();
  const Eigen::Vector3d u = r.normalized();
  const Eigen::Vector3d dipole = 1e-7 / std::pow(r.norm(), 3) * (3 * m.dot(u) * u - m) * 1e9;  // mu0/4pi = 1e-7
  const Eigen::Vector3d expected = st.pose.linear().transpose() * (F + dipole);
  EXPECT_GT(dipole.norm(), 300.0);  // [nT] a real anomaly
  EXPECT_LT((mag.last().field - expected).norm(), 1e-3 * dipole.norm());
  // the IMU sees it too (mG), so the KVH's output follows
  const Eigen::Vector3d imu = w.sensor<sensors::ImuSensor>("imu").last().magnetic_field;
  EXPECT_LT((imu * 100.0 - expected).norm(), 1e-3 * dipole.norm());
}

const char* kRobotField =
    "<magnetic><hard_iron value='310 -120 45'/>"
    "<soft_iron value='1.03 0.01 -0.02  0.01 0.97 0.015  -0.02 0.015 1.01'/>"
    "<thruster_current coefficient='0.2' exponent='1.5'/>"
    "<thruster id='0' field='4 -2.5 1'/></magnetic>\n";

TEST(Magnetometer, HardAndSoftIronAndAThrusterCurrent) {
  SphereSpec s;
  SensorWorld w(openWater(s), magUrdf(s, kIdeal, kRobotField));
  auto& mag = w.sensor<MagnetometerSensor>("magnetometer");
  const double T = 40.0;  // [N]
  w.robot().thruster(0).setCommand(T, 0.0);
  w.samples(mag, 1);
  ASSERT_NEAR(w.robot().thruster(0).thrust(), T, 1e-9);
  Eigen::Matrix3d S;
  S << 1.03, 0.01, -0.02, 0.01, 0.97, 0.015, -0.02, 0.015, 1.01;
  const Eigen::Vector3d h(310, -120, 45), v(4, -2.5, 1);
  const double I = 0.2 * std::pow(T, 1.5);  // [A]: 50.6 A
  const Eigen::Matrix3d R = w.robot().state().pose.linear();
  const Eigen::Vector3d external = R.transpose() * w.world->config().magnetic_field * 100.0;
  const Eigen::Vector3d expected = rpyMatrix(kMountRpy).transpose() * (S * external + h + v * I);
  EXPECT_LT((mag.last().field - expected).norm(), 1e-6 * expected.norm());
  EXPECT_LT((w.sensor<sensors::ImuSensor>("imu").last().magnetic_field * 100.0 - expected).norm(), 1e-6);
  // thrust reversed: the same current (|T|), so the same field
  w.robot().thruster(0).setCommand(-T, w.world->time());
  w.samples(mag, 1);
  const Eigen::Matrix3d R2 = w.robot().state().pose.linear();
  const Eigen::Vector3d expected2 =
      rpyMatrix(kMountRpy).transpose() * (S * R2.transpose() * w.world->config().magnetic_field * 100.0 + h + v * I);
  EXPECT_LT((mag.last().field - expected2).norm(), 1e-6 * expected2.norm());
}

TEST(Magnetometer, WhiteNoiseBiasAndResolution) {
  const SphereSpec s;
  const double sigma = 2.0, bias = 30.0, step = 0.5;  // [nT]
  SensorWorld w(
      openWater(s),
      magUrdf(s, {{"field_noise", num(sigma)}, {"field_bias", num(bias)}, {"resolution", num(step)}}, "", 500.0), 11);
  auto& mag = w.sensor<MagnetometerSensor>("magnetometer");
  const int n = 4000;
  std::vector<Eigen::Vector3d> reads;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    w.robot().setPose(sim::poseFromXyzRpy(Eigen::Vector3d(0, 0, -100), Eigen::Vector3d::Zero()));
    w.samples(mag, 1);
    const Eigen::Matrix3d R = w.robot().state().pose.linear();
    const Eigen::Vector3d truth = (R * rpyMatrix(kMountRpy)).transpose() * w.world->config().magnetic_field * 100.0;
    reads.push_back(mag.last().field - truth);
    mean += reads.back() / n;
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(mag.last().field[k] / step, std::round(mag.last().field[k] / step), 1e-6);  // on the grid
  }
  Eigen::Vector3d var = Eigen::Vector3d::Zero();
  for (const auto& r : reads)
    var += (r - mean).cwiseAbs2() / (n - 1);
  const double expected_var = sigma * sigma + step * step / 12;  // white + quantisation
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(var[k], expected_var, 5 * expected_var * std::sqrt(2.0 / n)) << k;
    EXPECT_LT(std::abs(mean[k]), 5 * bias) << k;  // the turn-on bias: one draw of 1 sigma = 30 nT
  }
  EXPECT_GT(mean.norm(), 5 * sigma / std::sqrt(n));  // a bias there is
  EXPECT_NEAR(mag.last().variance, expected_var, 1e-12);
  // the same seed, the same record
  SensorWorld again(
      openWater(s),
      magUrdf(s, {{"field_noise", num(sigma)}, {"field_bias", num(bias)}, {"resolution", num(step)}}, "", 500.0), 11);
  auto& mag2 = again.sensor<MagnetometerSensor>("magnetometer");
  again.samples(mag2, 1);
  SensorWorld first(
      openWater(s),
      magUrdf(s, {{"field_noise", num(sigma)}, {"field_bias", num(bias)}, {"resolution", num(step)}}, "", 500.0), 11);
  auto& mag1 = first.sensor<MagnetometerSensor>("magnetometer");
  first.samples(mag1, 1);
  EXPECT_EQ(mag1.last().field, mag2.last().field);
}

/// Centre of the quadric x^T A x + b^T x = 1 fitted to `points` by linear least squares: -A^-1 b / 2.
Eigen::Vector3d ellipsoidCentre(const std::vector<Eigen::Vector3d>& points, double scale) {
  Eigen::MatrixXd D(points.size(), 9);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d p = points[i] / scale;
    D.row(static_cast<Eigen::Index>(i)) << p.x() * p.x(), p.y() * p.y(), p.z() * p.z(), 2 * p.x() * p.y(),
        2 * p.x() * p.z(), 2 * p.y() * p.z(), p.x(), p.y(), p.z();
  }
  const Eigen::VectorXd c = D.colPivHouseholderQr().solve(Eigen::VectorXd::Ones(D.rows()));
  Eigen::Matrix3d A;
  A << c[0], c[3], c[4], c[3], c[1], c[5], c[4], c[5], c[2];
  return -0.5 * A.inverse() * c.segment<3>(6) * scale;
}

TEST(Magnetometer, AnEllipsoidFitOverManyAttitudesRecoversTheHardIron) {
  // What a user does before a survey: turn the robot through many attitudes on the spot, fit an ellipsoid to the
  // readings; its centre is the hard iron (the sensor mounted along the body axes, no turn-on bias, thrusters off).
  const SphereSpec s;
  const double sigma = 5.0;  // [nT] a noisy install
  SensorWorld w(openWater(s),
                magUrdf(s, {{"field_noise", num(sigma)}, {"field_bias", "0"}, {"resolution", "0.01"}}, kRobotField,
                        500.0, Eigen::Vector3d::Zero()),
                3);
  auto& mag = w.sensor<MagnetometerSensor>("magnetometer");
  std::mt19937_64 rng(42);
  std::normal_distribution<double> g(0.0, 1.0);
  const int n = 3000;
  std::vector<Eigen::Vector3d> reads;
  for (int i = 0; i < n; ++i) {
    const Eigen::Quaterniond q = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();  // uniform
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = q.toRotationMatrix();
    pose.translation() = Eigen::Vector3d(0, 0, -100);
    w.place(pose);
    w.samples(mag, 1);
    reads.push_back(mag.last().field);
  }
  const Eigen::Vector3d h(310, -120, 45);
  const Eigen::Vector3d centre = ellipsoidCentre(reads, 50000.0);
  // the centre of a fit over n points spread over the sphere: about sigma sqrt(3 / n) per axis; 5 of those
  const double tolerance = 5 * std::hypot(sigma, 0.01 / std::sqrt(12.0)) * std::sqrt(3.0 / n);
  EXPECT_LT((centre - h).norm(), std::sqrt(3.0) * tolerance) << centre.transpose() << " tolerance " << tolerance;
  EXPECT_LT(tolerance, 0.01 * h.norm());  // a test that can tell
  RecordProperty("centre_error_nT", std::to_string((centre - h).norm()));
  RecordProperty("tolerance_nT", std::to_string(std::sqrt(3.0) * tolerance));
}

TEST(Magnetometer, TheWorldFileGivesTheFieldAsIntensityAndAngles) {
  const std::string path = testTempDir() + "magnetometer.world";
  std::filesystem::copy_file(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/meshes/test_box.stl",
                             testTempDir() + "magnetometer_box.stl", std::filesystem::copy_options::overwrite_existing);
  auto write = [&](const std::string& field) {
    std::ofstream out(path);
    out << "name: magnetic\n"
        << field << "meshes:\n  - {name: box, file: magnetometer_box.stl}\nrobots:\n  - {name: UX_1, xyz: [0, 0, 0]}\n";
  };
  write("magnetic_field: {intensity: 49350, inclination: 67.7, declination: -1.5}\n");  // Ecton
  const Eigen::Vector3d b = sim::loadWorldConfig(path).magnetic_field * 100.0;          // [nT]
  const double H = 49350 * std::cos(67.7 * kPi / 180);
  EXPECT_LT((b - Eigen::Vector3d(H * std::sin(-1.5 * kPi / 180), H * std::cos(-1.5 * kPi / 180),
                                 -49350 * std::sin(67.7 * kPi / 180)))
                .norm(),
            1e-9 * 49350);
  write("magnetic_field: [24.0, 134.0, -508.0]\n");  // the vector form still reads
  EXPECT_EQ(sim::loadWorldConfig(path).magnetic_field, Eigen::Vector3d(24.0, 134.0, -508.0));
  write("");
  EXPECT_EQ(sim::loadWorldConfig(path).magnetic_field, Eigen::Vector3d(24.0, 134.0, -508.0));  // the default
  for (const auto& [text, expected] : std::vector<std::pair<std::string, std::string>>{
           {"{intensity: 49350, inclination: 95, declination: 0}",
            "'magnetic_field.inclination' = 95: expected [-90, 90]"},
           {"{intensity: 49.35, inclination: 60, declination: 0}",
            "'magnetic_field.intensity' = 49.35: expected [1000"},
           {"{intensity: 49350, inclination: 60, declination: 200}", "'magnetic_field.declination' = 200"},
           {"{intensity: 49350, inclination: 60}", "missing 'magnetic_field.declination'"},
           {"{intensity: 49350, inclination: 60, declination: 0, dip: 3}", "unknown key 'magnetic_field.dip'"}}) {
    write("magnetic_field: " + text + "\n");
    try {
      sim::loadWorldConfig(path);
      ADD_FAILURE() << text << " was accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
}

void expectError(const std::string& urdf, const std::string& expected) {
  const SphereSpec s;
  try {
    SensorWorld w(openWater(s), urdf);
    ADD_FAILURE() << "accepted; expected: " << expected;
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

TEST(Magnetometer, EveryBadParameterStopsStartUpNamingIt) {
  const SphereSpec s;
  expectError(magUrdf(s, {{"field_noise", "-1"}}),
              "sensor 'magnetometer' (type magnetometer): parameter 'field_noise'");
  expectError(magUrdf(s, {{"field_bias", "1e9"}}), "'field_bias' = 1000000000: expected a number in [0, 100000] nT");
  expectError(magUrdf(s, {{"resolution", "-0.1"}}), "'resolution'");
  expectError(magUrdf(s, {{"field_range", "10"}}), "'field_range'");
  expectError(magUrdf(s, {{"noise", "pink"}}), "'noise'");
  expectError(magUrdf(s, {{"feild_noise", "1"}}), "feild_noise");
  expectError(magUrdf(s, {}, "", 0.5), "'rate' = 0.5: expected [1, 1000] Hz");
  expectError(magUrdf(s, {}, "<magnetic><soft_iron value='1 0 0 0 1 0 0 0 0'/></magnetic>"),
              "<magnetic><soft_iron>@value has singular values 0");
  expectError(magUrdf(s, {}, "<magnetic><soft_iron value='1 0 0'/></magnetic>"), "has 3 numbers, expected 9");
  expectError(magUrdf(s, {}, "<magnetic><thruster id='7' field='1 0 0'/></magnetic>"), "the robot has no thruster 7");
  expectError(magUrdf(s, {}, "<magnetic><thruster id='0' field='1 0 0'/><thruster id='0' field='1 0 0'/></magnetic>"),
              "given twice");
  expectError(magUrdf(s, {}, "<magnetic><hardiron value='1 0 0'/></magnetic>"), "unknown element <hardiron>");
  expectError(magUrdf(s, {}, "<magnetic><thruster_current exponent='7'/></magnetic>"), "@exponent = 7");
  expectError(magUrdf(s, {}, "<magnetic><hard_iron value='2e6 0 0'/></magnetic>"), "at most 1000000 nT");
}

}  // namespace
}  // namespace test
}  // namespace unexmin

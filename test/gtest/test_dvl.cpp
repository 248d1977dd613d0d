// DVL model (cpp/unexmin/sensors/dvl_sensor.h) in the laboratory tank (worlds/tank.world, floor at z = -3 m):
// beam ranges against the analytic distance to the floor, velocity against the set robot velocity,
// velocity_z1/z2 each from its own beam pair (heave while moving and turning; one beam out of the window),
// bottom lock against the altitude window, the 3-beam solution, the ping schedule and start-up errors.
#include <unexmin/sensors/dvl_sensor.h>
#include <unexmin/water/seawater.h>
#include <unexmin/water/water_column.h>
#include "mesh_fixture.h"
#include "sensor_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace unexmin {
namespace test {
namespace {

constexpr double kFloorZ = -3.0;                  // [m] tank floor (docs/worlds.md)
constexpr double kBeamAngle = 25.0 * M_PI / 180;  // [rad]
constexpr double kAzimuth0 = 0.0;                 // [rad]

sim::WorldConfig tank() {
  return sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/tank.world");
}

std::string dvlUrdf(const SphereSpec& s, double rate, std::map<std::string, std::string> params) {
  params.emplace("beam_angle", num(kBeamAngle));
  params.emplace("beam_azimuth_0", num(kAzimuth0));
  params.emplace("beam_frames", "T/dvl_beam_0_link T/dvl_beam_1_link T/dvl_beam_2_link T/dvl_beam_3_link");
  return sensorUrdf(s, dvlLinks(kBeamAngle, kAzimuth0), sensorXml("dvl", "dvl", "T/dvl_link", rate, params));
}

/// Beam i in the DVL frame (formula of the model's documentation).
Eigen::Vector3d beam(int i) {
  const double c = kAzimuth0 + i * M_PI / 2;
  return Eigen::Vector3d(std::sin(kBeamAngle) * std::cos(c), std::sin(kBeamAngle) * std::sin(c), std::cos(kBeamAngle));
}

/// DVL frame in the world for the robot at `pose`: hull bottom, rpy (pi, 0, 0).
Eigen::Isometry3d dvlPose(const Eigen::Isometry3d& pose) {
  return pose * sim::poseFromXyzRpy(Eigen::Vector3d(0, 0, -0.3), Eigen::Vector3d(M_PI, 0, 0));
}

/// Slant distance from the DVL along beam i to the plane z = kFloorZ.
double floorRange(const Eigen::Isometry3d& dvl, int i) {
  const Eigen::Vector3d d = dvl.linear() * beam(i);
  EXPECT_LT(d.z(), 0.0) << "beam " << i << " does not point down";
  return (dvl.translation().z() - kFloorZ) / -d.z();
}

TEST(Dvl, BeamRangesEqualTheAnalyticDistanceToTheTankFloor) {
  const SphereSpec s = undampedSphere();
  SensorWorld w(tank(), dvlUrdf(s, 500.0, {{"noise", "none"}}));
  const Eigen::Isometry3d pose =
      sim::poseFromXyzRpy(Eigen::Vector3d(-1.5, 1.0, -1.2), Eigen::Vector3d(0.12, -0.08, 0.6));
  w.place(pose);
  w.step();
  auto& dvl = w.sensor<sensors::DvlSensor>("dvl");
  const Eigen::Isometry3d at = dvlPose(w.robot().state().pose);  // the pose of the ping
  ASSERT_TRUE(dvl.last().bottom_lock);
  double along_z = 0.0;
  for (int i = 0; i < 4; ++i) {
    const double expected = floorRange(at, i);
    // The floor point is in the open part of the tank (walls at |x| = 3, |y| = 2; anchor at the centre).
    const Eigen::Vector3d hit = at.translation() + expected * (at.linear() * beam(i));
    ASSERT_LT(std::abs(hit.x()), 2.9);
    ASSERT_LT(std::abs(hit.y()), 1.9);
    ASSERT_GT(std::hypot(hit.x(), hit.y()), 0.6);
    EXPECT_TRUE(dvl.last().beams[i].valid);
    EXPECT_NEAR(dvl.last().beams[i].range, expected, 0.002) << "beam " << i;  // issue: +-2 cm
    along_z += expected * std::cos(kBeamAngle) / 4.0;
  }
  EXPECT_NEAR(dvl.last().altitude, along_z, 0.002);
}

TEST(Dvl, VelocityEqualsTheSetRobotVelocityWithinThreeSigma) {
  const SphereSpec s = undampedSphere();
  const double sigma_beam = 0.003;   // [m/s]
  const double scale_sigma = 0.001;  // [-]
  SensorWorld w(
      tank(), dvlUrdf(s, 100.0, {{"beam_velocity_noise", num(sigma_beam)}, {"velocity_scale_error", num(scale_sigma)}}),
      21);
  const double yaw = 0.4;
  const Eigen::Vector3d v_world(0.15, -0.1, 0.02);  // [m/s], stays constant: no damping, neutral
  w.place(sim::poseFromXyzRpy(Eigen::Vector3d(-1.6, 0.8, -1.2), Eigen::Vector3d(0, 0, yaw)), v_world);
  // Expected in the DVL frame: R_dvl^T R^T v.
  const Eigen::Matrix3d R = dvlPose(sim::poseFromXyzRpy(Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, yaw))).linear();
  const Eigen::Vector3d expected = R.transpose() * v_world;
  auto& dvl = w.sensor<sensors::DvlSensor>("dvl");
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int pings = 0;
  for (int i = 0; i < 250; ++i) {  // 0.5 s: 50 pings, 0.1 m of travel
    w.step();
    if (dvl.sampleTime() != w.world->time())
      continue;
    ASSERT_TRUE(dvl.last().bottom_lock);
    sum += dvl.last().velocity;
    ++pings;
  }
  ASSERT_EQ(pings, 50);
  // Per ping: covariance s_b^2 (B^T B)^-1 (+ the scale term); B^T B = diag(2 s^2, 2 s^2, 4 c^2).
  const double sx = sigma_beam / (std::sqrt(2.0) * std::sin(kBeamAngle));
  const double sz = sigma_beam / (2.0 * std::cos(kBeamAngle));
  const Eigen::Vector3d one(sx, sx, sz);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(std::sqrt(dvl.last().covariance(a, a)), std::hypot(one[a], scale_sigma * expected[a]), 1e-6);
    EXPECT_NEAR(dvl.last().velocity[a], expected[a], 3.0 * std::hypot(one[a], scale_sigma * std::abs(expected[a])));
    // Mean of the pings: white part averages down, the turn-on scale error does not.
    EXPECT_NEAR(sum[a] / pings, expected[a], 3.0 * std::hypot(one[a] / std::sqrt(pings), scale_sigma * expected[a]))
        << "axis " << a;
  }
}

TEST(Dvl, RotationAddsTheLeverArmVelocityOfTheDvlOrigin) {
  const SphereSpec s = undampedSphere();
  SensorWorld w(tank(), dvlUrdf(s, 500.0, {{"noise", "none"}}));
  const Eigen::Vector3d v(0.05, 0.0, 0.0), omega(0.0, 0.3, 0.1);  // pitching and yawing
  w.place(sim::poseFromXyzRpy(Eigen::Vector3d(-1.5, -0.8, -1.2), Eigen::Vector3d::Zero()), v, omega);
  w.step();
  const sim::RobotState st = w.robot().state();  // at the ping
  const Eigen::Isometry3d at = dvlPose(st.pose);
  const Eigen::Vector3d r = at.translation() - st.pose.translation();
  const Eigen::Vector3d expected = at.linear().transpose() * (st.linear_velocity + st.angular_velocity.cross(r));
  EXPECT_GT((expected - at.linear().transpose() * st.linear_velocity).norm(), 0.05);  // the lever arm matters
  EXPECT_LT((w.sensor<sensors::DvlSensor>("dvl").last().velocity - expected).norm(), 1e-9);
}

/// Velocity of the DVL origin over the (static) floor in the DVL frame, from the robot state at the ping:
/// R_dvl^T (v + w x r), r the lever arm from the body origin to the DVL [m/s].
Eigen::Vector3d dvlVelocity(const sim::RobotState& st) {
  const Eigen::Isometry3d at = dvlPose(st.pose);
  const Eigen::Vector3d r = at.translation() - st.pose.translation();
  return at.linear().transpose() * (st.linear_velocity + st.angular_velocity.cross(r));
}

TEST(Dvl, HeaveWhileMovingAndTurningGivesVelocityZ1AndZ2FromTheirOwnBeamPairs) {
  // Heave plus a horizontal velocity and a yaw rate, the robot slightly rolled and pitched so the lever arm
  // counts. Beam i measures b_i . v; z1 = (u0 + u2) / (2 cos a) and z2 = (u1 + u3) / (2 cos a) are both the
  // DVL-frame z velocity. A wrong pair mixes in the horizontal velocity: (u0 + u1) / (2 cos a) =
  // v_z + tan(a) (v_x + v_y) / 2, (u0 + u3) / (2 cos a) = v_z + tan(a) (v_x - v_y) / 2, (2 u0) / (2 cos a) =
  // v_z + tan(a) v_x, ... so x, y, x + y and x - y are all made large against the 1e-9 tolerance.
  const SphereSpec s = undampedSphere();
  SensorWorld w(tank(), dvlUrdf(s, 500.0, {{"noise", "none"}}));
  const Eigen::Vector3d v(0.2, -0.07, 0.06), omega(0.04, -0.05, 0.35);  // [m/s] heave 6 cm/s up, [rad/s]
  w.place(sim::poseFromXyzRpy(Eigen::Vector3d(-1.5, 0.6, -1.2), Eigen::Vector3d(0.06, -0.04, 0.9)), v, omega);
  w.step();
  const sensors::DvlSample& p = w.sensor<sensors::DvlSensor>("dvl").last();
  const Eigen::Vector3d expected = dvlVelocity(w.robot().state());
  // The DVL's z is the world's -z (rpy pi 0 0 on a nearly level robot): the heave shows as -6 cm/s.
  ASSERT_NEAR(expected.z(), -v.z(), 0.01);
  for (double horizontal : {expected.x(), expected.y(), expected.x() + expected.y(), expected.x() - expected.y()})
    ASSERT_GT(std::abs(horizontal), 0.05);
  ASSERT_TRUE(p.bottom_lock);
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(p.beams[i].valid) << "beam " << i;
    EXPECT_NEAR(p.beams[i].velocity, beam(i).dot(expected), 1e-9) << "beam " << i;
  }
  EXPECT_NEAR(p.velocity_z1, expected.z(), 1e-9);
  EXPECT_NEAR(p.velocity_z2, expected.z(), 1e-9);
  EXPECT_LT((p.velocity - expected).norm(), 1e-9);
}

TEST(Dvl, VelocityZ1AndZ2AreNaNExactlyWhenABeamOfTheirOwnPairIsInvalid) {
  // Tilted so that one beam sees the floor farthest along the DVL z, and altitude_max set between it and the
  // others: that beam alone is invalid. Pitched (nose down), beam 2 (aft) is the far one: z1 (beams 0, 2) is
  // NaN and z2 (beams 1, 3) the z velocity; rolled, beam 3: z2 is NaN and z1 the z velocity. A z taken from
  // the other pair's beams comes out NaN where it must be a number, or a number where it must be NaN.
  const SphereSpec s = undampedSphere();
  const Eigen::Vector3d v(0.12, 0.05, -0.15), omega(0.0, 0.0, -0.3);  // [m/s] sinking 15 cm/s, [rad/s]
  struct Case {
    Eigen::Vector3d rpy;
    int far;
  };
  for (const Case& c : {Case{Eigen::Vector3d(0, 0.22, 0.3), 2}, Case{Eigen::Vector3d(0.22, 0, 0.3), 3}}) {
    const Eigen::Isometry3d pose = sim::poseFromXyzRpy(Eigen::Vector3d(-1.6, 0.3, -1.2), c.rpy);
    std::array<double, 4> along{};
    for (int i = 0; i < 4; ++i) {
      along[i] = floorRange(dvlPose(pose), i) * std::cos(kBeamAngle);
      const Eigen::Vector3d hit = dvlPose(pose) * (floorRange(dvlPose(pose), i) * beam(i));
      ASSERT_LT(std::abs(hit.x()), 2.9);  // on the open floor (walls at |x| = 3, |y| = 2; anchor at the centre)
      ASSERT_LT(std::abs(hit.y()), 1.9);
      ASSERT_GT(std::hypot(hit.x(), hit.y()), 0.6);
    }
    const int far = static_cast<int>(std::max_element(along.begin(), along.end()) - along.begin());
    ASSERT_EQ(far, c.far);
    double second = 0.0;
    for (int i = 0; i < 4; ++i)
      if (i != far)
        second = std::max(second, along[i]);
    ASSERT_GT(along[far] - second, 0.05);
    const double altitude_max = 0.5 * (second + along[far]);

    SensorWorld w(tank(), dvlUrdf(s, 500.0, {{"noise", "none"}, {"altitude_max", num(altitude_max)}}));
    w.place(pose, v, omega);
    w.step();
    const sensors::DvlSample& p = w.sensor<sensors::DvlSensor>("dvl").last();
    const Eigen::Vector3d expected = dvlVelocity(w.robot().state());
    ASSERT_GT(std::abs(expected.z()), 0.05);
    ASSERT_TRUE(p.bottom_lock);
    for (int i = 0; i < 4; ++i)
      EXPECT_EQ(p.beams[i].valid, i != far) << "beam " << i;
    const bool z1_valid = far != 0 && far != 2, z2_valid = far != 1 && far != 3;
    if (z1_valid)
      EXPECT_NEAR(p.velocity_z1, expected.z(), 1e-9) << "far beam " << far;
    else
      EXPECT_TRUE(std::isnan(p.velocity_z1)) << "far beam " << far << ": z1 = " << p.velocity_z1;
    if (z2_valid)
      EXPECT_NEAR(p.velocity_z2, expected.z(), 1e-9) << "far beam " << far;
    else
      EXPECT_TRUE(std::isnan(p.velocity_z2)) << "far beam " << far << ": z2 = " << p.velocity_z2;
    EXPECT_LT((p.velocity - expected).norm(), 1e-9);  // three beams still give the whole velocity
  }
}

TEST(Dvl, BeyondTheMaximumAltitudeEveryBeamIsInvalid) {
  const SphereSpec s = undampedSphere();
  SensorWorld w(tank(), dvlUrdf(s, 500.0, {{"noise", "none"}, {"altitude_max", "1.0"}}));
  w.place(sim::poseFromXyzRpy(Eigen::Vector3d(-1.5, 1.0, -1.2), Eigen::Vector3d::Zero()));  // altitude 1.5 m
  w.step();
  const sensors::DvlSample& p = w.sensor<sensors::DvlSensor>("dvl").last();
  EXPECT_FALSE(p.bottom_lock);
  for (const auto& b : p.beams) {
    EXPECT_FALSE(b.valid);
    EXPECT_TRUE(std::isinf(b.range));
    EXPECT_TRUE(std::isnan(b.velocity));
  }
  EXPECT_TRUE(std::isnan(p.velocity.x()));
  EXPECT_TRUE(std::isnan(p.altitude));
}

TEST(Dvl, BottomLockNeedsThreeBeamsAndThreeGiveTheVelocity) {
  const SphereSpec s = undampedSphere();
  // Rolled: the four beams see the floor at four different distances along the DVL z.
  const Eigen::Isometry3d pose = sim::poseFromXyzRpy(Eigen::Vector3d(-1.5, 0.5, -1.2), Eigen::Vector3d(0.25, 0.1, 0));
  std::array<double, 4> along{};
  for (int i = 0; i < 4; ++i)
    along[i] = floorRange(dvlPose(pose), i) * std::cos(kBeamAngle);
  std::array<double, 4> sorted = along;
  std::sort(sorted.begin(), sorted.end());
  ASSERT_GT(sorted[2] - sorted[1], 0.02);
  ASSERT_GT(sorted[3] - sorted[2], 0.02);
  const Eigen::Vector3d v(0.1, 0.05, -0.03);
  for (int keep : {2, 3}) {
    const double altitude_max = 0.5 * (sorted[keep - 1] + sorted[keep]);
    SensorWorld w(tank(), dvlUrdf(s, 500.0, {{"noise", "none"}, {"altitude_max", num(altitude_max)}}));
    w.place(pose, v);
    w.step();
    const sensors::DvlSample& p = w.sensor<sensors::DvlSensor>("dvl").last();
    int valid = 0;
    for (int i = 0; i < 4; ++i) {
      EXPECT_EQ(p.beams[i].valid, along[i] <= altitude_max) << "beam " << i;
      valid += p.beams[i].valid ? 1 : 0;
    }
    EXPECT_EQ(valid, keep);
    EXPECT_EQ(p.bottom_lock, keep == 3);
    if (keep == 3) {
      const sim::RobotState st = w.robot().state();
      const Eigen::Isometry3d at = dvlPose(st.pose);
      const Eigen::Vector3d r = at.translation() - st.pose.translation();
      const Eigen::Vector3d expected = at.linear().transpose() * (st.linear_velocity + st.angular_velocity.cross(r));
      EXPECT_LT((p.velocity - expected).norm(), 1e-9);
    }
  }
}

TEST(Dvl, PingsAtEightHertzOfSimulationTime) {
  const SphereSpec s;
  SensorWorld w(tank(), dvlUrdf(s, 8.0, {}));
  auto& dvl = w.sensor<sensors::DvlSensor>("dvl");
  std::vector<double> times;
  for (int i = 0; i < 5000; ++i) {  // 10 s at 500 Hz
    w.step();
    if (w.suite->fresh(0))
      times.push_back(w.world->time());
  }
  ASSERT_EQ(times.size(), 80u);
  EXPECT_EQ(dvl.sampleCount(), 80u);
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double due = (k + 1) / 8.0;  // first step at or after k+1 / rate
    EXPECT_GE(times[k], due - 1e-9);
    EXPECT_LT(times[k], due + w.world->dt() - 1e-9);
  }
}

TEST(Dvl, SoundSpeedFollowsMedwin) {
  // Medwin (1975) at 10 degC, fresh water, surface: 1449.2 + 46 - 5.5 + 0.29 + 1.24 (0 - 35).
  EXPECT_NEAR(sensors::soundSpeedMedwin(10.0, 0.0, 0.0), 1449.2 + 46.0 - 5.5 + 0.29 - 1.24 * 35.0, 1e-9);
  EXPECT_NEAR(sensors::soundSpeedMedwin(10.0, 35.0, 100.0) - sensors::soundSpeedMedwin(10.0, 35.0, 0.0), 1.6, 1e-9);
}

std::string startupError(const std::string& urdf) {
  try {
    SensorWorld w(tank(), urdf);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(Dvl, MalformedParametersStopStartUpNamingSensorAndParameter) {
  const SphereSpec s;
  std::string e = startupError(sensorUrdf(s, dvlLinks(kBeamAngle, 0),
                                          sensorXml("dvl", "dvl", "T/dvl_link", 8.0, {{"beam_angle", num(M_PI / 2)}})));
  EXPECT_NE(e.find("sensor 'dvl'"), std::string::npos) << e;
  EXPECT_NE(e.find("'beam_angle'"), std::string::npos) << e;

  e = startupError(dvlUrdf(s, 8.0, {{"noise", "brown"}}));
  EXPECT_NE(e.find("'noise'"), std::string::npos) << e;

  e = startupError(dvlUrdf(s, 8.0, {{"altitude_min", "5"}, {"altitude_max", "1"}}));
  EXPECT_NE(e.find("'altitude_max'"), std::string::npos) << e;

  // Beam frames that disagree with beam_angle (the URDF drawn at 30 deg, the model at 25 deg).
  e = startupError(sensorUrdf(
      s, dvlLinks(30.0 * M_PI / 180, 0),
      sensorXml("dvl", "dvl", "T/dvl_link", 8.0,
                {{"beam_angle", num(kBeamAngle)},
                 {"beam_frames", "T/dvl_beam_0_link T/dvl_beam_1_link T/dvl_beam_2_link T/dvl_beam_3_link"}})));
  EXPECT_NE(e.find("'beam_frames'"), std::string::npos) << e;
  EXPECT_NE(e.find("5 deg"), std::string::npos) << e;
}

TEST(Dvl, ABeamThatMeetsTheFreeSurfaceFirstReportsNoBottomAndSaysSo) {
  // The tank with a ceiling 0.4..0.5 m above its free surface (z = 0); the robot upside down, its DVL 0.3 m deep
  // looking up. Sound does not cross the surface: every beam meets it first, so no beam is valid, each is
  // flagged `surface` with its figure of merit (velocity_std) +inf, and there is no bottom lock or altitude --
  // not the ceiling as a false bottom. With the surface raised above the ceiling the same beams lock on it at
  // the ray-plane distance computed here.
  for (const double surface_z : {0.0, 2.0}) {
    sim::WorldConfig config = tank();
    config.surface_z = surface_z;
    sim::MeshEntry ceiling;
    ceiling.name = "ceiling";
    ceiling.file = writeStl("dvl_ceiling", box(Eigen::Vector3d(-2.9, -1.9, 0.4), Eigen::Vector3d(2.9, 1.9, 0.5)));
    config.meshes.push_back(ceiling);
    const SphereSpec s = undampedSphere();
    SensorWorld w(config, dvlUrdf(s, 500.0, {{"beam_velocity_noise", "0.002"}}));
    w.place(sim::poseFromXyzRpy(Eigen::Vector3d(-1.5, 1.0, -0.6), Eigen::Vector3d(M_PI, 0, 0)));
    w.step();
    auto& dvl = w.sensor<sensors::DvlSensor>("dvl");
    const Eigen::Isometry3d at = dvlPose(w.robot().state().pose);
    ASSERT_NEAR(at.translation().z(), -0.3, 1e-3);
    for (int i = 0; i < 4; ++i) {
      const auto& b = dvl.last().beams[i];
      const Eigen::Vector3d d = at.linear() * beam(i);
      ASSERT_GT(d.z(), 0.0) << "beam " << i << " does not point up";
      if (surface_z == 0.0) {
        EXPECT_FALSE(b.valid) << "beam " << i;
        EXPECT_TRUE(b.surface) << "beam " << i;
        EXPECT_TRUE(std::isinf(b.range)) << "beam " << i;
        EXPECT_TRUE(std::isinf(b.velocity_std)) << "beam " << i;
      } else {
        EXPECT_TRUE(b.valid) << "beam " << i;
        EXPECT_FALSE(b.surface) << "beam " << i;
        EXPECT_NEAR(b.range, (0.4 - at.translation().z()) / d.z(), 0.002) << "beam " << i;
        EXPECT_NEAR(b.velocity_std, 0.002, 1e-12) << "beam " << i;
      }
    }
    EXPECT_EQ(dvl.last().bottom_lock, surface_z != 0.0);
    EXPECT_EQ(std::isnan(dvl.last().altitude), surface_z == 0.0);
  }
}

TEST(Dvl, InAWaterColumnRangesAndVelocitiesScaleByTheAssumedOverTheTrueSoundSpeed) {
  // fresh water at 6 degC; the DVL left at salinity 35 assumes Medwin's sea-water sound speed: it reads its ranges
  // and beam velocities c_assumed / c_water long (about 3 %), and takes the water's temperature from the column
  const SphereSpec s = undampedSphere();
  sim::WorldConfig config = tank();
  water::Profile cold;
  cold.rows.resize(1);
  cold.rows[0].temperature = 6.0;
  water::checkProfile(cold, "water.profile");
  config.water_column =
      std::make_shared<const water::WaterColumn>(cold, std::vector<water::Region>{}, config.surface_z, config.gravity);
  SensorWorld w(config, dvlUrdf(s, 500.0, {{"noise", "none"}, {"salinity", "35"}}));
  const Eigen::Vector3d v_world(0.12, -0.05, 0.0);
  const Eigen::Isometry3d pose = sim::poseFromXyzRpy(Eigen::Vector3d(-1.5, 1.0, -1.2), Eigen::Vector3d(0, 0, 0.3));
  w.place(pose, v_world);
  w.step();
  auto& dvl = w.sensor<sensors::DvlSensor>("dvl");
  const Eigen::Isometry3d at = dvlPose(w.robot().state().pose);
  const double depth = config.surface_z - at.translation().z();
  const double assumed = sensors::soundSpeedMedwin(6.0, 35.0, depth);
  const double truth = water::soundSpeed(0.0, 6.0, 1e-4 * 1000.0 * config.gravity * depth);
  const double k = assumed / truth;
  ASSERT_GT(k, 1.025);  // a model that ignored the water would be 3 % off: far beyond the tolerances below
  EXPECT_NEAR(dvl.last().sound_speed, assumed, 1e-9);
  EXPECT_NEAR(dvl.last().temperature, 6.0, 1e-12);
  ASSERT_TRUE(dvl.last().bottom_lock);
  const Eigen::Vector3d v = at.linear().transpose() * w.robot().state().linear_velocity;
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(dvl.last().beams[i].range, k * floorRange(at, i), 0.002) << "beam " << i;
    EXPECT_NEAR(dvl.last().beams[i].velocity, k * beam(i).dot(v), 1e-6) << "beam " << i;
  }
  EXPECT_NEAR((dvl.last().velocity - k * v).norm(), 0.0, 1e-6);
}

}  // namespace
}  // namespace test
}  // namespace unexmin

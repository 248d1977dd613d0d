// SLS unit (cpp/unexmin/sensors/vision/sls_sensor.h) against geometry computed here: a laser head on the hull
// of the test sphere (x = +0.3 m, fan in its x-z plane) and a camera 20 deg round the hull looking outwards
// (REP-103 optical frame), facing the +x wall of the 4 m test box (x = 2 m). Every published point lies on the
// wall and on the laser plane; the points are exactly the fan's hits that the camera sees (inside its distorted
// image, bright enough by the line-strength formula); a box in the camera's line of sight removes exactly the
// points it hides; in turbid water the range shrinks to where the formula says; the raw fan, the motor's
// triangle wave, the triangulation noise and the parameter errors.
#include <unexmin/sensors/vision/sls_sensor.h>
#include <unexmin/sensors/vision/surface_materials.h>
#include "mesh_fixture.h"
#include "sonar_fixture.h"

#include <gtest/gtest.h>

#include <cmath>

namespace unexmin {
namespace test {
namespace {

using sensors::vision::SlsSensor;

constexpr double kDeg = M_PI / 180.0;
constexpr double kWallX = 2.0;         // [m] the test box's +x wall
constexpr double kHfov = 80.0 * kDeg;  // [rad]
constexpr int kWidth = 640, kHeight = 480;
const double kK1 = -0.1, kK2 = 0.02;          // plumb_bob radial terms (p1 = p2 = k3 = 0)
const Eigen::Vector3d kLaser(0.3, 0.0, 0.0);  // head origin, base frame
const Eigen::Vector3d kCamera(0.3 * std::cos(20 * kDeg), 0.3 * std::sin(20 * kDeg), 0.0);  // optical centre

sim::WorldConfig testBox(const std::string& visibility = "none") {
  sim::WorldConfig c = sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/test_box.world");
  c.visibility = visibility;
  return c;
}

/// Head on a revolute joint about z at (0.3, 0, 0); camera link at azimuth 20 deg (+x out of the lens) with its
/// optical frame (z forward, x right, y down).
std::string slsUrdf(std::map<std::string, std::string> params = {}, double rate = 10.0) {
  const std::string links =
      mountLink("T/sls_base_link", kLaser, Eigen::Vector3d::Zero()) +
      "<link name='T/sls_link'/><joint name='T/sls_motor_joint' type='revolute'><parent link='T/sls_base_link'/>"
      "<child link='T/sls_link'/><origin xyz='0 0 0' rpy='0 0 0'/><axis xyz='0 0 1'/>"
      "<limit lower='-1' upper='1' effort='1' velocity='1'/></joint>\n" +
      mountLink("T/camera_link", kCamera, Eigen::Vector3d(0, 0, 20 * kDeg)) +
      mountLink("T/camera_optical_frame", Eigen::Vector3d::Zero(), Eigen::Vector3d(-M_PI / 2, 0, -M_PI / 2),
                "T/camera_link");
  params.emplace("camera_frame", "T/camera_optical_frame");
  params.emplace("camera_width", num(kWidth));
  params.emplace("camera_height", num(kHeight));
  params.emplace("camera_hfov", num(kHfov));
  params.emplace("camera_distortion", num(kK1) + " " + num(kK2) + " 0 0 0");
  params.emplace("motor_speed", "0");
  params.emplace("motor_start", "0");  // still, facing +x
  params.emplace("rays", "101");
  params.emplace("noise", "none");
  return sensorUrdf(undampedSphere(), links, sensorXml("sls", "sls", "T/sls_link", rate, params));
}

/// Pixel of a point given in the camera's optical frame, by the plumb_bob formulas (closed form, p = k3 = 0);
/// false when behind the lens or outside the image.
bool pixel(const Eigen::Vector3d& p, double& u, double& v) {
  if (p.z() <= 0)
    return false;
  const double x = p.x() / p.z(), y = p.y() / p.z(), r2 = x * x + y * y;
  const double radial = 1 + kK1 * r2 + kK2 * r2 * r2;
  const double f = (kWidth / 2.0) / std::tan(kHfov / 2.0);
  u = f * x * radial + (kWidth - 1) / 2.0;
  v = f * y * radial + (kHeight - 1) / 2.0;
  return u >= -0.5 && u <= kWidth - 0.5 && v >= -0.5 && v <= kHeight - 0.5;
}

/// The camera's optical frame in the world for the robot at `base` (yaw 0): z along (cos 20, sin 20, 0).
Eigen::Isometry3d cameraInWorld(const Eigen::Vector3d& base) {
  Eigen::Matrix3d R;
  const double c = std::cos(20 * kDeg), s = std::sin(20 * kDeg);
  R.col(2) = Eigen::Vector3d(c, s, 0);   // z: optical axis
  R.col(0) = Eigen::Vector3d(s, -c, 0);  // x: right
  R.col(1) = Eigen::Vector3d(0, 0, -1);  // y: down
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = base + kCamera;
  return T;
}

/// Expected laser points on the +x wall for the robot at `base`, motor at 0: ray j at elevation e_j meets the
/// wall at base + laser + t (cos e, 0, sin e), t = (wall - x) / cos e; kept when the camera sees it and its
/// line strength reaches the detection level; `blocked` says whether an occluder hides the sight line.
inline double albedoAt(double albedo, const Eigen::Vector3d&) {
  return albedo;
}
template <class F>
double albedoAt(const F& albedo, const Eigen::Vector3d& w) {
  return albedo(w);
}

/// `albedo`: the wall's green albedo, a number or a function of the world point.
template <class Blocked, class Albedo = double>
std::vector<Eigen::Vector3d> expectedPoints(const Eigen::Vector3d& base, int rays, double fan, double c, double b,
                                            double threshold, double glow, Albedo albedo, Blocked blocked) {
  std::vector<Eigen::Vector3d> out;
  const Eigen::Isometry3d cam = cameraInWorld(base);
  for (int j = 0; j < rays; ++j) {
    const double e = -fan / 2 + j * fan / (rays - 1);
    const Eigen::Vector3d o = base + kLaser, d(std::cos(e), 0, std::sin(e));
    const double t = (kWallX - o.x()) / d.x();
    if (t > 5.0)
      continue;  // range_max
    const Eigen::Vector3d w = o + t * d;
    if (std::abs(w.z()) > 2.0)
      continue;  // beyond the wall: floor or ceiling
    double u, v;
    if (!pixel(cam.inverse() * w, u, v) || blocked(cam.translation(), w))
      continue;
    const double rc = (w - cam.translation()).norm();
    const double strength = albedoAt(albedo, w) * std::cos(e) * std::exp(-c * (t + rc)) / t;  // cos(incidence) = cos e
    if (strength >= threshold * (1 + b * glow))
      out.push_back(cam.inverse() * w);
  }
  return out;
}

auto noBlock = [](const Eigen::Vector3d&, const Eigen::Vector3d&) { return false; };

void expectSamePoints(const std::vector<Eigen::Vector3f>& got, const std::vector<Eigen::Vector3d>& want, double tol) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i)
    EXPECT_LT((got[i].cast<double>() - want[i]).norm(), tol) << "point " << i;
}

TEST(Sls, ThePointsAreTheFansHitsOnTheWallThatTheCameraSees) {
  SensorWorld w(testBox(), slsUrdf());
  auto& sls = w.sensor<SlsSensor>("sls");
  const Eigen::Vector3d base(0.5, 0.0, 0.3);
  w.place(sim::poseFromXyzRpy(base, Eigen::Vector3d::Zero()));
  w.samples(sls, 1);
  const Eigen::Vector3d at = w.robot().state().pose.translation();
  const auto want = expectedPoints(at, 101, 100 * kDeg, 0.151, 0.037, 1e-3, 1.0, 0.3, noBlock);
  ASSERT_GT(want.size(), 20u) << "the scene must show a good part of the line";
  ASSERT_LT(want.size(), 101u) << "and not all of it (the image edge must cut it)";
  expectSamePoints(sls.last().points, want, 1e-3);
  // Every point on the wall plane and on the laser plane (y = laser's y in the world), in the image.
  const Eigen::Isometry3d cam = cameraInWorld(at);
  for (const auto& p : sls.last().points) {
    const Eigen::Vector3d world = cam * p.cast<double>();
    EXPECT_NEAR(world.x(), kWallX, 1e-3);
    EXPECT_NEAR(world.y(), at.y() + kLaser.y(), 1e-3);
    double u, v;
    EXPECT_TRUE(pixel(p.cast<double>(), u, v));
  }
}

TEST(Sls, TheLinesDetectionUsesTheTexturedAlbedoAtTheHit) {
  // The wall of rock (contrast 0.5 around 0.3): a point is kept where the green albedo of the texture at its hit
  // makes the line strong enough; the threshold is set so that the texture decides for some points.
  sim::WorldConfig box = testBox();
  box.meshes.at(0).material = sim::materialDefaults("rock");
  box.meshes[0].material.contrast = 0.5;
  box.meshes[0].material.seed = 3;
  box.meshes[0].albedo = Eigen::Vector3d::Constant(0.3);
  const sensors::vision::SurfaceMaterials materials(box);
  const auto rock = [&](const Eigen::Vector3d& w) { return materials.albedo(0, w.cast<float>()).y(); };
  SensorWorld w(box, slsUrdf({{"threshold", "0.1"}}));
  auto& sls = w.sensor<SlsSensor>("sls");
  w.place(sim::poseFromXyzRpy(Eigen::Vector3d(0.5, 0.0, 0.3), Eigen::Vector3d::Zero()));
  w.samples(sls, 1);
  const Eigen::Vector3d at = w.robot().state().pose.translation();
  const auto want = expectedPoints(at, 101, 100 * kDeg, 0.151, 0.037, 0.1, 1.0, rock, noBlock);
  const auto flat = expectedPoints(at, 101, 100 * kDeg, 0.151, 0.037, 0.1, 1.0, 0.3, noBlock);
  ASSERT_GT(want.size(), 5u);
  ASSERT_NE(want.size(), flat.size()) << "the texture must decide for some points";
  expectSamePoints(sls.last().points, want, 1e-3);
}

TEST(Sls, TheRawFanMeasuresTheAnalyticDistanceToTheBox) {
  SensorWorld w(testBox(), slsUrdf());
  auto& sls = w.sensor<SlsSensor>("sls");
  const Eigen::Vector3d base(0.5, 0.2, -0.4);
  w.place(sim::poseFromXyzRpy(base, Eigen::Vector3d::Zero()));
  w.samples(sls, 1);
  const Eigen::Vector3d o = w.robot().state().pose.translation() + kLaser;
  ASSERT_EQ(sls.last().ranges.size(), 101u);
  for (int j = 0; j < 101; ++j) {
    const double e = -50 * kDeg + j * 100 * kDeg / 100;
    const double to_wall = (kWallX - o.x()) / std::cos(e);
    const double to_lid = (e > 0 ? 2.0 - o.z() : -2.0 - o.z()) / std::sin(e);  // ceiling / floor at +-2 m
    const double expected = std::min(to_wall, std::abs(e) > 1e-9 ? to_lid : INFINITY);
    EXPECT_NEAR(sls.last().ranges[j], expected, 1e-3) << "ray " << j << " at " << e / kDeg << " deg";
  }
}

TEST(Sls, ABoxInTheCamerasSightRemovesExactlyThePointsItHides) {
  // A box off the laser plane (y >= 0.03 m) between the wall and the camera (20 deg to the left of it).
  const Eigen::Vector3d lo(1.0, 0.03, 0.05), hi(1.1, 0.08, 0.5);
  sim::WorldConfig config = testBox();
  sim::MeshEntry occluder;
  occluder.name = "occluder";
  occluder.file = writeStl("sls_occluder", box(lo, hi));
  config.meshes.push_back(occluder);
  SensorWorld w(config, slsUrdf());
  auto& sls = w.sensor<SlsSensor>("sls");
  w.place(sim::poseFromXyzRpy(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));
  w.samples(sls, 1);
  const Eigen::Vector3d at = w.robot().state().pose.translation();
  auto blocked = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {  // segment a-b against the box (slabs)
    double t0 = 0, t1 = 1;
    for (int k = 0; k < 3; ++k) {
      const double d = b[k] - a[k];
      if (std::abs(d) < 1e-12) {
        if (a[k] < lo[k] || a[k] > hi[k])
          return false;
        continue;
      }
      double ta = (lo[k] - a[k]) / d, tb = (hi[k] - a[k]) / d;
      if (ta > tb)
        std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    return t0 <= t1;
  };
  const auto all = expectedPoints(at, 101, 100 * kDeg, 0.151, 0.037, 1e-3, 1.0, 0.3, noBlock);
  const auto want = expectedPoints(at, 101, 100 * kDeg, 0.151, 0.037, 1e-3, 1.0, 0.3, blocked);
  ASSERT_GE(all.size() - want.size(), 5u) << "the box must hide a few points";
  ASSERT_GT(want.size(), 10u);
  expectSamePoints(sls.last().points, want, 1e-3);
}

TEST(Sls, InTurbidWaterTheLineIsSeenOnlyAsFarAsTheStrengthFormulaAllows) {
  // Visibility high: c_g = 4, b_g = 3.4 (WaterOptics). The central ray's strength at wall distance t:
  // S(t) = 0.3 exp(-4 (t + r_c(t))) / t against 1e-3 (1 + 3.4). Find the distance where it crosses the level.
  auto central = [](double t) {
    const Eigen::Vector3d base(kWallX - kLaser.x() - t, 0, 0);
    const double rc = (Eigen::Vector3d(kWallX, 0, 0) - (base + kCamera)).norm();
    return 0.3 * std::exp(-4.0 * (t + rc)) / t;
  };
  const double level = 1e-3 * (1 + 3.4);
  double lo = 0.1, hi = 3.0;  // bisection: central(lo) > level > central(hi)
  for (int i = 0; i < 60; ++i)
    (central(0.5 * (lo + hi)) > level ? lo : hi) = 0.5 * (lo + hi);
  const double reach = lo;
  EXPECT_GT(reach, 0.4);
  EXPECT_LT(reach, 1.2);
  for (double t : {0.85 * reach, 1.15 * reach}) {
    SensorWorld w(testBox("high"), slsUrdf());
    auto& sls = w.sensor<SlsSensor>("sls");
    w.place(sim::poseFromXyzRpy(Eigen::Vector3d(kWallX - kLaser.x() - t, 0, 0), Eigen::Vector3d::Zero()));
    w.samples(sls, 1);
    const Eigen::Vector3d at = w.robot().state().pose.translation();
    const auto want = expectedPoints(at, 101, 100 * kDeg, 4.0, 3.4, 1e-3, 1.0, 0.3, noBlock);
    expectSamePoints(sls.last().points, want, 1e-3);
    if (t < reach)
      EXPECT_GT(sls.last().points.size(), 0u) << "inside the reach";
    else
      EXPECT_EQ(sls.last().points.size(), 0u) << "beyond the reach";
  }
}

TEST(Sls, TheMotorSweepsATriangleWaveBetweenItsLimits) {
  SensorWorld w(
      testBox(),
      slsUrdf({{"motor_speed", "0.5"}, {"motor_min", "-0.4"}, {"motor_max", "0.6"}, {"motor_start", "-0.4"}}));
  auto& sls = w.sensor<SlsSensor>("sls");
  // Start at motor_min, up at 0.5 rad/s: 0.6 at t = 2 s, back to -0.4 at t = 4 s.
  EXPECT_NEAR(sls.motorAngle(0.0), -0.4, 1e-12);
  EXPECT_NEAR(sls.motorAngle(1.0), 0.1, 1e-12);
  EXPECT_NEAR(sls.motorAngle(2.0), 0.6, 1e-12);
  EXPECT_NEAR(sls.motorAngle(3.0), 0.1, 1e-12);
  EXPECT_NEAR(sls.motorAngle(4.5), -0.15, 1e-12);
  EXPECT_DOUBLE_EQ(sls.motorVelocity(1.0), 0.5);
  EXPECT_DOUBLE_EQ(sls.motorVelocity(3.0), -0.5);
  // The head turns with it: after 1 s the laser plane is yawed by 0.1 rad, and joint_states carries it.
  w.place(sim::poseFromXyzRpy(Eigen::Vector3d(0.5, 0, 0), Eigen::Vector3d::Zero()));
  while (w.world->time() < 1.0 - 1e-9)
    w.step();
  EXPECT_NEAR(sls.last().motor_angle, sls.motorAngle(sls.last().time), 1e-12);
  const auto joints = w.suite->movedJoints();
  ASSERT_EQ(joints.size(), 1u);
  EXPECT_EQ(joints[0].name, "T/sls_motor_joint");
  EXPECT_NEAR(joints[0].position, sls.motorAngle(w.world->time()), 1e-12);
  const Eigen::Matrix3d R = sls.headPose(0.1).linear();
  EXPECT_NEAR(std::atan2(R(1, 0), R(0, 0)), 0.1, 1e-12);
}

TEST(Sls, TriangulationNoiseHasTheDepthSigmaOfTheBaseline) {
  SensorWorld w(testBox(), slsUrdf({{"noise", "gaussian"}, {"subpixel_noise", "0.3"}}), 7);
  auto& sls = w.sensor<SlsSensor>("sls");
  const double f = (kWidth / 2.0) / std::tan(kHfov / 2.0);
  const double B = (kCamera - kLaser).norm();
  EXPECT_NEAR(sls.baseline(), B, 1e-9);
  EXPECT_NEAR(sls.depthSigma(2.0), 4.0 * 0.3 / (f * B), 1e-12);
  // Depth errors against the wall over many samples: mean ~0, std within 10 % of sigma_Z.
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int k = 0; k < 40; ++k) {
    w.place(sim::poseFromXyzRpy(Eigen::Vector3d(0.5, 0, 0), Eigen::Vector3d::Zero()));
    w.samples(sls, 1);
    const Eigen::Isometry3d cam = cameraInWorld(w.robot().state().pose.translation());
    for (const auto& p : sls.last().points) {
      // True depth: where the camera ray through p meets the wall.
      const Eigen::Vector3d d = cam.linear() * p.cast<double>().normalized();
      const double s_true = (kWallX - cam.translation().x()) / d.x();
      const double z_true = s_true * p.cast<double>().normalized().z();
      const double err = (p.z() - z_true) / sls.depthSigma(z_true);
      sum += err;
      sum2 += err * err;
      ++n;
    }
  }
  ASSERT_GT(n, 500);
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 4.0 / std::sqrt(n));
  EXPECT_NEAR(sd, 1.0, 0.1);
}

TEST(Sls, BadParametersStopConstructionNamingThem) {
  auto message = [](const std::string& urdf) {
    try {
      SensorWorld w(testBox(), urdf);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message(slsUrdf({{"camera_frame", "T/nowhere"}})).find("camera_frame"), std::string::npos);
  EXPECT_NE(message(slsUrdf({{"fan", "4"}})).find("'fan' = 4"), std::string::npos);
  EXPECT_NE(message(slsUrdf({{"camera_distortion", "0.1 0.2"}})).find("camera_distortion"), std::string::npos);
  EXPECT_NE(message(slsUrdf({{"motor_min", "0.5"}, {"motor_max", "0.2"}})).find("motor_max"), std::string::npos);
  EXPECT_NE(message(slsUrdf({{"lazer", "1"}})).find("lazer"), std::string::npos);
}

}  // namespace
}  // namespace test
}  // namespace unexmin

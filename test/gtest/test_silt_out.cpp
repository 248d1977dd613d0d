// Silt-out, judged by the camera (docs/vision.md "Silt-out"): a robot held 0.3 m above the floor of the 4 m test box,
// its vertical thruster pushing it up (its jet down on the floor), sees the contrast of a painted plate on the floor
// fall; once the thruster stops and the silt has settled (its puffs sunk below the floor) the contrast is back to what
// it was. The same thrust 2 m above the floor raises nothing. The SLS laser line on the floor fades in the silt too.
#include <unexmin/raycast/ray_caster.h>
#include <unexmin/raycast/ray_caster_factory.h>
#include <unexmin/sensors/sensor_suite.h>
#include <unexmin/sensors/vision/camera_sensor.h>
#include <unexmin/sensors/vision/sls_sensor.h>
#include "mesh_fixture.h"
#include "sensor_fixture.h"

#include <gtest/gtest.h>

#include <cmath>

namespace unexmin {
namespace test {
namespace {

using sensors::vision::CameraSensor;

constexpr double kFloor = -2.0;                   // [m] the test box's floor
const Eigen::Vector3d kLens(0.0, 0.0, -0.1);      // [m] base frame: under the hull's centre, looking down
const Eigen::Vector3d kDown(M_PI, 0.0, 0.0);      // optical z = world -z, optical x = world x
const Eigen::Vector3d kLamp(0.1, 0.0, -0.1);      // [m] the LED beside it ...
const Eigen::Vector3d kLampDown(0, M_PI / 2, 0);  // ... its beam (+x) down
constexpr double kThrust = 40.0;                  // [N] thruster 1 (+z, at the centre): jet down

/// The test box, floor albedo 0.1 with a white plate (0.8) under +x, clear water, silt raised by thrusters (settling
/// at 2 cm/s so that the test runs in seconds of sim time).
sim::WorldConfig world() {
  sim::WorldConfig config = sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/test_box.world");
  config.meshes.at(0).albedo = Eigen::Vector3d::Constant(0.1);
  sim::MeshEntry plate;
  plate.name = "plate";
  plate.file = writeStl("plate", box(Eigen::Vector3d(0.0, -0.3, kFloor), Eigen::Vector3d(0.3, 0.3, kFloor + 0.005)));
  plate.albedo = Eigen::Vector3d::Constant(0.8);
  config.meshes.push_back(plate);
  config.sediment.enabled = true;
  config.sediment.settling_speed = 0.02;
  return config;
}

std::string robot() {
  const std::map<std::string, std::string> cam{
      {"width", "101"},     {"height", "81"},   {"hfov", num(M_PI / 3)}, {"noise", "none"},
      {"exposure", "0.25"}, {"clip_far", "10"}, {"lights", "T/lamp"},    {"light_intensity", "0.2 0.2 0.2"}};
  const std::map<std::string, std::string> sls{
      {"camera_frame", "T/cam"}, {"camera_width", "101"}, {"camera_height", "81"}, {"camera_hfov", num(M_PI / 3)},
      {"motor_speed", "0"},      {"noise", "none"},       {"range_max", "3"}};
  return sensorUrdf(SphereSpec(),
                    mountLink("T/cam", kLens, kDown) + mountLink("T/lamp", kLamp, kLampDown) +
                        "<link name='T/head'/><joint name='T/head_joint' type='revolute'><parent link='T/base_link'/>"
                        "<child link='T/head'/><origin xyz='-0.1 0 -0.1' rpy='0 1.5707963 0'/><axis xyz='0 0 1'/>"
                        "<limit lower='-1' upper='1' effort='1' velocity='1'/></joint>\n",
                    sensorXml("cam", "camera", "T/cam", 10.0, cam) + sensorXml("sls", "sls", "T/head", 10.0, sls));
}

struct SiltWorld {
  explicit SiltWorld(const sim::WorldConfig& config) {
    std::map<std::string, sim::RobotDescription> d;
    d.emplace(config.robots.at(0).name, sim::parseRobotDescription(robot(), "(test robot)"));
    world = std::make_unique<sim::World>(config, d, 1, 0.002, 1);
    caster = raycast::makeRayCaster("embree", *world);
    caster->update();
    static const sensors::SensorFactory factory = [] {
      sensors::SensorFactory f = coreModels();
      f.add<CameraSensor>("camera");
      return f;
    }();
    suite = std::make_unique<sensors::SensorSuite>(*world, world->robot(0), caster.get(), factory,
                                                   sensors::SensorSelection(), true);
    camera().setDemand([this] { return wanted; });
  }
  CameraSensor& camera() { return dynamic_cast<CameraSensor&>(*suite->find("cam")); }
  const sensors::vision::SlsSensor& sls() {
    return dynamic_cast<const sensors::vision::SlsSensor&>(*suite->find("sls"));
  }
  /// `seconds` of sim time with the robot held at `base` (world, level), thruster 1 at `thrust` [N].
  void run(double seconds, const Eigen::Vector3d& base, double thrust) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = base;
    const auto steps = static_cast<long>(std::lround(seconds / world->dt()));
    for (long i = 0; i < steps; ++i) {
      world->robot(0).thruster(1).setCommand(thrust, world->time());
      world->robot(0).setPose(pose);
      world->step();
      world->robot(0).setPose(pose);
      caster->update();
      suite->update();
    }
  }
  /// The next rendered frame's contrast of the plate against the floor: the step between them in the 8-bit image, as
  /// a fraction of full scale (green, means of 5 x 5 pixels 20 px either side of the centre), the robot held at
  /// `base`. (A ratio such as (B - D) / (B + D) would not see the silt: it dims both alike, and near black the
  /// rounding to 8 bits makes the ratio jump.)
  double contrast(const Eigen::Vector3d& base) {
    wanted = true;
    const std::uint64_t target = camera().sampleCount() + 1;
    while (camera().sampleCount() < target)
      run(world->dt(), base, 0.0);
    wanted = false;
    const auto& f = camera().last();
    EXPECT_TRUE(f.rendered);
    double bright = 0, dark = 0;
    for (int dv = -2; dv <= 2; ++dv)
      for (int du = -2; du <= 2; ++du) {
        bright += f.rgb[3 * ((40 + dv) * 101 + 70 + du) + 1];
        dark += f.rgb[3 * ((40 + dv) * 101 + 30 + du) + 1];
        EXPECT_LT(f.rgb[3 * ((40 + dv) * 101 + 70 + du) + 1], 250);  // not saturated
      }
    return (bright - dark) / (25.0 * 255.0);
  }

  bool wanted = false;
  std::unique_ptr<sim::World> world;
  std::unique_ptr<raycast::RayCaster> caster;
  std::unique_ptr<sensors::SensorSuite> suite;
};

TEST(SiltOut, ThrustNearTheFloorDrownsAPlatesContrastUntilTheSiltSettles) {
  SiltWorld w(world());
  const Eigen::Vector3d low(0.0, 0.0, kFloor + 0.3 - kLens.z());  // the lens 0.3 m above the floor
  const double clear = w.contrast(low);
  EXPECT_GT(clear, 0.3);  // a clear step of more than 75 levels
  const std::size_t points_clear = w.sls().last().points.size();
  ASSERT_GT(points_clear, 10u);

  w.run(10.0, low, kThrust);
  ASSERT_FALSE(w.world->sediment().empty());
  const double silted = w.contrast(low);
  ASSERT_NE(w.camera().silt(), nullptr);
  EXPECT_LT(silted, 0.05 * clear);
  EXPECT_LT(w.sls().last().points.size(), points_clear);  // the laser line fades where the silt is thick

  // The thruster stops: the contrast comes back as the silt sinks, and is the clear water's once it has gone.
  double last = silted;
  int frames = 0;
  while (!w.world->sediment().empty() && frames < 60) {
    w.run(5.0, low, 0.0);
    const double c = w.contrast(low);
    EXPECT_GE(c, last) << "at t = " << w.world->time() << " s";
    last = c;
    ++frames;
  }
  ASSERT_TRUE(w.world->sediment().empty()) << "still silt after " << w.world->time() << " s";
  // Settled within minutes: (0.3 m + 3 sigma) / 2 cm/s, sigma about 0.35 m (merged puffs, diffusion).
  EXPECT_LT(w.world->time(), 10.0 + 120.0);
  EXPECT_NEAR(w.contrast(low), clear, 1e-6);
  EXPECT_EQ(w.sls().last().points.size(), points_clear);
}

TEST(SiltOut, TheSameThrustInMidWaterRaisesNothing) {
  SiltWorld w(world());
  const Eigen::Vector3d mid(0.0, 0.0, 0.0);  // 2 m from the floor and the walls, the jet reaches 1 m
  const double before = w.contrast(mid);
  w.run(10.0, mid, kThrust);
  EXPECT_TRUE(w.world->sediment().empty());
  EXPECT_EQ(w.camera().silt(), nullptr);
  EXPECT_EQ(w.contrast(mid), before);
}

TEST(SiltOut, SedimentOffRaisesNothingNearTheFloor) {
  sim::WorldConfig config = world();
  config.sediment.enabled = false;
  SiltWorld w(config);
  const Eigen::Vector3d low(0.0, 0.0, kFloor + 0.3 - kLens.z());
  w.run(5.0, low, kThrust);
  EXPECT_TRUE(w.world->sediment().empty());
}

}  // namespace
}  // namespace test
}  // namespace unexmin

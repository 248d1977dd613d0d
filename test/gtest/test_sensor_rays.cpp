// Sensors on the world's ray caster (cpp/unexmin/raycast, built by the simulator from the world file): the
// DVL's beam ranges in the tank through Embree equal the analytic floor distances and those through the
// Bullet back end within 2 mm; a sensor's own hull is invisible to it, another robot's is seen where it is now.
#include <unexmin/raycast/ray_caster_factory.h>
#include <unexmin/sensors/dvl_sensor.h>
#include <unexmin/sensors/sonar/m3_sensor.h>
#include "sonar_fixture.h"

#include <gtest/gtest.h>

#include <cmath>

namespace unexmin {
namespace test {
namespace {

constexpr double kBeamAngle = 25.0 * M_PI / 180;

std::string dvlUrdf() {
  std::map<std::string, std::string> p = {{"noise", "none"}, {"beam_angle", num(kBeamAngle)}, {"beam_azimuth_0", "0"}};
  return sensorUrdf(undampedSphere(), dvlLinks(kBeamAngle, 0.0), sensorXml("dvl", "dvl", "T/dvl_link", 500.0, p));
}

TEST(SensorRays, DvlRangesThroughEmbreeEqualTheAnalyticFloorAndBulletWithinTwoMillimetres) {
  const sim::WorldConfig tank = sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/tank.world");
  SensorWorld embree(tank, dvlUrdf(), 1, 0.002, "embree");
  SensorWorld bullet(tank, dvlUrdf(), 1, 0.002, "bullet");
  EXPECT_STREQ(embree.caster->name(), "embree");
  EXPECT_STREQ(bullet.caster->name(), "bullet");
  for (const Eigen::Vector3d& rpy :
       {Eigen::Vector3d(0.12, -0.08, 0.6), Eigen::Vector3d(-0.2, 0.1, 2.0), Eigen::Vector3d(0.0, 0.0, -1.0)}) {
    const Eigen::Isometry3d pose = sim::poseFromXyzRpy(Eigen::Vector3d(-1.5, 1.0, -1.2), rpy);
    embree.place(pose);
    bullet.place(pose);
    embree.step();
    bullet.step();
    const auto& e = embree.sensor<sensors::DvlSensor>("dvl").last();
    const auto& b = bullet.sensor<sensors::DvlSensor>("dvl").last();
    const Eigen::Isometry3d dvl =
        embree.robot().state().pose * sim::poseFromXyzRpy(Eigen::Vector3d(0, 0, -0.3), Eigen::Vector3d(M_PI, 0, 0));
    for (int i = 0; i < 4; ++i) {
      const double c = i * M_PI / 2;
      const Eigen::Vector3d d =
          dvl.linear() *
          Eigen::Vector3d(std::sin(kBeamAngle) * std::cos(c), std::sin(kBeamAngle) * std::sin(c), std::cos(kBeamAngle));
      const double floor = (dvl.translation().z() + 3.0) / -d.z();  // tank floor at z = -3
      ASSERT_TRUE(e.beams[i].valid && b.beams[i].valid);
      EXPECT_NEAR(e.beams[i].range, floor, 0.002) << "beam " << i;
      EXPECT_NEAR(e.beams[i].range, b.beams[i].range, 0.002) << "beam " << i;
    }
  }
}

TEST(SensorRays, OwnHullIsInvisibleOtherRobotsAreSeenWhereTheyAreNow) {
  // Two test spheres (radius 0.3) 2 m apart on x in open water; T carries an M3 looking along +x whose
  // middle beams (k = 127, 128 of 256 over 120 deg: +-0.24 deg) meet U's near side.
  std::map<std::string, std::string> p = {{"noise", "none"}, {"rays_per_beam", "1"}, {"fov_v", "0.001"}};
  const std::string t_urdf =
      sensorUrdf(SphereSpec(), mountLink("T/m3_link", Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()),
                 sensorXml("m3", "m3", "T/m3_link", 500.0, p));
  sim::WorldConfig config = openWater(SphereSpec(), Eigen::Vector3d(0, 0, -50));
  sim::RobotSpawn other = config.robots[0];
  other.name = "U";
  other.pose.translation() = Eigen::Vector3d(2, 0, -50);
  config.robots.push_back(other);
  std::map<std::string, sim::RobotDescription> d;
  d.emplace("T", sim::parseRobotDescription(t_urdf, "T"));
  d.emplace("U", sim::parseRobotDescription(sphereUrdf(SphereSpec()), "U"));
  sim::World world(config, d, -1, 0.002, 1);
  const auto caster = raycast::makeRayCaster("embree", world);
  sensors::SensorSuite suite(world, world.robot(0), caster.get(), coreModels());
  const auto& m3 = dynamic_cast<const sensors::sonar::M3Sensor&>(*suite.find("m3"));
  auto step = [&] {
    world.robot(0).setPose(sim::poseFromXyzRpy(Eigen::Vector3d(0, 0, -50), Eigen::Vector3d::Zero()));
    world.step();
    caster->update();
    suite.update();
  };
  step();
  // Beam k at angle a: the ray from the centre meets the sphere of radius r at distance D = 2 m ahead at
  // D cos a - sqrt(r^2 - D^2 sin^2 a).
  auto expected = [](double a, double D) {
    return D * std::cos(a) - std::sqrt(0.09 - D * D * std::sin(a) * std::sin(a));
  };
  const double a = m3.angleIncrement() / 2;
  const double x_u = world.robot(1).state().pose.translation().x();
  EXPECT_NEAR(m3.last().ranges[127], expected(a, x_u), 0.01);
  EXPECT_NEAR(m3.last().ranges[128], expected(a, x_u), 0.01);
  // U moves 1 m away: the next sample sees it there.
  world.robot(1).setPose(sim::poseFromXyzRpy(Eigen::Vector3d(3, 0, -50), Eigen::Vector3d::Zero()));
  step();
  EXPECT_NEAR(m3.last().ranges[128], expected(a, world.robot(1).state().pose.translation().x()), 0.01);
  EXPECT_GT(m3.last().ranges[128], 2.5);
  // An unknown back end is refused with the accepted ones named.
  try {
    raycast::makeRayCaster("optix", world);
    ADD_FAILURE() << "expected RayCasterError";
  } catch (const RayCasterError& e) {
    EXPECT_NE(std::string(e.what()).find("embree"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace test
}  // namespace unexmin

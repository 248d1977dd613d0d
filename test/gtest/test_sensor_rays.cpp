// The sensors' ray interface over the sonar ray caster (cpp/sonar/sensor_rays.h, the simulator's default):
// the DVL's beam ranges in the tank through Embree equal the analytic floor distances and the Bullet
// caster's within 2 mm; the robot's own hull is invisible, another robot's is seen; one caster per world.
#include "sensors/dvl_sensor.h"
#include "sonar_fixture.h"

#include <gtest/gtest.h>

#include <cmath>

namespace unexmin {
namespace test {
namespace {

constexpr double kBeamAngle = 25.0 * M_PI / 180;

std::string dvlUrdf()
{
  std::map<std::string, std::string> p = {{"noise", "none"}, {"beam_angle", num(kBeamAngle)}, {"beam_azimuth_0", "0"}};
  return sensorUrdf(undampedSphere(), dvlLinks(kBeamAngle, 0.0), sensorXml("dvl", "dvl", "T/dvl_link", 500.0, p));
}

TEST(SensorRays, DvlRangesThroughEmbreeEqualTheAnalyticFloorAndBulletWithinTwoMillimetres)
{
  const sim::WorldConfig tank = sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/tank.world");
  SonarWorld embree(tank, dvlUrdf());
  SensorWorld bullet(tank, dvlUrdf());
  for (const Eigen::Vector3d& rpy : {Eigen::Vector3d(0.12, -0.08, 0.6), Eigen::Vector3d(-0.2, 0.1, 2.0),
                                    Eigen::Vector3d(0.0, 0.0, -1.0)}) {
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
      const Eigen::Vector3d d = dvl.linear() * Eigen::Vector3d(std::sin(kBeamAngle) * std::cos(c),
                                                               std::sin(kBeamAngle) * std::sin(c), std::cos(kBeamAngle));
      const double floor = (dvl.translation().z() + 3.0) / -d.z();  // tank floor at z = -3
      ASSERT_TRUE(e.beams[i].valid && b.beams[i].valid);
      EXPECT_NEAR(e.beams[i].range, floor, 0.002) << "beam " << i;
      EXPECT_NEAR(e.beams[i].range, b.beams[i].range, 0.002) << "beam " << i;
    }
  }
}

TEST(SensorRays, OwnHullIsInvisibleOtherRobotsAreSeenAndTheCasterIsShared)
{
  // Two test spheres (radius 0.3) 2 m apart on x in open water.
  sim::WorldConfig config = openWater(SphereSpec(), Eigen::Vector3d(0, 0, -50));
  sim::RobotSpawn other = config.robots[0];
  other.name = "U";
  other.pose.translation() = Eigen::Vector3d(2, 0, -50);
  config.robots.push_back(other);
  std::map<std::string, sim::RobotDescription> d;
  d.emplace("T", sim::parseRobotDescription(sphereUrdf(SphereSpec()), "T"));
  d.emplace("U", sim::parseRobotDescription(sphereUrdf(SphereSpec()), "U"));
  sim::World world(config, d, -1, 0.002, 1);
  const auto t = sonar::SensorRays::forRobot(world, world.robot(0));
  const auto u = sonar::SensorRays::forRobot(world, world.robot(1));
  EXPECT_EQ(&t->caster(), &u->caster());
  std::vector<sensors::Ray> rays(1);
  rays[0].origin = Eigen::Vector3d(0, 0, -50);
  rays[0].direction = Eigen::Vector3d(1, 0, 0);
  rays[0].max_range = 10.0;
  std::vector<sensors::RayHit> hits;
  t->cast(rays, hits);
  ASSERT_TRUE(hits[0].hit);
  EXPECT_NEAR(hits[0].range, 2.0 - 0.3, 1e-5);  // U's near side, not T's own hull
  EXPECT_NEAR(hits[0].normal.x(), -1.0, 1e-5);
  // U moves: the next cast sees it where it is now.
  world.robot(1).setPose(sim::poseFromXyzRpy(Eigen::Vector3d(3, 0, -50), Eigen::Vector3d::Zero()));
  t->cast(rays, hits);
  EXPECT_NEAR(hits[0].range, 3.0 - 0.3, 1e-5);
  EXPECT_THROW(sonar::SensorRays::forRobot(world, world.robot(0), "optix"), sonar::RayCasterError);
}

}  // namespace
}  // namespace test
}  // namespace unexmin

// Contacts with world meshes are real (Bullet) and do not tunnel at the robot's top speeds.
#include "sphere_fixture.h"

#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

using unexmin::test::SphereSpec;

namespace {

/// The shipped 4 m closed box, with the test sphere "T" at `xyz` in place of the shipped robots.
std::unique_ptr<unexmin::sim::World> boxWorld(const SphereSpec& s, const Eigen::Vector3d& xyz) {
  auto config = unexmin::sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/test_box.world");
  config.robots.clear();
  unexmin::sim::RobotSpawn spawn;
  spawn.name = "T";
  spawn.pose.translation() = xyz;
  config.robots.push_back(spawn);
  return unexmin::test::makeWorld(config, s);
}

}  // namespace

TEST(Contacts, RobotDrivenIntoAWallAtTwoMetresPerSecondStopsAtTheWall) {
  SphereSpec s;
  const double half = 2.0;  // the box is 4 m on a side, centred on the origin
  for (double speed : {2.0, 5.0}) {
    auto world = boxWorld(s, Eigen::Vector3d::Zero());
    auto& robot = world->robot(0);
    robot.body()->setLinearVelocity(btVector3(static_cast<btScalar>(speed), 0, 0));
    ASSERT_TRUE(robot.thruster(0).setCommand(s.thrust_limit, 0.0));  // keep pushing into the wall
    double max_x = -1e9;
    for (int i = 0; i < 2500; ++i) {  // 5 s
      world->step();
      max_x = std::max(max_x, robot.state().pose.translation().x());
    }
    // Never through the wall; penetration no deeper than a few millimetres.
    EXPECT_LT(max_x, half - s.radius + 0.01) << "speed " << speed;
    // Resting against the wall under thrust.
    EXPECT_NEAR(robot.state().pose.translation().x(), half - s.radius, 0.02) << "speed " << speed;
    EXPECT_LT(std::abs(robot.state().linear_velocity.x()), 0.05);
  }
}

TEST(Contacts, TwoRobotsCollideInsteadOfPassingThrough) {
  SphereSpec s;
  auto config = unexmin::sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/test_box.world");
  config.robots.clear();
  for (double x : {-0.8, 0.8}) {
    unexmin::sim::RobotSpawn spawn;
    spawn.name = x < 0 ? "A" : "B";
    spawn.pose.translation() = Eigen::Vector3d(x, 0, 0);
    config.robots.push_back(spawn);
  }
  std::map<std::string, unexmin::sim::RobotDescription> d;
  for (const char* n : {"A", "B"})
    d.emplace(n, unexmin::sim::parseRobotDescription(unexmin::test::sphereUrdf(s), n));
  unexmin::sim::World world(config, d, 2, 0.002, 1);
  world.robot(0).body()->setLinearVelocity(btVector3(2, 0, 0));
  world.robot(1).body()->setLinearVelocity(btVector3(-2, 0, 0));
  double min_gap = 1e9;
  for (int i = 0; i < 1000; ++i) {
    world.step();
    const double gap = (world.robot(1).state().pose.translation() - world.robot(0).state().pose.translation()).x();
    min_gap = std::min(min_gap, gap);
  }
  EXPECT_GT(min_gap, 2.0 * s.radius - 0.02);
  EXPECT_LT(world.robot(0).state().pose.translation().x(), world.robot(1).state().pose.translation().x());
}

// Spawn poses of the robots a world file does not list (sim/spawn_placement.h): the lattice rule in a box room of
// closed-form clearance, its failure when the room is too small, and the tank with a team larger than its list.
#include "expect_error.h"
#include "xacro_fixture.h"

#include <unexmin/sim/spawn_placement.h>
#include <unexmin/sim/world.h>
#include <unexmin/sim/world_config.h>

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace {

using unexmin::sim::kSpawnMargin;
using unexmin::sim::RobotSpawn;
using unexmin::sim::SpawnProbe;

/// A closed box room |x|, |y|, |z + half| <= half [m] (its top at z = 0): a sphere is clear when it fits inside, and
/// every segment between two points inside stays inside (the room is convex).
SpawnProbe boxRoom(double half) {
  auto inside = [half](const Eigen::Vector3d& p, double radius) {
    return std::abs(p.x()) + radius <= half && std::abs(p.y()) + radius <= half &&
           std::abs(p.z() + half) + radius <= half;
  };
  return {inside,
          [inside](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return inside(a, 0.0) && inside(b, 0.0); }};
}

RobotSpawn spawnAt(const std::string& name, const Eigen::Vector3d& xyz, double yaw, bool placed) {
  RobotSpawn s;
  s.name = name;
  s.pose = unexmin::sim::poseFromXyzRpy(xyz, Eigen::Vector3d(0, 0, yaw));
  s.placed = placed;
  return s;
}

TEST(SpawnPlacement, ExtrasTakeTheNearestClearLatticePointsAlongTheAnchorsHeadingFirst) {
  const Eigen::Vector3d anchor(0, 0, -5);
  const double r = 0.5, step = 2 * r + kSpawnMargin;  // 1.3 m
  std::vector<RobotSpawn> spawns{spawnAt("A_1", anchor, M_PI / 2, true), spawnAt("A_2", anchor, M_PI / 2, false),
                                 spawnAt("A_3", anchor, M_PI / 2, false), spawnAt("A_4", anchor, M_PI / 2, false)};
  unexmin::sim::placeSpawns(spawns, {r, r, r, r}, 4, 0.0, boxRoom(5.0), "room.world");
  // heading +y (yaw 90 deg): +x of the robot is world +y, +y of the robot is world -x
  EXPECT_LT((spawns[1].pose.translation() - (anchor + Eigen::Vector3d(0, step, 0))).norm(), 1e-12);
  EXPECT_LT((spawns[2].pose.translation() - (anchor + Eigen::Vector3d(0, -step, 0))).norm(), 1e-12);
  EXPECT_LT((spawns[3].pose.translation() - (anchor + Eigen::Vector3d(-step, 0, 0))).norm(), 1e-12);
  EXPECT_TRUE(spawns[3].pose.linear().isApprox(spawns[0].pose.linear(), 1e-12));
  for (const auto& s : spawns)
    EXPECT_TRUE(s.placed);
}

TEST(SpawnPlacement, AWallTheSurfaceAndALargerNeighbourMoveAnExtraOn) {
  // The anchor 1 m under the surface and 1 m from the room's +x wall: +x is walled, up is the surface.
  const Eigen::Vector3d anchor(4.0, 0, -1);
  const double r = 0.3, step = 2 * r + kSpawnMargin;  // 0.9 m
  std::vector<RobotSpawn> spawns{spawnAt("B_1", anchor, 0, true), spawnAt("B_2", anchor, 0, false),
                                 spawnAt("C_1", anchor + Eigen::Vector3d(-1.2, 0, 0), 0, true)};
  unexmin::sim::placeSpawns(spawns, {r, r, 0.5}, 3, 0.0, boxRoom(5.0), "room.world");
  // +x: 4.9 + 0.6 > 5 (wall); -x: 0.3 m from C_1, under 0.3 + 0.5 + 0.3 (neighbour); +y: 1.5 m from C_1, clear.
  EXPECT_LT((spawns[1].pose.translation() - (anchor + Eigen::Vector3d(0, step, 0))).norm(), 1e-12);
}

TEST(SpawnPlacement, ARoomTooSmallStopsWithOneLineNamingTheRobot) {
  std::vector<RobotSpawn> spawns{spawnAt("U_1", Eigen::Vector3d(0, 0, -1.5), 0, true),
                                 spawnAt("U_2", Eigen::Vector3d(0, 0, -1.5), 0, false)};
  const std::string message = unexmin::test::thrownMessage<unexmin::ConfigError>(
      [&] { unexmin::sim::placeSpawns(spawns, {0.5, 0.5}, 2, 0.0, boxRoom(1.5), "small.world"); });
  EXPECT_EQ(message.rfind("small.world: no room for robot 'U_2' (hull radius 0.5 m)", 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
}

TEST(SpawnPlacement, SelectRobotsAnchorsANumberedNameAtItsPrefixAndRefusesOthers) {
  unexmin::sim::WorldConfig config;
  config.file = "team.world";
  config.robots = {spawnAt("ROV_1", Eigen::Vector3d(1, 2, -3), 0, true),
                   spawnAt("UX_1", Eigen::Vector3d(0, 0, -1), 0, true)};
  unexmin::sim::selectRobots(config, {"UX_1", "ROV_1", "ROV_2"});
  ASSERT_EQ(config.robots.size(), 3u);
  EXPECT_EQ(config.robots[2].name, "ROV_2");
  EXPECT_FALSE(config.robots[2].placed);
  EXPECT_EQ(config.robots[2].pose.translation(), Eigen::Vector3d(1, 2, -3));
  for (const std::string bad : {"AUV_2", "ROV_0", "ROV_x", "ROV"}) {
    auto copy = config;
    const std::string message =
        unexmin::test::thrownMessage<unexmin::ConfigError>([&] { unexmin::sim::selectRobots(copy, {bad}); });
    EXPECT_TRUE(unexmin::test::contains(message, "team.world: no robot '" + bad + "' in 'robots'")) << message;
  }
}

/// The descriptions of `team` (names <prefix>_<k>), each type expanded once (as <prefix>_1) and renamed.
std::map<std::string, unexmin::sim::RobotDescription> teamDescriptions(const std::vector<std::string>& team) {
  const std::map<std::string, std::string> files{
      {"UX", "ux1.urdf.xacro"}, {"ROV", "bluerov2_heavy.urdf.xacro"}, {"AUV", "remus100.urdf.xacro"}};
  std::map<std::string, std::string> xml;
  std::map<std::string, unexmin::sim::RobotDescription> descriptions;
  for (const auto& name : team) {
    const std::string prefix = name.substr(0, name.find('_'));
    if (!xml.count(prefix))
      xml[prefix] = unexmin::test::expand(files.at(prefix), "name:=" + prefix + "_1");
    std::string text = xml[prefix];
    for (std::size_t at = 0; (at = text.find(prefix + "_1", at)) != std::string::npos; at += name.size())
      text.replace(at, prefix.size() + 2, name);
    descriptions.emplace(name, unexmin::sim::parseRobotDescription(text, name));
  }
  return descriptions;
}

TEST(SpawnPlacement, TheTankHoldsATeamLargerThanItsListEachHullClearOfTheWallsAndTheOthers) {
  const std::string file = std::string(UNEXMIN_SOURCE_DIR) + "/worlds/tank_team.world";
  const std::vector<std::string> team{"UX_1", "ROV_1", "ROV_2", "AUV_1", "UX_2", "ROV_3"};
  unexmin::sim::WorldConfig config = unexmin::sim::loadWorldConfig(file);
  unexmin::sim::selectRobots(config, team);
  auto descriptions = teamDescriptions({"UX_1", "ROV_1", "ROV_2", "AUV_1", "UX_2", "ROV_3", "AUV_2"});
  unexmin::sim::World world(config, descriptions, static_cast<int>(team.size()), 0.002, 1);
  ASSERT_EQ(world.robotCount(), team.size());
  // The tank's walls: its mesh's bounding box (a box-shaped tank).
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e9f), hi = -lo;
  for (const auto& v : world.mesh(0).vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  for (std::size_t i = 0; i < team.size(); ++i) {
    const Eigen::Vector3d p = world.robot(i).state().pose.translation();
    const double r = unexmin::sim::hullRadius(descriptions.at(team[i]));
    EXPECT_TRUE(world.config().robots[i].placed) << team[i];
    // the placed ones (ROV_2, UX_2, ROV_3) with the margin; the world file's own with their hull
    const double clear = r + (team[i].back() == '1' ? 0.0 : kSpawnMargin) - 1e-6;
    for (int a = 0; a < 2; ++a)  // the side walls; the top is the surface at z = 0
      EXPECT_GE(std::min(p[a] - lo[a], hi[a] - p[a]), clear) << team[i] << " axis " << a;
    EXPECT_GE(p.z() - lo.z(), clear) << team[i];
    EXPECT_LE(p.z() + clear, 0.0) << team[i];
    for (std::size_t j = 0; j < i; ++j) {
      const double rj = unexmin::sim::hullRadius(descriptions.at(team[j]));
      EXPECT_GE((world.robot(j).state().pose.translation() - p).norm(), r + rj) << team[i] << " / " << team[j];
    }
  }
  // The listed robots keep the world file's poses.
  EXPECT_LT((world.robot(1).state().pose.translation() - Eigen::Vector3d(-2.0, -1.0, -1.0)).norm(), 1e-9);
  EXPECT_LT((world.robot(3).state().pose.translation() - Eigen::Vector3d(-2.0, 1.0, -1.0)).norm(), 1e-9);
  // A second REMUS 100 (hull radius 0.72 m, a 1.75 m lattice) finds no room in the 3 m deep, 4.1 m wide tank.
  std::vector<std::string> more = team;
  more.push_back("AUV_2");
  unexmin::sim::WorldConfig full = unexmin::sim::loadWorldConfig(file);
  unexmin::sim::selectRobots(full, more);
  const std::string message = unexmin::test::thrownMessage<unexmin::ConfigError>(
      [&] { unexmin::sim::World(full, descriptions, static_cast<int>(more.size()), 0.002, 1); });
  EXPECT_EQ(message.rfind(file + ": no room for robot 'AUV_2' (hull radius 0.72", 0), 0u) << message;
}

}  // namespace

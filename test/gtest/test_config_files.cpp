// Malformed world and robot files stop start-up with one clear message naming the file and problem.
#include <unexmin/sim/robot_description.h>
#include <unexmin/sim/world.h>
#include "sphere_fixture.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>

using unexmin::ConfigError;

namespace {

std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = unexmin::test::testTempDir() + name;
  std::ofstream(path) << text;
  return path;
}

/// The message of the ConfigError thrown by f ("" if none).
template <typename F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

const char* kGoodWorld = R"(
name: w
gravity: 9.81
water: {density: 1000.0, surface_z: 0.0}
robots:
  - {name: UX_1, xyz: [0, 0, -1], rpy: [0, 0, 0]}
)";

}  // namespace

TEST(WorldFile, ShippedWorldsLoad) {
  for (const char* name : {"tank.world", "tank_target.world", "test_box.world"}) {
    const auto w = unexmin::sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/" + name);
    EXPECT_FALSE(w.robots.empty()) << name;
    EXPECT_FALSE(w.meshes.empty()) << name;
    for (const auto& m : w.meshes)
      EXPECT_GT(unexmin::sim::loadMesh(m).triangleCount(), 0u) << m.file;
  }
}

TEST(WorldFile, GoodMinimalWorldLoads) {
  const auto w = unexmin::sim::loadWorldConfig(writeTemp("good.world", kGoodWorld));
  EXPECT_EQ(w.robots.size(), 1u);
  EXPECT_DOUBLE_EQ(w.water_density, 1000.0);
}

TEST(WorldFile, DefectsAreNamed) {
  struct Case {
    std::string text;
    std::string expected;  // regex the message must contain
  };
  const std::vector<Case> cases = {
      {"name: [unclosed", "not valid YAML"},
      {"- just a list", "must be a YAML map"},
      {"name: w\nrobots: []\n", "'robots' must be a non-empty list"},
      {"name: w\ngravity: fast\nrobots: [{name: A}]\n", "'gravity' must be a number"},
      {"name: w\ngravity: -1\nrobots: [{name: A}]\n", "'gravity' must be > 0"},
      {"name: w\nwater: {density: 0}\nrobots: [{name: A}]\n", "'water.density' must be > 0"},
      {"name: w\nrobots: [{name: A, xyz: [1, 2]}]\n", "'robots\\[0\\]\\.xyz' must be a list of 3 numbers"},
      {"name: w\nrobots: [{name: A}, {name: A}]\n", "robot name 'A' appears twice"},
      {"name: w\nmeshes: [{name: m, file: nowhere.stl}]\nrobots: [{name: A}]\n",
       "meshes\\[0\\]\\.file.*does not exist"},
      {"name: w\ncurrent: {speed: {mean: 1, min: 0, max: 0.5}}\nrobots: [{name: A}]\n", "current\\.speed"},
      {"name: w\nvisibility: {level: foggy}\nrobots: [{name: A}]\n", "expected none\\|low\\|medium\\|high"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string path = writeTemp("bad" + std::to_string(i) + ".world", cases[i].text);
    const std::string msg = errorOf([&] { unexmin::sim::loadWorldConfig(path); });
    EXPECT_TRUE(std::regex_search(msg, std::regex(cases[i].expected))) << "case " << i << ": '" << msg << "'";
    EXPECT_EQ(msg.rfind(path, 0), 0u) << "message must start with the file name: '" << msg << "'";
  }
  const std::string missing = errorOf([] { unexmin::sim::loadWorldConfig("/nonexistent/x.world"); });
  EXPECT_NE(missing.find("/nonexistent/x.world: cannot open"), std::string::npos) << missing;
}

TEST(WorldFile, MeshFilesMustStayInsideTheWorldFilesFolder) {
  // A world file names its meshes relative to its own folder (docs/worlds.md, "Paths"): an absolute path or a
  // path climbing out with '..' is refused, naming the file, the key and the path, before anything is read.
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(unexmin::test::testTempDir()) / "paths" / "world";
  fs::create_directories(dir / "meshes");
  const std::string box = std::string(UNEXMIN_SOURCE_DIR) + "/worlds/meshes/test_box.stl";
  fs::copy_file(box, dir / "meshes" / "box.stl", fs::copy_options::overwrite_existing);
  fs::copy_file(box, dir.parent_path() / "outside.stl", fs::copy_options::overwrite_existing);
  auto world = [&](const std::string& name, const std::string& file) {
    const std::string path = (dir / name).string();
    std::ofstream(path) << "name: w\nmeshes:\n  - {name: m, file: '" << file << "'}\nrobots: [{name: A}]\n";
    return path;
  };
  // Inside: plain, with '.' and with a '..' that stays inside; resolved against the world file's folder.
  for (const std::string file : {"meshes/box.stl", "./meshes/box.stl", "meshes/../meshes/box.stl"}) {
    const auto w = unexmin::sim::loadWorldConfig(world("inside.world", file));
    ASSERT_EQ(w.meshes.size(), 1u) << file;
    EXPECT_EQ(w.meshes[0].file, (dir / "meshes" / "box.stl").string()) << file;
    EXPECT_GT(unexmin::sim::loadMesh(w.meshes[0]).triangleCount(), 0u) << file;
  }
  // Outside: each file exists (or is a real system file), so only the rule can refuse it.
  struct Case {
    std::string file, expected;
  };
  const std::vector<Case> cases = {
      {(dir.parent_path() / "outside.stl").string(), "is an absolute path"},
      {"/etc/passwd", "is an absolute path"},
      {"../outside.stl", "is not inside the world file's folder"},
      {"meshes/../../outside.stl", "is not inside the world file's folder"},
      {"meshes/../../../../../../../../etc/passwd", "is not inside the world file's folder"},
      {".", "is not inside the world file's folder"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string path = world("outside" + std::to_string(i) + ".world", cases[i].file);
    const std::string msg = errorOf([&] { unexmin::sim::loadWorldConfig(path); });
    EXPECT_EQ(msg.rfind(path + ": 'meshes[0].file' " + cases[i].file + " " + cases[i].expected, 0), 0u)
        << "case " << i << ": '" << msg << "'";
  }
}

TEST(WorldFile, TooManyRobotsIsAnError) {
  unexmin::test::SphereSpec s;
  const auto config = unexmin::test::openWater(s);
  std::map<std::string, unexmin::sim::RobotDescription> d;
  d.emplace("T", unexmin::sim::parseRobotDescription(unexmin::test::sphereUrdf(s), "t"));
  const std::string msg = errorOf([&] { unexmin::sim::World(config, d, 2, 0.002, 0); });
  EXPECT_NE(msg.find("2 robots asked for"), std::string::npos) << msg;
}

TEST(RobotFile, DefectsAreNamed) {
  unexmin::test::SphereSpec s;
  const std::string good = unexmin::test::sphereUrdf(s);
  ASSERT_NO_THROW(unexmin::sim::parseRobotDescription(good, "good"));
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string x = good;
    const auto pos = x.find(from);
    if (pos == std::string::npos)
      throw std::logic_error("test fixture lacks: " + from);
    return x.replace(pos, from.size(), to);
  };
  struct Case {
    std::string xml;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"<robot", "not valid XML"},
      {"<nothing/>", "no <robot> element"},
      {std::regex_replace(good, std::regex("unexmin>"), "other>"), "no <unexmin> element"},
      {replaced("<mass value='", "<mass value='x"), "hydrodynamics>/mass@value: '.*' is not a finite number"},
      {replaced("<volume value='", "<volume value='-"), "volume"},
      {replaced("type='zero_order'", "type='second_order'"), "thruster id=0.*second_order"},
      {replaced("joint='T/t1_joint'", "joint='T/nope'"), "joint 'T/nope' does not exist"},
      {replaced("<child link='T/t0'/>", "<child link='T/ghost'/>"), "child link 'T/ghost' does not exist"},
      {replaced("<thrust min='-100'", "<thrust min='200'"), "thruster id=0"},
      {replaced("speed='", "speed='-"), "<pendulum>.*speed"},
      {replaced("thruster id='1'", "thruster id='3'"), "thruster ids must be 0..1"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string msg =
        errorOf([&] { unexmin::sim::parseRobotDescription(cases[i].xml, "/UX_1/robot_description"); });
    EXPECT_TRUE(std::regex_search(msg, std::regex(cases[i].expected))) << "case " << i << ": '" << msg << "'";
    EXPECT_EQ(msg.rfind("/UX_1/robot_description: ", 0), 0u) << msg;
  }
}

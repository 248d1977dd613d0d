// The world-file schema (config/world_schema.yaml, docs/worlds.md): an unknown key at any level stops loading
// with one line naming the file, the key's path, the accepted keys and the nearest one; every shipped world passes.
#include <unexmin/sim/world_config.h>
#include <unexmin/sim/world_schema.h>
#include "expect_error.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using unexmin::ConfigError;
namespace sim = unexmin::sim;

namespace {

const std::string kSchema = std::string(UNEXMIN_SOURCE_DIR) + "/config/world_schema.yaml";

/// The message of the ConfigError that loading the world `text` (written to <temp>/`name`) throws; its path in `path`.
std::string refusal(const std::string& name, const std::string& text, std::string& path,
                    const std::string& schema = kSchema) {
  path = unexmin::test::testTempDir() + name;
  std::ofstream(path) << text;
  return unexmin::test::thrownMessage<ConfigError>([&] { sim::loadWorldConfig(path, schema); });
}

/// A world with every level present; each argument is appended to its level (top level, water, current.speed, the
/// second mesh, its material, the robot).
std::string world(const std::string& top, const std::string& water, const std::string& speed, const std::string& mesh,
                  const std::string& material, const std::string& robot) {
  return "name: w\ngravity: 9.81\n" + top + "water: {density: 1000.0, surface_z: 0.0" + water +
         "}\nvisibility: {level: low, colour: [0.25, 0.3, 0.2]}\n"
         "current:\n  speed: {mean: 0.1, min: 0.0, max: 0.5, noise: 0.0, mu: 0.0" +
         speed +
         "}\nmeshes:\n"
         "  - {name: a, file: nowhere.stl}\n"
         "  - {name: b, file: nowhere.stl, albedo: [0.1, 0.1, 0.1]" +
         mesh + ", material: {kind: rock, seed: 7" + material +
         "}}\n"
         "robots:\n  - {name: UX_1, xyz: [0, 0, -1]" +
         robot + "}\n";
}

}  // namespace

TEST(WorldSchema, TypoAtEachLevelIsRefusedWithItsPathAndTheNearestKey) {
  struct Case {
    std::string text, path, accepted, nearest;
  };
  const std::vector<Case> cases = {
      {world("gravty: 9.81\n", "", "", "", "", ""), "gravty",
       "name, gravity, water, atmospheric_pressure, visibility, ray_caster, magnetic_field, current, meshes, robots",
       "gravity"},
      {world("visiblity: {level: high}\n", "", "", "", "", ""), "visiblity",
       "name, gravity, water, atmospheric_pressure, visibility, ray_caster, magnetic_field, current, meshes, robots",
       "visibility"},
      {world("", ", densty: 1025", "", "", "", ""), "water.densty", "density, surface_z", "density"},
      {world("", "", ", meen: 0.2", "", "", ""), "current.speed.meen", "mean, min, max, noise, mu", "mean"},
      {world("", "", "", ", albdo: [0.1, 0.1, 0.1]", "", ""), "meshes[1].albdo",
       "name, file, scale, xyz, rpy, collision, visual, albedo, material", "albedo"},
      {world("", "", "", "", ", grian: 0.02", ""), "meshes[1].material.grian",
       "kind, albedo, seed, contrast, relief, grain, cracks, strata, stains, region, tint", "grain"},
      {world("", "", "", "", "", ", descripton: ux1.urdf.xacro"), "robots[0].descripton", "name, description, xyz, rpy",
       "description"},
  };
  std::string path;
  for (const auto& c : cases) {
    const std::string message = refusal("typo.world", c.text, path);
    EXPECT_EQ(message, path + ": unknown key '" + c.path + "' (accepted: " + c.accepted + "); did you mean '" +
                           c.nearest + "'?");
  }
  // the same world without a typo is refused only for its missing mesh file, after every key passed
  EXPECT_NE(refusal("good.world", world("", "", "", "", "", ""), path).find("nowhere.stl does not exist"),
            std::string::npos);
}

TEST(WorldSchema, NoSuggestionWhenNoKeyIsClose) {
  std::string path;
  const std::string message = refusal("far.world", world("zzz: 1\n", "", "", "", "", ""), path);
  EXPECT_EQ(message,
            path +
                ": unknown key 'zzz' (accepted: name, gravity, water, atmospheric_pressure, visibility, ray_caster, "
                "magnetic_field, current, meshes, robots)");
}

TEST(WorldSchema, NearestKeyAgreesWithPythonsDifflib) {
  // expected: difflib.get_close_matches(key, accepted, n=1) of Python 3.11
  const std::vector<std::string> process = {"mean", "min", "max", "noise", "mu"};
  EXPECT_EQ(sim::nearestKey("mu", process), "mu");
  EXPECT_EQ(sim::nearestKey("my", process), "");  // ratio 0.5 < 0.6
  EXPECT_EQ(sim::nearestKey("maxx", process), "max");
  EXPECT_EQ(sim::nearestKey("mn", process), "min");
  EXPECT_EQ(sim::nearestKey("mnx", process), "min");  // 'min' and 'max' tie at 2/3: the later in byte order
  EXPECT_EQ(sim::nearestKey("color", {"level", "colour"}), "colour");
  EXPECT_EQ(sim::nearestKey("zzz", {"name", "description", "xyz", "rpy"}), "");
  EXPECT_DOUBLE_EQ(sim::keySimilarity("albedo", "albdo"), 2.0 * 5 / 11);
  EXPECT_DOUBLE_EQ(sim::keySimilarity("", ""), 1.0);
}

TEST(WorldSchema, EveryShippedWorldPasses) {
  int worlds = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(UNEXMIN_SOURCE_DIR) + "/worlds")) {
    if (entry.path().extension() != ".world")
      continue;
    ++worlds;
    EXPECT_NO_THROW(sim::checkWorldKeys(YAML::LoadFile(entry.path().string()), entry.path().string(), kSchema))
        << entry.path();
  }
  EXPECT_GE(worlds, 3);  // mine, tank, test_box
}

TEST(WorldSchema, FoundInThePackageAndAMissingOneIsNamed) {
  unsetenv("UNEXMIN_WORLD_SCHEMA");
  EXPECT_TRUE(std::filesystem::equivalent(sim::worldSchemaFile(), kSchema));
  setenv("UNEXMIN_WORLD_SCHEMA", "/nonexistent/world_schema.yaml", 1);
  const std::string msg = unexmin::test::thrownMessage<ConfigError>([] { sim::worldSchemaFile(); });
  unsetenv("UNEXMIN_WORLD_SCHEMA");
  EXPECT_EQ(msg,
            "world-file schema not found at /nonexistent/world_schema.yaml: expected the unexmin package's "
            "config/world_schema.yaml (or a file named by $UNEXMIN_WORLD_SCHEMA)");
  std::string path;
  EXPECT_EQ(refusal("good.world", world("", "", "", "", "", ""), path, "/nonexistent/schema.yaml")
                .rfind("/nonexistent/schema.yaml: cannot read the world-file schema", 0),
            0u);
}

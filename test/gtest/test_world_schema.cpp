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
       "name, gravity, water, atmospheric_pressure, visibility, sediment, ray_caster, magnetic_field, current, meshes, "
       "geology, robots",
       "gravity"},
      {world("visiblity: {level: high}\n", "", "", "", "", ""), "visiblity",
       "name, gravity, water, atmospheric_pressure, visibility, sediment, ray_caster, magnetic_field, current, meshes, "
       "geology, robots",
       "visibility"},
      {world("", ", densty: 1025", "", "", "", ""), "water.densty",
       "density, surface_z, profile, interpolation, boundary, regions", "density"},
      {world("", "", ", meen: 0.2", "", "", ""), "current.speed.meen", "mean, min, max, noise, mu", "mean"},
      {world("", "", "", ", albdo: [0.1, 0.1, 0.1]", "", ""), "meshes[1].albdo",
       "name, file, scale, xyz, rpy, collision, visual, seen_by, albedo, material", "albedo"},
      {world("", "", "", "", ", grian: 0.02", ""), "meshes[1].material.grian",
       "kind, albedo, seed, contrast, relief, grain, cracks, strata, stains, region, tint, square, rows, columns, "
       "dark, border, image",
       "grain"},
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
  EXPECT_EQ(message, path +
                         ": unknown key 'zzz' (accepted: name, gravity, water, atmospheric_pressure, visibility, "
                         "sediment, ray_caster, "
                         "magnetic_field, current, meshes, geology, robots)");
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

namespace {

/// (key path with list indices as [0], the schema's entry) of every number or vec3 key with a bound, and of every
/// string key with choices, outside `skip` (a subtree the reader does not read yet).
void boundedKeys(const YAML::Node& spec, const std::string& path, const std::string& skip,
                 std::vector<std::pair<std::string, YAML::Node>>& out) {
  if (path == skip)
    return;
  const std::string type = spec["type"].as<std::string>();
  if (type == "list")
    return boundedKeys(spec["items"], path + "[0]", skip, out);
  if (type == "map") {
    for (const auto& kv : spec["keys"])
      boundedKeys(kv.second, (path.empty() ? "" : path + ".") + kv.first.as<std::string>(), skip, out);
    return;
  }
  if (spec["min"] || spec["max"] || spec["exclusive_min"] || spec["choices"])
    out.emplace_back(path, spec);
}

/// The node at `path` ("a.b[0].c") of `root`, made if missing.
YAML::Node at(YAML::Node root, const std::string& path) {
  YAML::Node node = root;
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t dot = path.find('.', start);
    std::string part = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    const std::size_t bracket = part.find('[');
    if (bracket == std::string::npos) {
      node.reset(node[part]);
    } else {
      node.reset(node[part.substr(0, bracket)]);
      node.reset(node[std::stoi(part.substr(bracket + 1))]);
    }
    if (dot == std::string::npos)
      break;
    start = dot + 1;
  }
  return node;
}

/// Gives the test world what the key at `path` is read with: a water profile (and its boundary, its region) for the
/// water column's keys, a host rock and a body of the kind the key belongs to for the geology's.
void withContext(YAML::Node& w, const std::string& path) {
  const auto starts = [&](const std::string& prefix) { return path.rfind(prefix, 0) == 0; };
  const std::string boundary = "{depth: 10, amplitude: 1, period: 60}";
  if (starts("water.profile") || starts("water.boundary") || starts("water.regions")) {
    w["water"].remove("density");
    w["water"]["profile"] = YAML::Load(starts("water.boundary") ? "[{depth: 0}, {depth: 50}]" : "[{depth: 0}]");
    if (starts("water.boundary"))
      w["water"]["boundary"] = YAML::Load(boundary);
    if (starts("water.regions"))
      w["water"]["regions"] = YAML::Load(
          starts("water.regions[0].boundary")
              ? "[{min: [-1, -1, -1], max: [1, 1, 1], profile: [{depth: 0}, {depth: 50}], boundary: " + boundary + "}]"
              : "[{min: [-1, -1, -1], max: [1, 1, 1], profile: [{depth: 0}]}]");
  }
  if (starts("magnetic_field."))  // the map form, its three keys required
    w["magnetic_field"] = YAML::Load("{intensity: 50000, inclination: 60, declination: 0}");
  if (starts("geology")) {
    const std::string kind = starts("geology.bodies[0].size") ? "box"
                             : starts("geology.bodies[0].thickness") || starts("geology.bodies[0].extent")
                                 ? "vein"
                                 : "ellipsoid";
    const std::string shape = kind == "box"    ? "size: [1, 1, 1]"
                              : kind == "vein" ? "normal: [0, 0, 1], thickness: 1"
                                               : "radii: [1, 1, 1]";
    w["geology"] = YAML::Load("{host: [{mineral: granite, fraction: 1}], bodies: [{name: b, kind: " + kind + ", " +
                              shape + ", minerals: [{mineral: quartz, fraction: 1}]}]}");
  }
}

}  // namespace

TEST(WorldSchema, TheReaderRefusesEveryValueOutsideTheSchemasBounds) {
  // The simulator checks values where it reads them; here each bound of the schema is crossed once and the reader
  // must refuse the world naming the key (ray_caster: checked when the caster is built; materials: read by the
  // material reader where it is built).
  std::filesystem::path dir = unexmin::test::testTempDir() + "bounds";
  std::filesystem::create_directories(dir);
  std::filesystem::create_directory_symlink(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/meshes", dir / "meshes");
  std::vector<std::pair<std::string, YAML::Node>> keys;
  boundedKeys(YAML::LoadFile(kSchema), "", "meshes[0].material", keys);
  int checked = 0;
  for (const auto& [path, spec] : keys) {
    if (path == "ray_caster")
      continue;
    std::vector<YAML::Node> bad_values;  // one beyond each bound
    if (spec["choices"])
      bad_values.emplace_back("not_" + spec["choices"][0].as<std::string>());
    std::vector<double> beyond;
    if (spec["exclusive_min"])
      beyond.push_back(spec["exclusive_min"].as<double>());
    if (spec["min"])
      beyond.push_back(spec["min"].as<double>() - 0.5);
    if (spec["max"])
      beyond.push_back(spec["max"].as<double>() + 0.5);
    for (const double x : beyond) {
      YAML::Node bad;
      if (spec["type"].as<std::string>() == "vec3") {
        bad.push_back(0.5);
        bad.push_back(x);
        bad.push_back(0.5);
      } else {
        bad = x;
      }
      bad_values.push_back(bad);
    }
    for (const auto& bad : bad_values) {
      YAML::Node w = YAML::LoadFile(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/test_box.world");
      withContext(w, path);
      at(w, path) = bad;
      const std::string file = (dir / "bad.world").string();
      std::ofstream(file) << YAML::Dump(w);
      const std::string message =
          unexmin::test::thrownMessage<ConfigError>([&] { sim::loadWorldConfig(file, kSchema); });
      EXPECT_NE(message.find("'" + path + "'"), std::string::npos)
          << path << " = " << YAML::Dump(bad) << ": " << message;
      ++checked;
    }
  }
  // gravity, density, pressure, level, colour x2, noise and mu x3, scale, seen_by, albedo x2, the seven sediment
  // numbers x2; the water column's (a profile row's depth and seven fields x2, the interpolation, the boundary's
  // depth and period, the same again in a region) and the geology's (fractions x2 twice, kind, radii, size,
  // thickness, extent); the magnetic field's map form (intensity, inclination and declination x2)
  EXPECT_EQ(checked, 81);
}

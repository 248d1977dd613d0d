#include <unexmin/sim/world_config.h>

#include <unexmin/geo/magnetics.h>
#include <unexmin/sim/world_geology.h>
#include <unexmin/sim/world_reader.h>
#include <unexmin/sim/world_schema.h>
#include <unexmin/sim/world_water.h>

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace unexmin {
namespace sim {
namespace {

using Reader = WorldReader;

std::string dirOf(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

}  // namespace

namespace {

/// A mesh's `seen_by:` list (docs/worlds.md) into e.seen_by_cameras / e.seen_by_sonars; absent: from its
/// visual / collision flags.
void readSeenBy(const WorldReader& r, const YAML::Node& mesh, const std::string& where, MeshEntry& e) {
  e.seen_by_cameras = e.visual;
  e.seen_by_sonars = e.collision;
  const YAML::Node v = mesh["seen_by"];
  if (!v)
    return;
  const std::string expected = "a list of cameras|sonars, each at most once (e.g. [cameras, sonars] or [])";
  if (!v.IsSequence())
    r.fail("'" + where + "seen_by' must be " + expected);
  e.seen_by_cameras = e.seen_by_sonars = false;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const std::string who = v[k].IsScalar() ? v[k].Scalar() : "(not a name)";
    bool& seen = who == "cameras" ? e.seen_by_cameras : e.seen_by_sonars;
    if ((who != "cameras" && who != "sonars") || seen)
      r.fail("'" + where + "seen_by[" + formatNumber(k) + "]' is '" + who + "': expected " + expected);
    seen = true;
  }
}

// The stages of loadWorldConfig, one per block of the world file, each reading `root` into `w` (errors through `r`).

/// The parsed file, checked against the schema.
YAML::Node readRoot(Reader& r, const std::string& path, const std::string& schema_file) {
  std::ifstream in(path);
  if (!in)
    r.fail("cannot open the world file");
  YAML::Node root;
  try {
    root = YAML::Load(in);
  } catch (const YAML::Exception& e) {
    r.fail(std::string("not valid YAML: ") + e.what());
  }
  if (!root.IsMap())
    r.fail("the world file must be a YAML map (name, gravity, water, meshes, robots, ...)");
  checkWorldKeys(root, path, schema_file.empty() ? worldSchemaFile() : schema_file);

  return root;
}

/// magnetic_field: [x, y, z] in mG (ENU), or {intensity [nT], inclination [deg], declination [deg]}.
void readMagneticField(Reader& r, const YAML::Node& root, WorldConfig& w) {
  const YAML::Node field = root["magnetic_field"];
  if (!field || !field.IsMap()) {
    w.magnetic_field = r.vec3(root, "magnetic_field", "", w.magnetic_field);  // [mG], ENU
    return;
  }
  const std::string at = "magnetic_field.";
  const double intensity = r.number(field, "intensity", at, 0.0, true);
  const double inclination = r.number(field, "inclination", at, 0.0, true);
  const double declination = r.number(field, "declination", at, 0.0, true);
  if (!(intensity >= 1000.0 && intensity <= 100000.0))
    r.fail("'magnetic_field.intensity' = " + formatNumber(intensity) +
           ": expected [1000, 100000] nT (the Earth's field is about 22 000 to 67 000 nT)");
  if (!(inclination >= -90.0 && inclination <= 90.0))
    r.fail("'magnetic_field.inclination' = " + formatNumber(inclination) + ": expected [-90, 90] deg (down positive)");
  if (!(declination >= -180.0 && declination <= 180.0))
    r.fail("'magnetic_field.declination' = " + formatNumber(declination) +
           ": expected [-180, 180] deg (east of north positive)");
  w.magnetic_field = geo::fieldFromAngles(intensity, inclination, declination) / geo::kNanoteslaPerMilligauss;
}

/// name, gravity, water, atmospheric_pressure, ray_caster, visibility, magnetic_field.
void readEnvironment(Reader& r, const YAML::Node& root, WorldConfig& w) {
  w.name = r.text(root, "name", "", "world");
  w.gravity = r.number(root, "gravity", "", 9.81);
  if (w.gravity <= 0.0)
    r.fail("'gravity' must be > 0 [m/s^2]");
  if (const YAML::Node water = root["water"]) {
    if (!water.IsMap())
      r.fail("'water' must be a map of density/surface_z/profile/interpolation/boundary/regions");
    w.water_density = r.number(water, "density", "water.", 1000.0);
    w.surface_z = r.number(water, "surface_z", "water.", 0.0);
    w.water_column = readWaterColumn(r, water, w.surface_z, w.gravity);
    if (w.water_column)  // the density at the surface, for what reads one density
      w.water_density = w.water_column->at(Eigen::Vector3d(0, 0, w.surface_z), 0.0).density;
  }
  if (w.water_density <= 0.0)
    r.fail("'water.density' must be > 0 [kg/m^3]");
  w.atmospheric_pressure = r.number(root, "atmospheric_pressure", "", 101325.0);
  if (w.atmospheric_pressure < 0.0)
    r.fail("'atmospheric_pressure' must be >= 0 [Pa]");
  w.ray_caster = r.text(root, "ray_caster", "", w.ray_caster);
  if (w.ray_caster.empty())
    r.fail("'ray_caster' is empty, expected the name of a ray-casting back end (embree|bullet)");
  if (const YAML::Node vis = root["visibility"]) {
    w.visibility = r.text(vis, "level", "visibility.", "none");
    const auto& levels = visibilityLevels();
    if (std::find(levels.begin(), levels.end(), w.visibility) == levels.end()) {
      std::string choices;
      for (const auto& l : levels)
        choices += (choices.empty() ? "" : "|") + l;
      r.fail("'visibility.level' is '" + w.visibility + "', expected " + choices);
    }
    if (w.visibility == "water" && !w.water_column)
      r.fail("'visibility.level' is 'water': expected a 'water.profile' (the turbidity by depth it reads)");
    w.visibility_colour = r.vec3(vis, "colour", "visibility.", w.visibility_colour);
    if ((w.visibility_colour.array() <= 0.0).any() || (w.visibility_colour.array() > 1.0).any())
      r.fail("'visibility.colour' must be three numbers in (0, 1]");
  }

  readMagneticField(r, root, w);
}

/// sediment (off unless given).
void readSediment(Reader& r, const YAML::Node& root, const std::string& path, WorldConfig& w) {
  if (const YAML::Node sed = root["sediment"]) {
    if (!sed.IsMap())
      r.fail("'sediment' must be a map of enabled/settling_speed/raise/reach/puff_size/diffusivity/interval/max_puffs");
    SedimentParams& s = w.sediment;
    s.enabled = r.flag(sed, "enabled", "sediment.", s.enabled);
    s.settling_speed = r.number(sed, "settling_speed", "sediment.", s.settling_speed);
    s.raise = r.number(sed, "raise", "sediment.", s.raise);
    s.reach = r.number(sed, "reach", "sediment.", s.reach);
    s.puff_size = r.number(sed, "puff_size", "sediment.", s.puff_size);
    s.diffusivity = r.number(sed, "diffusivity", "sediment.", s.diffusivity);
    s.interval = r.number(sed, "interval", "sediment.", s.interval);
    const double puffs = r.number(sed, "max_puffs", "sediment.", s.max_puffs);
    if (puffs != std::floor(puffs) || !(puffs >= 1.0 && puffs <= 100000.0))
      r.fail("'sediment.max_puffs' is " + formatNumber(puffs) + ", expected a whole number in [1, 100000]");
    s.max_puffs = static_cast<int>(puffs);
    validate(s, path);
  }
}

/// current: the three Gauss-Markov channels.
void readCurrent(Reader& r, const YAML::Node& root, WorldConfig& w) {
  hydro::GaussMarkovParams zero;
  hydro::GaussMarkovParams h_angle;
  h_angle.min = -M_PI;
  h_angle.max = M_PI;
  w.current.speed = zero;
  w.current.horizontal_angle = h_angle;
  w.current.vertical_angle = zero;
  if (const YAML::Node cur = root["current"]) {
    if (!cur.IsMap())
      r.fail("'current' must be a map of speed/horizontal_angle/vertical_angle");
    w.current.speed = r.channel(cur, "speed", zero);
    w.current.horizontal_angle = r.channel(cur, "horizontal_angle", h_angle);
    w.current.vertical_angle = r.channel(cur, "vertical_angle", zero);
  }
  try {
    hydro::validate(w.current);
  } catch (const ParameterError& e) {
    r.fail(e.what());
  }
}

/// meshes, their files relative to the world file's folder.
void readMeshes(Reader& r, const YAML::Node& root, const std::string& path, WorldConfig& w) {
  const std::string base = dirOf(path);
  if (const YAML::Node meshes = root["meshes"]) {
    if (!meshes.IsSequence())
      r.fail("'meshes' must be a list");
    for (std::size_t i = 0; i < meshes.size(); ++i) {
      const YAML::Node m = meshes[i];
      const std::string where = "meshes[" + formatNumber(i) + "].";
      if (!m.IsMap())
        r.fail("'" + where + "' must be a map");
      MeshEntry e;
      e.name = r.text(m, "name", where, "mesh" + formatNumber(i));
      const std::string file = r.text(m, "file", where, "", true);
      e.file = r.insidePath(base, file, where + "file");
      if (!std::ifstream(e.file))
        r.fail("'" + where + "file' " + e.file + " does not exist");
      e.scale = r.vec3(m, "scale", where, Eigen::Vector3d::Ones());
      if ((e.scale.array() <= 0.0).any())
        r.fail("'" + where + "scale' must be > 0 on every axis");
      e.pose = poseFromXyzRpy(r.vec3(m, "xyz", where, Eigen::Vector3d::Zero()),
                              r.vec3(m, "rpy", where, Eigen::Vector3d::Zero()));
      e.collision = r.flag(m, "collision", where, true);
      e.visual = r.flag(m, "visual", where, true);
      readSeenBy(r, m, where, e);
      e.albedo = r.vec3(m, "albedo", where, e.albedo);
      if ((e.albedo.array() < 0.0).any() || (e.albedo.array() > 1.0).any())
        r.fail("'" + where + "albedo' must be three numbers in [0, 1]");
      e.material.albedo = e.albedo;
      if (const YAML::Node mat = m["material"]) {
        if (m["albedo"])
          r.fail("'" + where + "albedo' and '" + where + "material' both given: put the albedo in the material");
        e.material = r.material(mat, where + "material.", base);
        e.albedo = e.material.albedo;
      }
      w.meshes.push_back(e);
    }
  }
}

/// robots: the spawns, named once each.
void readRobots(Reader& r, const YAML::Node& root, WorldConfig& w) {
  const YAML::Node robots = root["robots"];
  if (!robots || !robots.IsSequence() || robots.size() == 0)
    r.fail("'robots' must be a non-empty list of {name, description, xyz, rpy}");
  for (std::size_t i = 0; i < robots.size(); ++i) {
    const YAML::Node m = robots[i];
    const std::string where = "robots[" + formatNumber(i) + "].";
    if (!m.IsMap())
      r.fail("'" + where + "' must be a map");
    RobotSpawn s;
    s.name = r.text(m, "name", where, "", true);
    s.description = r.text(m, "description", where, "ux1.urdf.xacro");
    s.pose = poseFromXyzRpy(r.vec3(m, "xyz", where, Eigen::Vector3d::Zero()),
                            r.vec3(m, "rpy", where, Eigen::Vector3d::Zero()));
    for (const auto& other : w.robots)
      if (other.name == s.name)
        r.fail("robot name '" + s.name + "' appears twice");
    w.robots.push_back(s);
  }
}

}  // namespace

WorldConfig loadWorldConfig(const std::string& path, const std::string& schema_file) {
  Reader r(path);
  const YAML::Node root = readRoot(r, path, schema_file);
  WorldConfig w;
  w.file = path;
  readEnvironment(r, root, w);
  readSediment(r, root, path, w);
  readCurrent(r, root, w);
  readMeshes(r, root, path, w);
  readRobots(r, root, w);
  if (const YAML::Node geology = root["geology"])
    w.geology = readGeology(r, geology, mineralTableFile());
  return w;
}

void selectRobots(WorldConfig& config, const std::vector<std::string>& names) {
  std::vector<RobotSpawn> chosen;
  std::string known;
  for (const auto& r : config.robots)
    known += (known.empty() ? "" : ", ") + r.name;
  for (const auto& name : names) {
    if (std::any_of(chosen.begin(), chosen.end(), [&](const RobotSpawn& r) { return r.name == name; }))
      throw ConfigError(config.file + ": robot '" + name + "' is selected twice");
    const auto it =
        std::find_if(config.robots.begin(), config.robots.end(), [&](const RobotSpawn& r) { return r.name == name; });
    if (it != config.robots.end()) {
      chosen.push_back(*it);
      continue;
    }
    // <prefix>_<k>: anchored at the world's first robot of that prefix, placed by the world
    const std::size_t cut = name.rfind('_');
    const std::string prefix = cut == std::string::npos ? "" : name.substr(0, cut + 1);
    const bool numbered = cut != std::string::npos && cut + 1 < name.size() && name[cut + 1] != '0' &&
                          name.find_first_not_of("0123456789", cut + 1) == std::string::npos;
    const auto anchor = std::find_if(config.robots.begin(), config.robots.end(), [&](const RobotSpawn& r) {
      return !prefix.empty() && r.name.compare(0, prefix.size(), prefix) == 0;
    });
    if (!numbered || anchor == config.robots.end())
      throw ConfigError(config.file + ": no robot '" + name + "' in 'robots' (expected one of: " + known +
                        ", or <prefix>_<k> of a listed robot's prefix)");
    RobotSpawn extra = *anchor;
    extra.name = name;
    extra.placed = false;
    chosen.push_back(extra);
  }
  for (const auto& r : config.robots)
    if (std::find(names.begin(), names.end(), r.name) == names.end())
      chosen.push_back(r);
  config.robots = chosen;
}

}  // namespace sim
}  // namespace unexmin

#include <unexmin/sim/world_config.h>

#include <unexmin/sim/world_schema.h>

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace unexmin {
namespace sim {
namespace {

std::string dirOf(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

class Reader {
public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& what) const { throw ConfigError(file_ + ": " + what); }

  double number(const YAML::Node& node, const std::string& key, const std::string& where, double fallback,
                bool required = false) const {
    const YAML::Node v = node[key];
    if (!v) {
      if (required)
        fail("missing '" + where + key + "' (a number)");
      return fallback;
    }
    double x = 0.0;
    try {
      x = v.as<double>();
    } catch (const YAML::Exception&) {
      fail("'" + where + key + "' must be a number");
    }
    if (!std::isfinite(x))
      fail("'" + where + key + "' must be finite");
    return x;
  }

  Eigen::Vector3d vec3(const YAML::Node& node, const std::string& key, const std::string& where,
                       const Eigen::Vector3d& fallback) const {
    const YAML::Node v = node[key];
    if (!v)
      return fallback;
    if (!v.IsSequence() || v.size() != 3)
      fail("'" + where + key + "' must be a list of 3 numbers");
    Eigen::Vector3d out;
    for (int i = 0; i < 3; ++i) {
      try {
        out[i] = v[i].as<double>();
      } catch (const YAML::Exception&) {
        fail("'" + where + key + "' must be a list of 3 numbers");
      }
      if (!std::isfinite(out[i]))
        fail("'" + where + key + "' must be finite");
    }
    return out;
  }

  std::string text(const YAML::Node& node, const std::string& key, const std::string& where,
                   const std::string& fallback, bool required = false) const {
    const YAML::Node v = node[key];
    if (!v) {
      if (required)
        fail("missing '" + where + key + "' (a string)");
      return fallback;
    }
    if (!v.IsScalar())
      fail("'" + where + key + "' must be a string");
    return v.as<std::string>();
  }

  bool flag(const YAML::Node& node, const std::string& key, const std::string& where, bool fallback) const {
    const YAML::Node v = node[key];
    if (!v)
      return fallback;
    try {
      return v.as<bool>();
    } catch (const YAML::Exception&) {
      fail("'" + where + key + "' must be true or false");
    }
  }

  /// The mesh file `file` (key `key`) of a world file in folder `base`: a relative path that stays inside `base`
  /// once normalised (docs/worlds.md, "Paths"), returned resolved against it. A world file cannot make the
  /// simulator read anything else: absolute paths and paths climbing out with '..' are refused.
  std::string insidePath(const std::string& base, const std::string& file, const std::string& key) const {
    const std::filesystem::path rel(file);
    if (rel.is_absolute())
      fail("'" + key + "' " + file + " is an absolute path: expected a path relative to the world file's folder " +
           base + " and inside it");
    const std::filesystem::path norm = rel.lexically_normal();
    if (norm.empty() || norm == "." || *norm.begin() == "..")
      fail("'" + key + "' " + file + " is not inside the world file's folder " + base +
           ": expected a relative path to a file in it or below it (no '..' out of it)");
    return base + "/" + norm.string();
  }

  /// A mesh's `seen_by:` list (docs/worlds.md) into e.seen_by_cameras / e.seen_by_sonars; absent: from its
  /// visual / collision flags.
  void seenBy(const YAML::Node& mesh, const std::string& where, MeshEntry& e) const {
    e.seen_by_cameras = e.visual;
    e.seen_by_sonars = e.collision;
    const YAML::Node v = mesh["seen_by"];
    if (!v)
      return;
    const std::string expected = "a list of cameras|sonars, each at most once (e.g. [cameras, sonars] or [])";
    if (!v.IsSequence())
      fail("'" + where + "seen_by' must be " + expected);
    e.seen_by_cameras = e.seen_by_sonars = false;
    for (std::size_t k = 0; k < v.size(); ++k) {
      const std::string who = v[k].IsScalar() ? v[k].Scalar() : "(not a name)";
      bool& seen = who == "cameras" ? e.seen_by_cameras : e.seen_by_sonars;
      if ((who != "cameras" && who != "sonars") || seen)
        fail("'" + where + "seen_by[" + formatNumber(k) + "]' is '" + who + "': expected " + expected);
      seen = true;
    }
  }

  hydro::GaussMarkovParams channel(const YAML::Node& node, const std::string& key,
                                   const hydro::GaussMarkovParams& fallback) const {
    const YAML::Node c = node[key];
    if (!c)
      return fallback;
    if (!c.IsMap())
      fail("'current." + key + "' must be a map of mean/min/max/noise/mu");
    const std::string where = "current." + key + ".";
    hydro::GaussMarkovParams p;
    p.mean = number(c, "mean", where, fallback.mean);
    p.min = number(c, "min", where, std::min(fallback.min, p.mean));
    p.max = number(c, "max", where, std::max(fallback.max, p.mean));
    p.noise = number(c, "noise", where, 0.0);
    p.mu = number(c, "mu", where, 0.0);
    return p;
  }

  /// A mesh's `material:` map (docs/worlds.md): the kind's defaults, then every key given; unknown keys and bad
  /// values stop with the key's name.
  Material material(const YAML::Node& node, const std::string& where, const std::string& base) const {
    if (!node.IsMap())
      fail("'" + where.substr(0, where.size() - 1) + "' must be a map (kind, albedo, seed, ...)");
    Material m;
    try {
      m = materialDefaults(text(node, "kind", where, "plain"), where);
      m.albedo = vec3(node, "albedo", where, m.albedo);
      const double seed = number(node, "seed", where, 0.0);
      if (seed < 0.0 || seed > 9007199254740992.0 || seed != std::floor(seed))
        fail("'" + where + "seed' = " + formatNumber(seed) + ": expected an integer >= 0");
      m.seed = static_cast<std::uint64_t>(seed);
      const std::pair<const char*, double*> numbers[] = {
          {"contrast", &m.contrast}, {"relief", &m.relief}, {"grain", &m.grain},   {"cracks", &m.cracks},
          {"strata", &m.strata},     {"stains", &m.stains}, {"region", &m.region}, {"tint", &m.tint}};
      for (const auto& kv : numbers)
        *kv.second = number(node, kv.first, where, *kv.second);
      checkerboard(node, where, m);
      if (node["image"]) {
        m.image = insidePath(base, text(node, "image", where, ""), where + "image");
        if (!std::ifstream(m.image))
          fail("'" + where + "image' " + m.image + " does not exist");
      }
      checkMaterial(m, where);
    } catch (const ParameterError& e) {
      fail(e.what());
    }
    return m;
  }

  /// A checkerboard's keys (square, rows, columns, dark, border) into `m`; on another kind they stop start-up.
  void checkerboard(const YAML::Node& node, const std::string& where, Material& m) const {
    const char* keys[] = {"square", "rows", "columns", "dark", "border"};
    if (!m.checkerboard()) {
      for (const char* key : keys)
        if (node[key])
          fail("'" + where + key + "' is a key of kind checkerboard, not of '" + m.kind + "'");
      return;
    }
    m.square = number(node, "square", where, m.square);
    m.border = number(node, "border", where, m.border);
    m.dark = vec3(node, "dark", where, m.dark);
    for (int* n : {&m.rows, &m.columns}) {
      const char* key = n == &m.rows ? "rows" : "columns";
      const double x = number(node, key, where, *n);
      if (!(x >= 2.0 && x <= 1000.0 && x == std::floor(x)))
        fail("'" + where + key + "' = " + formatNumber(x) + ": expected an integer in [2, 1000]");
      *n = static_cast<int>(x);
    }
  }

private:
  std::string file_;
};

}  // namespace

namespace {

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

/// name, gravity, water, atmospheric_pressure, ray_caster, visibility, magnetic_field.
void readEnvironment(Reader& r, const YAML::Node& root, WorldConfig& w) {
  w.name = r.text(root, "name", "", "world");
  w.gravity = r.number(root, "gravity", "", 9.81);
  if (w.gravity <= 0.0)
    r.fail("'gravity' must be > 0 [m/s^2]");
  if (const YAML::Node water = root["water"]) {
    if (!water.IsMap())
      r.fail("'water' must be a map of density/surface_z");
    w.water_density = r.number(water, "density", "water.", 1000.0);
    w.surface_z = r.number(water, "surface_z", "water.", 0.0);
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
    w.visibility_colour = r.vec3(vis, "colour", "visibility.", w.visibility_colour);
    if ((w.visibility_colour.array() <= 0.0).any() || (w.visibility_colour.array() > 1.0).any())
      r.fail("'visibility.colour' must be three numbers in (0, 1]");
  }

  w.magnetic_field = r.vec3(root, "magnetic_field", "", w.magnetic_field);  // [mG], ENU
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
      r.seenBy(m, where, e);
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

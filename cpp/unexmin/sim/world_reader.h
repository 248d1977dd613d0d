// Reads the values of a parsed world file (docs/worlds.md) with one wording for every key: a wrong value throws
// ConfigError("<file>: '<key>' ...") naming the key's path. Shared by the readers of each block of the file.
#pragma once

#include <unexmin/core/error.h>
#include <unexmin/hydro/current.h>
#include <unexmin/sim/material.h>

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

namespace unexmin {
namespace sim {

class WorldReader {
public:
  explicit WorldReader(std::string file) : file_(std::move(file)) {}

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

}  // namespace sim
}  // namespace unexmin

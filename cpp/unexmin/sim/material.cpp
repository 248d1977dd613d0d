#include <unexmin/sim/material.h>

#include <unexmin/core/error.h>

#include <cmath>

namespace unexmin {
namespace sim {
namespace {

[[noreturn]] void fail(const std::string& prefix, const std::string& key, const std::string& value,
                       const std::string& expected)
{
  throw ParameterError("'" + prefix + key + "' = " + value + ": expected " + expected);
}

void checkRange(const std::string& prefix, const std::string& key, double x, double lo, double hi,
                const std::string& expected)
{
  if (!std::isfinite(x) || x < lo || x > hi) fail(prefix, key, formatNumber(x), expected);
}

}  // namespace

const std::vector<std::string>& materialKinds()
{
  static const std::vector<std::string> kinds{"plain", "rock", "painted", "rusty"};
  return kinds;
}

Material materialDefaults(const std::string& kind, const std::string& prefix)
{
  // Scales and weights are assumed (chosen to look like the surface at 1-3 m through the UX-1's cameras), not
  // measured; docs/worlds.md lists them.
  Material m;
  m.kind = kind;
  if (kind == "plain") return m;
  if (kind == "rock") {  // weathered rock of a mine gallery: grains, cracks, strata, stains
    m.albedo = Eigen::Vector3d(0.32, 0.29, 0.25);
    m.contrast = 0.35;
    m.relief = 0.35;
    m.grain = 0.02;
    m.cracks = 0.3;
    m.strata = 0.5;
    m.stains = 2.0;
    m.weights = Eigen::Vector4d(1.0, 0.7, 0.5, 0.8);
    return m;
  }
  if (kind == "painted") {  // painted concrete: a faint grain under the paint, dirt stains
    m.albedo = Eigen::Vector3d(0.7, 0.72, 0.7);
    m.contrast = 0.08;
    m.relief = 0.1;
    m.grain = 0.02;
    m.stains = 1.0;
    m.weights = Eigen::Vector4d(0.5, 0.0, 0.0, 1.0);
    return m;
  }
  if (kind == "rusty") {  // rusted steel: small pits and blotches of rust
    m.albedo = Eigen::Vector3d(0.42, 0.24, 0.12);
    m.contrast = 0.35;
    m.relief = 0.3;
    m.grain = 0.01;
    m.cracks = 0.04;
    m.stains = 0.12;
    m.weights = Eigen::Vector4d(0.6, 0.4, 0.0, 1.0);
    return m;
  }
  fail(prefix, "kind", "'" + kind + "'", "plain|rock|painted|rusty");
}

void checkMaterial(const Material& m, const std::string& prefix)
{
  materialDefaults(m.kind, prefix);  // the kind is known
  for (int k = 0; k < 3; ++k)
    checkRange(prefix, "albedo", m.albedo[k], 0.0, 1.0, "three numbers in [0, 1]");
  checkRange(prefix, "contrast", m.contrast, 0.0, 1.0, "a number in [0, 1]");
  checkRange(prefix, "tint", m.tint, 0.0, 1.0, "a number in [0, 1]");
  checkRange(prefix, "relief", m.relief, 0.0, 100.0, "a number in [0, 100]");
  const std::pair<const char*, double> scales[] = {
      {"grain", m.grain}, {"cracks", m.cracks}, {"strata", m.strata}, {"stains", m.stains}, {"region", m.region}};
  for (const auto& s : scales) checkRange(prefix, s.first, s.second, 0.0, 1e6, "a scale in [0, 1e6] m (0: off)");
  if (!m.textured() && (m.contrast > 0.0 || m.relief > 0.0 || m.tint > 0.0))
    fail(prefix, "kind", "'plain'", "rock|painted|rusty for a texture (contrast, relief or tint > 0)");
}

}  // namespace sim
}  // namespace unexmin

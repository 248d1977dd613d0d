#include <unexmin/sim/material.h>

#include <unexmin/core/error.h>

#include <cmath>

namespace unexmin {
namespace sim {
namespace {

[[noreturn]] void fail(const std::string& prefix, const std::string& key, const std::string& value,
                       const std::string& expected) {
  throw ParameterError("'" + prefix + key + "' = " + value + ": expected " + expected);
}

void checkRange(const std::string& prefix, const std::string& key, double x, double lo, double hi,
                const std::string& expected) {
  if (!std::isfinite(x) || x < lo || x > hi)
    fail(prefix, key, formatNumber(x), expected);
}

}  // namespace

const std::vector<std::string>& materialKinds() {
  static const std::vector<std::string> kinds{"plain", "rock", "painted", "rusty", "image", "vertex_colours"};
  return kinds;
}

Material materialDefaults(const std::string& kind, const std::string& prefix) {
  // Per textured kind: albedo, contrast, relief, grain, cracks, strata, stains [m], weights of the four components.
  // Assumed (chosen to look like the surface at 1-3 m through the UX-1's cameras), not measured; docs/worlds.md.
  struct Row {
    const char* kind;
    double albedo[3], contrast, relief, scale[4], weight[4];
  };
  static const Row rows[] = {
      // weathered rock of a mine gallery: grains, cracks, strata, stains
      {"rock", {0.32, 0.29, 0.25}, 0.35, 0.35, {0.02, 0.3, 0.5, 2.0}, {1.0, 0.7, 0.5, 0.8}},
      // painted concrete: a faint grain under the paint, dirt stains
      {"painted", {0.7, 0.72, 0.7}, 0.08, 0.1, {0.02, 0.0, 0.0, 1.0}, {0.5, 0.0, 0.0, 1.0}},
      // rusted steel: small pits and blotches of rust
      {"rusty", {0.42, 0.24, 0.12}, 0.35, 0.3, {0.01, 0.04, 0.0, 0.12}, {0.6, 0.4, 0.0, 1.0}},
  };
  Material m;
  m.kind = kind;
  if (kind == "plain")
    return m;
  if (kind == "image" || kind == "vertex_colours") {
    m.albedo = Eigen::Vector3d::Ones();  // the image's or the vertices' colours as they are
    return m;
  }
  for (const Row& r : rows) {
    if (kind != r.kind)
      continue;
    m.albedo = Eigen::Vector3d(r.albedo[0], r.albedo[1], r.albedo[2]);
    m.contrast = r.contrast;
    m.relief = r.relief;
    m.grain = r.scale[0];
    m.cracks = r.scale[1];
    m.strata = r.scale[2];
    m.stains = r.scale[3];
    m.weights = Eigen::Vector4d(r.weight[0], r.weight[1], r.weight[2], r.weight[3]);
    return m;
  }
  fail(prefix, "kind", "'" + kind + "'", "plain|rock|painted|rusty|image|vertex_colours");
}

void checkMaterial(const Material& m, const std::string& prefix) {
  materialDefaults(m.kind, prefix);  // the kind is known
  for (int k = 0; k < 3; ++k)
    checkRange(prefix, "albedo", m.albedo[k], 0.0, 1.0, "three numbers in [0, 1]");
  checkRange(prefix, "contrast", m.contrast, 0.0, 1.0, "a number in [0, 1]");
  checkRange(prefix, "tint", m.tint, 0.0, 1.0, "a number in [0, 1]");
  checkRange(prefix, "relief", m.relief, 0.0, 100.0, "a number in [0, 100]");
  const std::pair<const char*, double> scales[] = {
      {"grain", m.grain}, {"cracks", m.cracks}, {"strata", m.strata}, {"stains", m.stains}, {"region", m.region}};
  for (const auto& s : scales)
    checkRange(prefix, s.first, s.second, 0.0, 1e6, "a scale in [0, 1e6] m (0: off)");
  if (!m.textured() && (m.contrast > 0.0 || m.relief > 0.0 || m.tint > 0.0))
    fail(prefix, "kind", "'" + m.kind + "'", "rock|painted|rusty for a texture (contrast, relief or tint > 0)");
  if ((m.kind == "image") != !m.image.empty())
    fail(prefix, m.image.empty() ? "image" : "kind", m.image.empty() ? "(none)" : "'" + m.kind + "'",
         m.image.empty() ? "the PNG or JPEG file of kind image" : "image (the only kind with an image file)");
}

}  // namespace sim
}  // namespace unexmin

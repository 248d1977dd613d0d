#include <unexmin/sim/material.h>

#include <unexmin/core/error.h>

#include <algorithm>
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
  static const std::vector<std::string> kinds{"plain",        "rock",  "painted",       "rusty",
                                              "checkerboard", "image", "vertex_colours"};
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
  if (kind == "checkerboard") {
    // Assumed: a printed target of 9 x 7 squares of 8 cm (8 x 6 inner corners) with a 6 cm white margin, matt
    // white paper (0.85) and black ink (0.04).
    m.albedo = Eigen::Vector3d::Constant(0.85);
    m.dark = Eigen::Vector3d::Constant(0.04);
    m.square = 0.08;
    m.rows = 7;
    m.columns = 9;
    m.border = 0.06;
    return m;
  }
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
  fail(prefix, "kind", "'" + kind + "'", "plain|rock|painted|rusty|checkerboard|image|vertex_colours");
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
  if (!m.checkerboard())
    return;
  checkRange(prefix, "square", m.square, 1e-4, 100.0, "a side in [1e-4, 100] m");
  checkRange(prefix, "rows", m.rows, 2, 1000, "an integer in [2, 1000]");
  checkRange(prefix, "columns", m.columns, 2, 1000, "an integer in [2, 1000]");
  checkRange(prefix, "border", m.border, 0.0, 100.0, "a width in [0, 100] m");
  for (int k = 0; k < 3; ++k)
    checkRange(prefix, "dark", m.dark[k], 0.0, 1.0, "three numbers in [0, 1]");
  for (const auto& s : scales)
    checkRange(prefix, s.first, s.second, 0.0, 0.0, "0 on a checkerboard (no rock texture)");
  checkRange(prefix, "contrast", m.contrast, 0.0, 0.0, "0 on a checkerboard (no rock texture)");
  checkRange(prefix, "relief", m.relief, 0.0, 0.0, "0 on a checkerboard (no rock texture)");
  checkRange(prefix, "tint", m.tint, 0.0, 0.0, "0 on a checkerboard (no rock texture)");
}

Eigen::Vector3f checkerboardAlbedo(const Material& m, const Eigen::Vector3f& p) {
  const double half_x = 0.5 * m.columns * m.square, half_y = 0.5 * m.rows * m.square;
  const double x = p.x() + half_x, y = p.y() + half_y;  // from the squares' corner at the most negative x and y
  bool dark;
  if (x >= 0.0 && x < 2.0 * half_x && y >= 0.0 && y < 2.0 * half_y) {
    const int i = std::min(static_cast<int>(x / m.square), m.columns - 1);
    const int j = std::min(static_cast<int>(y / m.square), m.rows - 1);
    dark = (i + j) % 2 == 0;
  } else {
    dark = std::abs(p.x()) >= half_x + m.border || std::abs(p.y()) >= half_y + m.border;
  }
  return (dark ? m.dark : m.albedo).cast<float>();
}

}  // namespace sim
}  // namespace unexmin

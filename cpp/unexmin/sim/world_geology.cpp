#include <unexmin/sim/world_geology.h>

#include <unexmin/sim/pose.h>
#include <unexmin/sim/world_schema.h>

#include <algorithm>
#include <limits>

namespace unexmin {
namespace sim {
namespace {

std::vector<geo::Component> readComponents(const WorldReader& r, const YAML::Node& list, const std::string& key) {
  if (!list || !list.IsSequence())
    r.fail("'" + key + "' must be a list of {mineral, fraction} (volume fractions summing to 1)");
  std::vector<geo::Component> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string at = key + "[" + formatNumber(static_cast<double>(i)) + "].";
    if (!list[i].IsMap())
      r.fail("'" + at.substr(0, at.size() - 1) + "' must be a map {mineral, fraction}");
    geo::Component c;
    c.mineral = r.text(list[i], "mineral", at, "", true);
    c.fraction = r.number(list[i], "fraction", at, 0.0, true);
    out.push_back(c);
  }
  return out;
}

geo::Rock readRock(const WorldReader& r, const geo::MineralTable& table, const YAML::Node& node,
                   const std::string& key) {
  try {
    return geo::mixRock(table, readComponents(r, node, key), key);
  } catch (const ConfigError& e) {
    r.fail(e.what());
  }
}

/// A unit vector from `key` (default `fallback`); a zero vector is refused.
Eigen::Vector3d direction(const WorldReader& r, const YAML::Node& node, const std::string& key,
                          const std::string& where, const Eigen::Vector3d& fallback) {
  const Eigen::Vector3d v = r.vec3(node, key, where, fallback);
  if (v.norm() < 1e-12)
    r.fail("'" + where + key + "' must be a non-zero vector");
  return v.normalized();
}

/// A frame whose z axis is the unit normal n, at point c.
Eigen::Isometry3d planeFrame(const Eigen::Vector3d& c, const Eigen::Vector3d& n) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), n).toRotationMatrix();
  pose.translation() = c;
  return pose;
}

geo::Body readBody(const WorldReader& r, const geo::MineralTable& table, const YAML::Node& b, const std::string& at) {
  geo::Body body;
  body.name = r.text(b, "name", at, "", true);
  const std::string kind = r.text(b, "kind", at, "", true);
  const auto& kinds = geo::bodyKindNames();
  const auto it = std::find(kinds.begin(), kinds.end(), kind);
  if (it == kinds.end())
    r.fail("'" + at + "kind' is '" + kind + "', expected ellipsoid|box|vein|stratum");
  body.kind = static_cast<geo::BodyKind>(it - kinds.begin());
  const Eigen::Vector3d xyz = r.vec3(b, "xyz", at, Eigen::Vector3d::Zero());
  // the keys of each kind; another kind's key is refused
  const std::vector<std::string> own = body.kind == geo::BodyKind::ellipsoid ? std::vector<std::string>{"radii", "rpy"}
                                       : body.kind == geo::BodyKind::box     ? std::vector<std::string>{"size", "rpy"}
                                       : body.kind == geo::BodyKind::vein
                                           ? std::vector<std::string>{"normal", "thickness", "extent"}
                                           : std::vector<std::string>{"normal", "thickness"};
  for (const char* key : {"radii", "size", "rpy", "normal", "thickness", "extent"})
    if (b[key] && std::find(own.begin(), own.end(), key) == own.end())
      r.fail("'" + at + key + "' is not a key of kind " + kind);
  switch (body.kind) {
    case geo::BodyKind::ellipsoid:
    case geo::BodyKind::box: {
      const char* key = body.kind == geo::BodyKind::ellipsoid ? "radii" : "size";
      if (!b[key])
        r.fail("missing '" + at + key + "' (3 lengths [m])");
      body.size = r.vec3(b, key, at, Eigen::Vector3d::Ones());
      if ((body.size.array() <= 0.0).any())
        r.fail("'" + at + key + "' must be > 0 [m] on every axis");
      body.pose = poseFromXyzRpy(xyz, r.vec3(b, "rpy", at, Eigen::Vector3d::Zero()));
      break;
    }
    case geo::BodyKind::vein:
    case geo::BodyKind::stratum: {
      if (!b["normal"])
        r.fail("missing '" + at + "normal' (the plane's normal, world frame)");
      body.pose = planeFrame(xyz, direction(r, b, "normal", at, Eigen::Vector3d::UnitZ()));
      const double thickness = r.number(b, "thickness", at, 0.0, true);
      if (!(thickness > 0.0))
        r.fail("'" + at + "thickness' = " + formatNumber(thickness) + ": expected > 0 m");
      double extent = std::numeric_limits<double>::infinity();
      if (body.kind == geo::BodyKind::vein && b["extent"]) {
        extent = r.number(b, "extent", at, 0.0);
        if (!(extent > 0.0))
          r.fail("'" + at + "extent' = " + formatNumber(extent) + ": expected > 0 m (the vein's radius in its plane)");
      }
      body.size = Eigen::Vector3d(extent, extent, thickness);
      break;
    }
  }
  if (b["remanence_direction"])
    body.remanence_direction = direction(r, b, "remanence_direction", at, Eigen::Vector3d::UnitZ());
  body.rock = readRock(r, table, b["minerals"], at + "minerals");
  return body;
}

}  // namespace

std::string mineralTableFile() {
  return packageConfigFile("minerals.yaml", "UNEXMIN_MINERALS", "mineral table");
}

std::shared_ptr<const geo::Geology> readGeology(const WorldReader& r, const YAML::Node& geology,
                                                const std::string& minerals_file) {
  if (!geology.IsMap())
    r.fail("'geology' must be a map of host/bodies");
  const geo::MineralTable table = geo::MineralTable::load(minerals_file);
  if (!geology["host"])
    r.fail("missing 'geology.host' (the host rock: a list of {mineral, fraction})");
  geo::Rock host = readRock(r, table, geology["host"], "geology.host");
  std::vector<geo::Body> bodies;
  if (const YAML::Node list = geology["bodies"]) {
    if (!list.IsSequence())
      r.fail("'geology.bodies' must be a list of {name, kind, xyz, ..., minerals}");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string at = "geology.bodies[" + formatNumber(static_cast<double>(i)) + "].";
      if (!list[i].IsMap())
        r.fail("'" + at.substr(0, at.size() - 1) + "' must be a map");
      bodies.push_back(readBody(r, table, list[i], at));
      const std::string& name = bodies.back().name;
      const bool twice =
          std::any_of(bodies.begin(), bodies.end() - 1, [&](const geo::Body& b) { return b.name == name; });
      if (twice || name == "host")
        r.fail("'" + at + "name' = '" + name + "': " + (twice ? "another body has it" : "the host rock's name"));
    }
  }
  return std::make_shared<const geo::Geology>(std::move(host), std::move(bodies));
}

}  // namespace sim
}  // namespace unexmin

// <hydrodynamics link="..."> of a robot description: the rigid body's mass, volume, radius, centres, inertia,
// added mass, damping and optional bounding box (docs/robot_description.md).
#include <unexmin/sim/description_entities.h>

namespace unexmin {
namespace sim {
namespace description {
namespace {

const std::string kWhere = "<hydrodynamics>";

Eigen::Vector3d principalInertia(const DescriptionReader& r, const tinyxml2::XMLElement* hyd) {
  const auto* inertia = r.child(hyd, "inertia", kWhere);
  const std::string where = kWhere + "/inertia";
  return Eigen::Vector3d(r.attr(inertia, "ixx", where), r.attr(inertia, "iyy", where), r.attr(inertia, "izz", where));
}

void readDamping(const DescriptionReader& r, const tinyxml2::XMLElement* hyd, hydro::HydroParams& h) {
  const auto added = r.valueOf(hyd, "added_mass", 36, kWhere);
  for (int row = 0; row < 6; ++row)
    for (int col = 0; col < 6; ++col)
      h.added_mass(row, col) = added[6 * row + col];
  const auto linear = r.valueOf(hyd, "linear_damping", 6, kWhere);
  const auto quadratic = r.valueOf(hyd, "quadratic_damping", 6, kWhere);
  for (int i = 0; i < 6; ++i) {
    h.linear_damping[i] = linear[i];
    h.quadratic_damping[i] = quadratic[i];
  }
}

}  // namespace

void parseHydrodynamics(const DescriptionReader& r, const tinyxml2::XMLElement* ext, const LinkNames& links,
                        RobotDescription& d) {
  const auto* hyd = r.child(ext, "hydrodynamics", "<unexmin>");
  d.base_link = textOf(hyd, "link");
  if (!links.count(d.base_link))
    r.fail(kWhere + "@link '" + d.base_link + "' is not a link of the robot");
  auto& h = d.hydro;
  h.mass = r.valueOf(hyd, "mass", 1, kWhere)[0];
  h.volume = r.valueOf(hyd, "volume", 1, kWhere)[0];
  h.radius = r.valueOf(hyd, "radius", 1, kWhere)[0];
  h.center_of_gravity = r.vector3(r.child(hyd, "center_of_gravity", kWhere), "xyz", kWhere + "/center_of_gravity");
  h.center_of_buoyancy = r.vector3(r.child(hyd, "center_of_buoyancy", kWhere), "xyz", kWhere + "/center_of_buoyancy");
  h.inertia = principalInertia(r, hyd);
  readDamping(r, hyd, h);
  try {
    hydro::validate(h);
  } catch (const ParameterError& e) {
    r.fail(kWhere + ": " + e.what());
  }
  if (const auto* box = hyd->FirstChildElement("bounding_box")) {
    d.hull_box = r.vector3(box, "size", kWhere + "/bounding_box");
    if (!(d.hull_box.minCoeff() > 0.0))
      r.fail(kWhere + "/bounding_box@size must be three lengths > 0 [m]");
  }
}

}  // namespace description
}  // namespace sim
}  // namespace unexmin

// <magnetic> of a robot description: the robot's own field at its magnetometers (optional; none: zero field).
//   <magnetic>
//     <hard_iron value="x y z"/>                      [nT], body frame; default 0
//     <soft_iron value="s11 s12 s13 ... s33"/>         row-major 3x3 on the external field; default identity
//     <thruster_current coefficient="k" exponent="n"/> I = k |T|^n [A], T in N; default k = 0, n = 1.5
//     <thruster id="0" field="x y z"/>                 [nT/A], body frame, per thruster id; default 0
//   </magnetic>
#include <unexmin/sim/description_entities.h>

#include <Eigen/SVD>

#include <cstring>

namespace unexmin {
namespace sim {
namespace description {
namespace {

void requireAtMost(const DescriptionReader& r, const Eigen::Vector3d& v, double limit, const std::string& where,
                   const char* unit) {
  if (v.norm() > limit)
    r.fail(where + " has magnitude " + formatNumber(v.norm()) + " " + unit + ", expected at most " +
           formatNumber(limit) + " " + unit);
}

}  // namespace

void parseMagnetics(const DescriptionReader& r, const tinyxml2::XMLElement* ext, RobotDescription& d) {
  const auto* mag = ext->FirstChildElement("magnetic");
  if (!mag)
    return;
  if (mag->NextSiblingElement("magnetic"))
    r.fail("<magnetic> given twice: expected one <magnetic> element");
  RobotMagnetics& m = d.magnetics;
  for (const auto* e = mag->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const char* tag = e->Name();
    if (std::strcmp(tag, "hard_iron") && std::strcmp(tag, "soft_iron") && std::strcmp(tag, "thruster_current") &&
        std::strcmp(tag, "thruster"))
      r.fail(std::string("<magnetic>: unknown element <") + tag +
             "> (expected hard_iron, soft_iron, thruster_current, thruster)");
  }
  if (const auto* h = mag->FirstChildElement("hard_iron")) {
    m.hard_iron = r.vector3(h, "value", "<magnetic><hard_iron>");
    requireAtMost(r, m.hard_iron, 1e6, "<magnetic><hard_iron>@value", "nT");
  }
  if (const auto* s = mag->FirstChildElement("soft_iron")) {
    const auto v = r.attrNumbers(s, "value", 9, "<magnetic><soft_iron>");
    for (int i = 0; i < 9; ++i)
      m.soft_iron(i / 3, i % 3) = v[static_cast<std::size_t>(i)];
    const Eigen::Vector3d sv = Eigen::JacobiSVD<Eigen::Matrix3d>(m.soft_iron).singularValues();
    if (m.soft_iron.determinant() <= 0.0 || sv.minCoeff() < 0.5 || sv.maxCoeff() > 2.0)
      r.fail("<magnetic><soft_iron>@value has singular values " + formatNumber(sv.minCoeff()) + " .. " +
             formatNumber(sv.maxCoeff()) + " and determinant " + formatNumber(m.soft_iron.determinant()) +
             ": expected a rotation-preserving matrix (determinant > 0) with singular values in [0.5, 2]");
  }
  if (const auto* c = mag->FirstChildElement("thruster_current")) {
    const std::string cw = "<magnetic><thruster_current>";
    m.current_coefficient = r.attrOr(c, "coefficient", cw, m.current_coefficient);
    m.current_exponent = r.attrOr(c, "exponent", cw, m.current_exponent);
    if (!(m.current_coefficient >= 0.0 && m.current_coefficient <= 1000.0))
      r.fail(cw + "@coefficient = " + formatNumber(m.current_coefficient) + ": expected [0, 1000] A/N^n");
    if (!(m.current_exponent >= 0.5 && m.current_exponent <= 3.0))
      r.fail(cw + "@exponent = " + formatNumber(m.current_exponent) + ": expected [0.5, 3]");
  }
  std::vector<bool> seen(d.thrusters.size(), false);
  for (const auto* t = mag->FirstChildElement("thruster"); t; t = t->NextSiblingElement("thruster")) {
    const int id = actuatorId(r, t, "magnetic><thruster");
    const std::string tw = "<magnetic><thruster id=\"" + formatNumber(id) + "\">";
    if (static_cast<std::size_t>(id) >= d.thrusters.size())
      r.fail(tw + ": the robot has no thruster " + formatNumber(id) + " (ids 0 .. " +
             formatNumber(static_cast<double>(d.thrusters.size()) - 1.0) + ")");
    if (seen[static_cast<std::size_t>(id)])
      r.fail(tw + " given twice");
    seen[static_cast<std::size_t>(id)] = true;
    m.thruster_field.resize(d.thrusters.size(), Eigen::Vector3d::Zero());
    m.thruster_field[static_cast<std::size_t>(id)] = r.vector3(t, "field", tw);
    requireAtMost(r, m.thruster_field[static_cast<std::size_t>(id)], 1e5, tw + "@field", "nT/A");
  }
}

}  // namespace description
}  // namespace sim
}  // namespace unexmin

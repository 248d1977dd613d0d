// <thruster id joint> of a robot description: pose from its joint, dynamics and conversion families by name, thrust
// and command ranges, watchdog (docs/robot_description.md).
#include <unexmin/sim/description_entities.h>

namespace unexmin {
namespace sim {
namespace description {
namespace {

/// A <dynamics>/<conversion> child: the family name and its <param>s.
void readFamily(const DescriptionReader& r, const tinyxml2::XMLElement* t, const char* tag, const std::string& where,
                std::string& family, hydro::ParamMap& params) {
  const auto* e = r.child(t, tag, where);
  family = textOf(e, "type");
  params = r.params(e, where + "/" + tag);
}

hydro::ThrusterParams readThruster(const DescriptionReader& r, const tinyxml2::XMLElement* t, RobotDescription& d,
                                   std::string& joint) {
  hydro::ThrusterParams tp;
  tp.id = actuatorId(r, t, "thruster");
  const std::string tw = "<thruster id=" + formatNumber(tp.id) + ">";
  const JointInfo& j = actuatorJoint(r, d, t->Attribute("joint"), tw);
  joint = j.name;
  const Eigen::Isometry3d pose = d.linkPose(j.parent) * j.origin;
  tp.position = pose.translation();
  requireInsideHull(r, d, tp.position, tw);
  tp.axis = pose.linear() * j.axis;
  readFamily(r, t, "dynamics", tw, tp.dynamics, tp.dynamics_params);
  readFamily(r, t, "conversion", tw, tp.conversion, tp.conversion_params);
  const auto* thrust = r.child(t, "thrust", tw);
  tp.min_thrust = r.attr(thrust, "min", tw + "/thrust");
  tp.max_thrust = r.attr(thrust, "max", tw + "/thrust");
  const auto* cmd = t->FirstChildElement("command");
  tp.min_command = r.attrOr(cmd, "min", tw + "/command", tp.min_thrust);
  tp.max_command = r.attrOr(cmd, "max", tw + "/command", tp.max_thrust);
  if (const auto* to = t->FirstChildElement("timeout"))
    tp.timeout = r.attr(to, "value", tw + "/timeout");
  try {
    hydro::Thruster check(tp, d.thruster_families);  // validates dynamics/conversion names and parameters
  } catch (const ParameterError& e) {
    r.fail(tw + ": " + e.what());
  }
  return tp;
}

}  // namespace

void parseThrusters(const DescriptionReader& r, const tinyxml2::XMLElement* ext, RobotDescription& d) {
  readActuators(
      r, ext, "thruster",
      [&](const tinyxml2::XMLElement* e, std::string& joint) { return readThruster(r, e, d, joint); }, d.thrusters,
      d.thruster_joints);
}

}  // namespace description
}  // namespace sim
}  // namespace unexmin

// The simulator's view of a robot description (URDF, expanded from xacro): parseRobotDescription reads the joint
// tree for the actuator poses plus the <unexmin> element with the hydrodynamic, thruster, pendulum and VBS
// parameters into a RobotDescription (sim/description_types.h). See docs/robot_description.md for the schema.
#pragma once

#include <unexmin/hydro/thruster_factory.h>
#include <unexmin/sim/description_types.h>

#include <string>

namespace unexmin {
namespace sim {

/// Parses URDF XML; throws ConfigError("<source>: <problem>") naming the element and attribute. The thrusters'
/// families are looked up in `thruster_families` (ThrusterFactory::builtin() unless given).
RobotDescription parseRobotDescription(const std::string& xml, const std::string& source);
RobotDescription parseRobotDescription(const std::string& xml, const std::string& source,
                                       const hydro::ThrusterFactory& thruster_families);

}  // namespace sim
}  // namespace unexmin

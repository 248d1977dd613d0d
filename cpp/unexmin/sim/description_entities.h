// The parsers of the entities of a robot description (docs/robot_description.md), one per file of this folder:
// the joint tree (robot_description.cpp), <hydrodynamics>, <thruster>, <fin>, <pendulum>, <vbs> (the ballast),
// <magnetic> and <sensor>. parseRobotDescription (sim/robot_description.h) calls them in that order on one
// RobotDescription; each fills its part and throws ConfigError("<source>: <problem>") naming the element.
#pragma once

#include <unexmin/sim/description_reader.h>
#include <unexmin/sim/description_types.h>

#include <tinyxml2.h>

#include <Eigen/Core>

#include <set>
#include <string>
#include <vector>

namespace unexmin {
namespace sim {
namespace description {

using LinkNames = std::set<std::string>;

/// The named <link>s of <robot>.
LinkNames parseLinks(const tinyxml2::XMLElement* robot);
/// The <joint>s of <robot> into d.joints, in document order; their links must be in `links`.
void parseJoints(const DescriptionReader& r, const tinyxml2::XMLElement* robot, const LinkNames& links,
                 RobotDescription& d);
/// <hydrodynamics> of the <unexmin> element `ext`: d.base_link, d.hydro, d.hull_box.
void parseHydrodynamics(const DescriptionReader& r, const tinyxml2::XMLElement* ext, const LinkNames& links,
                        RobotDescription& d);
/// The <thruster>s of `ext` into d.thrusters and d.thruster_joints, sorted by id (families of d.thruster_families).
void parseThrusters(const DescriptionReader& r, const tinyxml2::XMLElement* ext, RobotDescription& d);
/// The <fin>s of `ext` into d.fins and d.fin_joints, sorted by id (families of d.fin_families).
void parseFins(const DescriptionReader& r, const tinyxml2::XMLElement* ext, RobotDescription& d);
/// The optional <pendulum> of `ext` (after the hydrodynamics: its mass is checked against the vehicle's).
void parsePendulum(const DescriptionReader& r, const tinyxml2::XMLElement* ext, RobotDescription& d);
/// The optional <vbs> of `ext`, the variable ballast; none: a range of 0 kg.
void parseBallast(const DescriptionReader& r, const tinyxml2::XMLElement* ext, RobotDescription& d);
/// The optional <magnetic> of `ext` (after the thrusters): the robot's own field at its magnetometers; none: zero.
void parseMagnetics(const DescriptionReader& r, const tinyxml2::XMLElement* ext, RobotDescription& d);
/// The <sensor>s of `ext` into d.sensors, in document order; their links must be in `links`.
void parseSensors(const DescriptionReader& r, const tinyxml2::XMLElement* ext, const LinkNames& links,
                  RobotDescription& d);

// Shared by the actuators (description_actuators.cpp).

/// The joint named by attribute `name` of an actuator element (`where` names it); it must exist in d.joints.
const JointInfo& actuatorJoint(const DescriptionReader& r, const RobotDescription& d, const char* name,
                               const std::string& where);
/// The id of an actuator element <tag id="...">: a non-negative integer.
int actuatorId(const DescriptionReader& r, const tinyxml2::XMLElement* e, const std::string& tag);
/// An actuator at `at` [m, body] must lie inside the hull: its box when the description gives one, else its sphere.
void requireInsideHull(const DescriptionReader& r, const RobotDescription& d, const Eigen::Vector3d& at,
                       const std::string& where);
/// Checks that the ids of `ids` (in document order) are 0..n-1 and returns the document indices sorted by id;
/// `what` names the actuators in the error.
std::vector<std::size_t> idOrder(const DescriptionReader& r, const std::vector<int>& ids, const std::string& what);

/// `items` in the order `order` (indices into it).
template <class T>
std::vector<T> reordered(const std::vector<T>& items, const std::vector<std::size_t>& order) {
  std::vector<T> out;
  out.reserve(order.size());
  for (const std::size_t k : order)
    out.push_back(items[k]);
  return out;
}

/// Every <`tag`> child of `ext`, read by `read(element, joint name out)`, appended to `params` with its joint's name
/// in `joints`, then both ordered by id (idOrder: the ids 0 .. n-1, each once).
template <class Params, class Read>
void readActuators(const DescriptionReader& r, const tinyxml2::XMLElement* ext, const char* tag, Read read,
                   std::vector<Params>& params, std::vector<std::string>& joints) {
  std::vector<int> ids;
  for (const auto* e = ext->FirstChildElement(tag); e; e = e->NextSiblingElement(tag)) {
    std::string joint;
    params.push_back(read(e, joint));
    joints.push_back(joint);
    ids.push_back(params.back().id);
  }
  const auto order = idOrder(r, ids, tag);
  params = reordered(params, order);
  joints = reordered(joints, order);
}

}  // namespace description
}  // namespace sim
}  // namespace unexmin

// parseRobotDescription: the XML document, the links and joint tree, then one parser per entity
// (sim/description_entities.h).
#include <unexmin/sim/robot_description.h>

#include <unexmin/sim/description_entities.h>
#include <unexmin/sim/pose.h>

#include <tinyxml2.h>

namespace unexmin {
namespace sim {
namespace description {
namespace {

JointInfo readJoint(const DescriptionReader& r, const tinyxml2::XMLElement* j, const LinkNames& links) {
  JointInfo info;
  info.name = textOf(j, "name");
  const std::string where = "joint '" + info.name + "'";
  info.type = textOf(j, "type");
  info.parent = textOf(r.child(j, "parent", where), "link");
  info.child = textOf(r.child(j, "child", where), "link");
  if (!links.count(info.parent))
    r.fail(where + ": parent link '" + info.parent + "' does not exist");
  if (!links.count(info.child))
    r.fail(where + ": child link '" + info.child + "' does not exist");
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero(), rpy = Eigen::Vector3d::Zero();
  if (const auto* o = j->FirstChildElement("origin")) {
    if (o->Attribute("xyz"))
      xyz = r.vector3(o, "xyz", where + "/origin");
    if (o->Attribute("rpy"))
      rpy = r.vector3(o, "rpy", where + "/origin");
  }
  info.origin = poseFromXyzRpy(xyz, rpy);
  info.xyz = xyz;
  info.rpy = rpy;
  if (const auto* a = j->FirstChildElement("axis")) {
    info.axis = r.vector3(a, "xyz", where + "/axis");
    if (info.axis.norm() < 1e-9)
      r.fail(where + "/axis has zero length");
    info.axis.normalize();
  }
  return info;
}

}  // namespace

LinkNames parseLinks(const tinyxml2::XMLElement* robot) {
  LinkNames links;
  for (const auto* l = robot->FirstChildElement("link"); l; l = l->NextSiblingElement("link"))
    if (l->Attribute("name"))
      links.insert(l->Attribute("name"));
  return links;
}

void parseJoints(const DescriptionReader& r, const tinyxml2::XMLElement* robot, const LinkNames& links,
                 RobotDescription& d) {
  for (const auto* j = robot->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint"))
    d.joints.push_back(readJoint(r, j, links));
}

}  // namespace description

RobotDescription parseRobotDescription(const std::string& xml, const std::string& source) {
  return parseRobotDescription(xml, source, hydro::ThrusterFactory::builtin());
}

RobotDescription parseRobotDescription(const std::string& xml, const std::string& source,
                                       const hydro::ThrusterFactory& thruster_families) {
  using namespace description;
  const DescriptionReader r(source);
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS)
    r.fail(std::string("not valid XML: ") + (doc.ErrorStr() ? doc.ErrorStr() : "?"));
  const auto* robot = doc.FirstChildElement("robot");
  if (!robot)
    r.fail("no <robot> element");

  RobotDescription d;
  d.source = source;
  d.thruster_families = thruster_families;
  d.name = textOf(robot, "name");
  const LinkNames links = parseLinks(robot);
  parseJoints(r, robot, links, d);
  const auto* ext = robot->FirstChildElement("unexmin");
  if (!ext)
    r.fail("no <unexmin> element (hydrodynamics, thrusters, pendulum, vbs)");
  parseHydrodynamics(r, ext, links, d);
  parseThrusters(r, ext, d);
  parseFins(r, ext, d);
  parsePendulum(r, ext, d);
  parseBallast(r, ext, d);
  parseMagnetics(r, ext, d);
  parseSensors(r, ext, links, d);
  return d;
}

}  // namespace sim
}  // namespace unexmin

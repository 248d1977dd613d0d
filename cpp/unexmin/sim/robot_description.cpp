#include <unexmin/sim/robot_description.h>

#include <unexmin/sim/world_config.h>

#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace unexmin {
namespace sim {
namespace {

class Parser {
public:
  explicit Parser(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& what) const { throw ConfigError(source_ + ": " + what); }

  std::vector<double> numbers(const char* text, const std::string& where) const {
    std::vector<double> out;
    if (!text)
      return out;
    std::istringstream in(text);
    std::string tok;
    while (in >> tok) {
      char* end = nullptr;
      const double v = std::strtod(tok.c_str(), &end);
      if (end == tok.c_str() || *end != '\0' || !std::isfinite(v))
        fail(where + ": '" + tok + "' is not a finite number");
      out.push_back(v);
    }
    return out;
  }

  std::vector<double> attrNumbers(const tinyxml2::XMLElement* e, const char* attr, std::size_t count,
                                  const std::string& where) const {
    const char* text = e ? e->Attribute(attr) : nullptr;
    if (!text)
      fail("missing " + where + " attribute '" + attr + "'");
    auto v = numbers(text, where + "@" + attr);
    if (count && v.size() != count)
      fail(where + "@" + attr + " has " + formatNumber(v.size()) + " numbers, expected " + formatNumber(count));
    return v;
  }

  double attr(const tinyxml2::XMLElement* e, const char* name, const std::string& where) const {
    return attrNumbers(e, name, 1, where)[0];
  }

  double attrOr(const tinyxml2::XMLElement* e, const char* name, const std::string& where, double fallback) const {
    return (e && e->Attribute(name)) ? attr(e, name, where) : fallback;
  }

  const tinyxml2::XMLElement* child(const tinyxml2::XMLElement* e, const char* name, const std::string& where) const {
    const auto* c = e->FirstChildElement(name);
    if (!c)
      fail("missing <" + std::string(name) + "> in " + where);
    return c;
  }

  /// Value of <name value="..."/> under e, with `count` numbers.
  std::vector<double> valueOf(const tinyxml2::XMLElement* e, const char* name, std::size_t count,
                              const std::string& where) const {
    return attrNumbers(child(e, name, where), "value", count, where + "/" + name);
  }

  hydro::ParamMap params(const tinyxml2::XMLElement* e, const std::string& where) const {
    hydro::ParamMap out;
    for (const auto* p = e->FirstChildElement("param"); p; p = p->NextSiblingElement("param")) {
      const char* name = p->Attribute("name");
      if (!name)
        fail(where + "/param has no 'name'");
      out[name] = attrNumbers(p, "value", 0, where + "/param[" + name + "]");
    }
    return out;
  }

private:
  std::string source_;
};

Eigen::Vector3d vec(const std::vector<double>& v) {
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

std::string xyz(const Eigen::Vector3d& v) {
  return "(" + formatNumber(v.x()) + ", " + formatNumber(v.y()) + ", " + formatNumber(v.z()) + ")";
}

/// The id of an actuator element <tag id="...">: a non-negative integer.
int actuatorId(const Parser& p, const tinyxml2::XMLElement* e, const std::string& tag) {
  const double id = p.attr(e, "id", "<" + tag + ">");
  if (id < 0 || id != std::floor(id))
    p.fail("<" + tag + ">@id must be a non-negative integer");
  return static_cast<int>(id);
}

/// Sorts actuators (and their joints, same order) by id; the ids must be 0..n-1. `what` names them in the error.
template <class Params>
void sortById(const Parser& p, std::vector<Params>& items, std::vector<std::string>& joints, const std::string& what) {
  std::vector<std::size_t> order(items.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return items[a].id < items[b].id; });
  std::vector<Params> sorted;
  std::vector<std::string> sorted_joints;
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (items[order[k]].id != static_cast<int>(k))
      p.fail(what + " ids must be 0.." + formatNumber(order.size() - 1) + " without gaps or repeats");
    sorted.push_back(items[order[k]]);
    sorted_joints.push_back(joints[order[k]]);
  }
  items = sorted;
  joints = sorted_joints;
}

/// An actuator at `at` [m, body] must lie inside the hull: its box when the description gives one, else its sphere.
void requireInsideHull(const Parser& p, const RobotDescription& d, const Eigen::Vector3d& at,
                       const std::string& where) {
  constexpr double kSlack = 1e-6;  // [m] rounding of the expanded description
  if (d.hull_box.minCoeff() > 0.0) {
    const Eigen::Vector3d half = 0.5 * d.hull_box;
    if ((at.cwiseAbs() - half).maxCoeff() > kSlack)
      p.fail(where + ": position " + xyz(at) +
             " [m] is outside the hull's bounding box (accepted: |x| <= " + formatNumber(half.x()) +
             ", |y| <= " + formatNumber(half.y()) + ", |z| <= " + formatNumber(half.z()) + " [m])");
  } else if (d.hydro.radius > 0.0 && at.norm() > d.hydro.radius + kSlack) {
    p.fail(where + ": position " + xyz(at) +
           " [m] is outside the hull (accepted: distance from the centre <= " + formatNumber(d.hydro.radius) + " [m])");
  }
}

/// <fin> elements (docs/robot_description.md): pose from the joint, model by family name, limits required.
template <class JointLookup, class InsideHull>
void parseFins(const Parser& p, const tinyxml2::XMLElement* ext, RobotDescription& d, JointLookup joint,
               InsideHull inside_hull) {
  for (const auto* f = ext->FirstChildElement("fin"); f; f = f->NextSiblingElement("fin")) {
    const int id = actuatorId(p, f, "fin");
    const std::string fw = "<fin id=" + formatNumber(id) + ">";
    hydro::FinParams fp;
    fp.id = id;
    const JointInfo& j = joint(f->Attribute("joint"), fw);
    // The joint frame in the body frame: origin = centre of pressure, axis = span, x = chord at angle 0.
    const Eigen::Isometry3d frame = d.linkPose(j.parent) * j.origin;
    fp.axis = frame.linear() * j.axis;
    fp.chord = frame.linear().col(0);
    fp.position = frame.translation();
    inside_hull(fp.position, fw);
    const auto* model = f->FirstChildElement("model");
    if (!model)
      p.fail(fw + ": missing <model type=...> (a fin lift family, e.g. linear_lift)");
    fp.model = model->Attribute("type") ? model->Attribute("type") : "";
    fp.model_params = p.params(model, fw + "/model");
    const auto* area = f->FirstChildElement("area");
    if (!area)
      p.fail(fw + ": missing <area value=...> (planform area > 0 [m^2])");
    fp.area = p.attr(area, "value", fw + "/area");
    const auto* angle = f->FirstChildElement("angle");
    if (!angle || !angle->Attribute("min") || !angle->Attribute("max"))
      p.fail(fw + ": missing <angle min=... max=...> (limits [rad], -pi/2 <= min <= 0 <= max <= pi/2)");
    fp.min_angle = p.attr(angle, "min", fw + "/angle");
    fp.max_angle = p.attr(angle, "max", fw + "/angle");
    const auto* rate = f->FirstChildElement("rate");
    if (!rate)
      p.fail(fw + ": missing <rate value=...> (largest fin speed > 0 [rad/s])");
    fp.rate = p.attr(rate, "value", fw + "/rate");
    if (const auto* to = f->FirstChildElement("timeout"))
      fp.timeout = p.attr(to, "value", fw + "/timeout");
    try {
      hydro::Fin check(fp, d.fin_families);
    } catch (const ParameterError& e) {
      p.fail(fw + ": " + e.what());
    }
    d.fins.push_back(fp);
    d.fin_joints.push_back(j.name);
  }
  sortById(p, d.fins, d.fin_joints, "fin");
}

}  // namespace

Eigen::Isometry3d RobotDescription::linkPose(const std::string& link) const {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  std::string current = link;
  for (std::size_t guard = 0; current != base_link && guard <= joints.size(); ++guard) {
    const auto it = std::find_if(joints.begin(), joints.end(), [&](const JointInfo& j) { return j.child == current; });
    if (it == joints.end())
      throw ConfigError(source + ": link '" + link + "' is not connected to '" + base_link + "'");
    pose = it->origin * pose;
    current = it->parent;
  }
  if (current != base_link)
    throw ConfigError(source + ": joint loop above link '" + link + "'");
  return pose;
}

std::vector<std::string> RobotDescription::movableJoints() const {
  std::vector<std::string> out;
  for (const auto& j : joints)
    if (j.type != "fixed")
      out.push_back(j.name);
  return out;
}

RobotDescription parseRobotDescription(const std::string& xml, const std::string& source) {
  return parseRobotDescription(xml, source, hydro::ThrusterFactory::builtin());
}

RobotDescription parseRobotDescription(const std::string& xml, const std::string& source,
                                       const hydro::ThrusterFactory& thruster_families) {
  Parser p(source);
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS)
    p.fail(std::string("not valid XML: ") + (doc.ErrorStr() ? doc.ErrorStr() : "?"));
  const auto* robot = doc.FirstChildElement("robot");
  if (!robot)
    p.fail("no <robot> element");

  RobotDescription d;
  d.source = source;
  d.thruster_families = thruster_families;
  d.name = robot->Attribute("name") ? robot->Attribute("name") : "";

  std::map<std::string, bool> links;
  for (const auto* l = robot->FirstChildElement("link"); l; l = l->NextSiblingElement("link"))
    if (l->Attribute("name"))
      links[l->Attribute("name")] = true;

  for (const auto* j = robot->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    JointInfo info;
    info.name = j->Attribute("name") ? j->Attribute("name") : "";
    const std::string where = "joint '" + info.name + "'";
    info.type = j->Attribute("type") ? j->Attribute("type") : "";
    const auto* parent = p.child(j, "parent", where);
    const auto* childl = p.child(j, "child", where);
    info.parent = parent->Attribute("link") ? parent->Attribute("link") : "";
    info.child = childl->Attribute("link") ? childl->Attribute("link") : "";
    if (!links.count(info.parent))
      p.fail(where + ": parent link '" + info.parent + "' does not exist");
    if (!links.count(info.child))
      p.fail(where + ": child link '" + info.child + "' does not exist");
    Eigen::Vector3d xyz = Eigen::Vector3d::Zero(), rpy = Eigen::Vector3d::Zero();
    if (const auto* o = j->FirstChildElement("origin")) {
      if (o->Attribute("xyz"))
        xyz = vec(p.attrNumbers(o, "xyz", 3, where + "/origin"));
      if (o->Attribute("rpy"))
        rpy = vec(p.attrNumbers(o, "rpy", 3, where + "/origin"));
    }
    info.origin = poseFromXyzRpy(xyz, rpy);
    if (const auto* a = j->FirstChildElement("axis")) {
      info.axis = vec(p.attrNumbers(a, "xyz", 3, where + "/axis"));
      if (info.axis.norm() < 1e-9)
        p.fail(where + "/axis has zero length");
      info.axis.normalize();
    }
    d.joints.push_back(info);
  }
  auto joint = [&](const char* name, const std::string& where) -> const JointInfo& {
    if (!name)
      p.fail(where + " has no 'joint' attribute");
    const auto it = std::find_if(d.joints.begin(), d.joints.end(), [&](const JointInfo& j) { return j.name == name; });
    if (it == d.joints.end())
      p.fail(where + ": joint '" + std::string(name) + "' does not exist");
    return *it;
  };

  const auto* ext = robot->FirstChildElement("unexmin");
  if (!ext)
    p.fail("no <unexmin> element (hydrodynamics, thrusters, pendulum, vbs)");

  const auto* hyd = p.child(ext, "hydrodynamics", "<unexmin>");
  const std::string hw = "<hydrodynamics>";
  d.base_link = hyd->Attribute("link") ? hyd->Attribute("link") : "";
  if (!links.count(d.base_link))
    p.fail(hw + "@link '" + d.base_link + "' is not a link of the robot");
  auto& h = d.hydro;
  h.mass = p.valueOf(hyd, "mass", 1, hw)[0];
  h.volume = p.valueOf(hyd, "volume", 1, hw)[0];
  h.radius = p.valueOf(hyd, "radius", 1, hw)[0];
  h.center_of_gravity = vec(p.attrNumbers(p.child(hyd, "center_of_gravity", hw), "xyz", 3, hw + "/center_of_gravity"));
  h.center_of_buoyancy =
      vec(p.attrNumbers(p.child(hyd, "center_of_buoyancy", hw), "xyz", 3, hw + "/center_of_buoyancy"));
  const auto* inertia = p.child(hyd, "inertia", hw);
  h.inertia = Eigen::Vector3d(p.attr(inertia, "ixx", hw + "/inertia"), p.attr(inertia, "iyy", hw + "/inertia"),
                              p.attr(inertia, "izz", hw + "/inertia"));
  const auto ma = p.valueOf(hyd, "added_mass", 36, hw);
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c)
      h.added_mass(r, c) = ma[6 * r + c];
  const auto dl = p.valueOf(hyd, "linear_damping", 6, hw);
  const auto dq = p.valueOf(hyd, "quadratic_damping", 6, hw);
  for (int i = 0; i < 6; ++i) {
    h.linear_damping[i] = dl[i];
    h.quadratic_damping[i] = dq[i];
  }
  try {
    hydro::validate(h);
  } catch (const ParameterError& e) {
    p.fail(hw + ": " + e.what());
  }
  if (const auto* box = hyd->FirstChildElement("bounding_box")) {
    d.hull_box = vec(p.attrNumbers(box, "size", 3, hw + "/bounding_box"));
    if (!(d.hull_box.minCoeff() > 0.0))
      p.fail(hw + "/bounding_box@size must be three lengths > 0 [m]");
  }
  auto inside_hull = [&](const Eigen::Vector3d& at, const std::string& where) { requireInsideHull(p, d, at, where); };

  for (const auto* t = ext->FirstChildElement("thruster"); t; t = t->NextSiblingElement("thruster")) {
    hydro::ThrusterParams tp;
    tp.id = actuatorId(p, t, "thruster");
    const std::string tw = "<thruster id=" + formatNumber(tp.id) + ">";
    const JointInfo& j = joint(t->Attribute("joint"), tw);
    const Eigen::Isometry3d pose = d.linkPose(j.parent) * j.origin;
    tp.position = pose.translation();
    inside_hull(tp.position, tw);
    tp.axis = pose.linear() * j.axis;
    const auto* dyn = p.child(t, "dynamics", tw);
    tp.dynamics = dyn->Attribute("type") ? dyn->Attribute("type") : "";
    tp.dynamics_params = p.params(dyn, tw + "/dynamics");
    const auto* conv = p.child(t, "conversion", tw);
    tp.conversion = conv->Attribute("type") ? conv->Attribute("type") : "";
    tp.conversion_params = p.params(conv, tw + "/conversion");
    const auto* thrust = p.child(t, "thrust", tw);
    tp.min_thrust = p.attr(thrust, "min", tw + "/thrust");
    tp.max_thrust = p.attr(thrust, "max", tw + "/thrust");
    const auto* cmd = t->FirstChildElement("command");
    tp.min_command = p.attrOr(cmd, "min", tw + "/command", tp.min_thrust);
    tp.max_command = p.attrOr(cmd, "max", tw + "/command", tp.max_thrust);
    if (const auto* to = t->FirstChildElement("timeout"))
      tp.timeout = p.attr(to, "value", tw + "/timeout");
    try {
      hydro::Thruster check(tp, thruster_families);  // validates dynamics/conversion names and parameters
    } catch (const ParameterError& e) {
      p.fail(tw + ": " + e.what());
    }
    d.thrusters.push_back(tp);
    d.thruster_joints.push_back(j.name);
  }
  sortById(p, d.thrusters, d.thruster_joints, "thruster");
  parseFins(p, ext, d, joint, inside_hull);

  if (const auto* pend = ext->FirstChildElement("pendulum")) {
    const std::string pw = "<pendulum>";
    d.pendulum_joint = joint(pend->Attribute("joint"), pw).name;
    d.pendulum.mass = p.attr(pend, "mass", pw);
    d.pendulum.arm = p.attr(pend, "arm", pw);
    d.pendulum.speed = p.attr(pend, "speed", pw);
    d.pendulum.min_angle = p.attr(pend, "min", pw);
    d.pendulum.max_angle = p.attr(pend, "max", pw);
    try {
      hydro::Pendulum check(d.pendulum);
    } catch (const ParameterError& e) {
      p.fail(pw + ": " + e.what());
    }
    if (d.pendulum.mass >= h.mass)
      p.fail(pw + "@mass must be less than the vehicle mass");
  }
  if (const auto* vbs = ext->FirstChildElement("vbs")) {
    const std::string vw = "<vbs>";
    d.vbs.min_mass = p.attr(vbs, "min", vw);
    d.vbs.max_mass = p.attr(vbs, "max", vw);
    if (vbs->Attribute("xyz"))
      d.vbs.position = vec(p.attrNumbers(vbs, "xyz", 3, vw));
    try {
      hydro::Vbs check(d.vbs);
    } catch (const ParameterError& e) {
      p.fail(vw + ": " + e.what());
    }
  } else {
    d.vbs.min_mass = d.vbs.max_mass = 0.0;
  }

  for (const auto* e = ext->FirstChildElement("sensor"); e; e = e->NextSiblingElement("sensor")) {
    SensorSpec sp;
    sp.name = e->Attribute("name") ? e->Attribute("name") : "";
    const std::string sw = "<sensor name='" + sp.name + "'>";
    if (sp.name.empty())
      p.fail("a <sensor> has no 'name'");
    for (const auto& other : d.sensors)
      if (other.name == sp.name)
        p.fail(sw + ": the name is used twice");
    sp.type = e->Attribute("type") ? e->Attribute("type") : "";
    if (sp.type.empty())
      p.fail(sw + " has no 'type'");
    sp.link = e->Attribute("link") ? e->Attribute("link") : "";
    if (!links.count(sp.link))
      p.fail(sw + "@link '" + sp.link + "' is not a link of the robot");
    sp.pose = d.linkPose(sp.link);
    sp.rate = p.attr(e, "rate", sw);
    if (!(sp.rate > 0.0))
      p.fail(sw + "@rate = " + formatNumber(sp.rate) + " must be > 0 [Hz]");
    for (const auto* q = e->FirstChildElement("param"); q; q = q->NextSiblingElement("param")) {
      const char* key = q->Attribute("name");
      const char* value = q->Attribute("value");
      if (!key)
        p.fail(sw + "/param has no 'name'");
      if (!value)
        p.fail(sw + "/param[" + key + "] has no 'value'");
      std::istringstream in(value);
      std::string tok;
      bool numeric = true;
      std::vector<double> numbers;
      while (in >> tok) {
        char* end = nullptr;
        const double v = std::strtod(tok.c_str(), &end);
        if (end == tok.c_str() || *end != '\0')
          numeric = false;
        else if (!std::isfinite(v))
          p.fail(sw + "/param[" + key + "]: '" + tok + "' is not finite");
        numbers.push_back(v);
      }
      if (numeric && !numbers.empty())
        sp.params[key] = numbers;
      else
        sp.text[key] = value;
    }
    d.sensors.push_back(sp);
  }
  return d;
}

}  // namespace sim
}  // namespace unexmin

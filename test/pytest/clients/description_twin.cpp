// sim::parseRobotDescription on the command line, for test/pytest/test_description_twin.py (its Python twin,
// unexmin.description.parse, against it). Reads the expanded robot description (URDF) in the file named by the one
// argument and writes the parsed record as one JSON object on stdout, every number with 17 significant digits (a
// double read back is the same double). A description the parser rejects: its message on stderr, exit code 1.
#include <unexmin/core/error.h>
#include <unexmin/sim/robot_description.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using unexmin::sim::RobotDescription;

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\')
      out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string number(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

template <class Vector>
std::string array(const Vector& v) {
  std::string out = "[";
  for (int i = 0; i < static_cast<int>(v.size()); ++i)
    out += (i ? ", " : "") + number(v[i]);
  return out + "]";
}

std::string matrix(const Eigen::MatrixXd& m) {  // rows, row after row
  std::vector<double> flat;
  for (int r = 0; r < m.rows(); ++r)
    for (int c = 0; c < m.cols(); ++c)
      flat.push_back(m(r, c));
  return array(flat);
}

std::string params(const unexmin::hydro::ParamMap& p) {
  std::string out = "{";
  for (const auto& [key, values] : p)
    out += (out.size() > 1 ? ", " : "") + quoted(key) + ": " + array(values);
  return out + "}";
}

std::string texts(const std::map<std::string, std::string>& p) {
  std::string out = "{";
  for (const auto& [key, value] : p)
    out += (out.size() > 1 ? ", " : "") + quoted(key) + ": " + quoted(value);
  return out + "}";
}

std::string pose(const Eigen::Isometry3d& x) {
  return "\"position\": " + array(Eigen::Vector3d(x.translation())) + ", \"rotation\": " + matrix(x.linear());
}

template <class Items, class Write>
std::string list(const Items& items, Write write) {
  std::string out = "[";
  for (std::size_t i = 0; i < items.size(); ++i)
    out += (i ? ", " : "") + std::string("{") + write(i) + "}";
  return out + "]";
}

std::string hydrodynamics(const RobotDescription& d) {
  const auto& h = d.hydro;
  return "{\"mass\": " + number(h.mass) + ", \"volume\": " + number(h.volume) + ", \"radius\": " + number(h.radius) +
         ", \"center_of_gravity\": " + array(h.center_of_gravity) +
         ", \"center_of_buoyancy\": " + array(h.center_of_buoyancy) + ", \"inertia\": " + array(h.inertia) +
         ", \"added_mass\": " + matrix(h.added_mass) + ", \"linear_damping\": " + array(h.linear_damping) +
         ", \"quadratic_damping\": " + array(h.quadratic_damping) + ", \"hull_box\": " + array(d.hull_box) + "}";
}

std::string thrusters(const RobotDescription& d) {
  return list(d.thrusters, [&](std::size_t i) {
    const auto& t = d.thrusters[i];
    return "\"id\": " + number(t.id) + ", \"joint\": " + quoted(d.thruster_joints[i]) +
           ", \"position\": " + array(t.position) + ", \"axis\": " + array(t.axis) +
           ", \"dynamics\": " + quoted(t.dynamics) + ", \"dynamics_params\": " + params(t.dynamics_params) +
           ", \"conversion\": " + quoted(t.conversion) + ", \"conversion_params\": " + params(t.conversion_params) +
           ", \"min_thrust\": " + number(t.min_thrust) + ", \"max_thrust\": " + number(t.max_thrust) +
           ", \"min_command\": " + number(t.min_command) + ", \"max_command\": " + number(t.max_command) +
           ", \"timeout\": " + number(t.timeout);
  });
}

std::string fins(const RobotDescription& d) {
  return list(d.fins, [&](std::size_t i) {
    const auto& f = d.fins[i];
    return "\"id\": " + number(f.id) + ", \"joint\": " + quoted(d.fin_joints[i]) +
           ", \"position\": " + array(f.position) + ", \"axis\": " + array(f.axis) + ", \"chord\": " + array(f.chord) +
           ", \"model\": " + quoted(f.model) + ", \"model_params\": " + params(f.model_params) +
           ", \"area\": " + number(f.area) + ", \"min_angle\": " + number(f.min_angle) +
           ", \"max_angle\": " + number(f.max_angle) + ", \"rate\": " + number(f.rate) +
           ", \"timeout\": " + number(f.timeout);
  });
}

std::string actuators(const RobotDescription& d) {
  const auto& p = d.pendulum;
  return "\"pendulum\": {\"joint\": " + quoted(d.pendulum_joint) + ", \"mass\": " + number(p.mass) +
         ", \"arm\": " + number(p.arm) + ", \"speed\": " + number(p.speed) + ", \"min_angle\": " + number(p.min_angle) +
         ", \"max_angle\": " + number(p.max_angle) + "}, \"vbs\": {\"min_mass\": " + number(d.vbs.min_mass) +
         ", \"max_mass\": " + number(d.vbs.max_mass) + ", \"position\": " + array(d.vbs.position) + "}";
}

std::string magnetics(const RobotDescription& d) {
  const auto& m = d.magnetics;
  std::string fields = "[";
  for (std::size_t i = 0; i < m.thruster_field.size(); ++i)
    fields += (i ? ", " : "") + array(m.thruster_field[i]);
  return "{\"hard_iron\": " + array(m.hard_iron) + ", \"soft_iron\": " + matrix(m.soft_iron) +
         ", \"thruster_field\": " + fields + "], \"current_coefficient\": " + number(m.current_coefficient) +
         ", \"current_exponent\": " + number(m.current_exponent) + "}";
}

std::string joints(const RobotDescription& d) {
  return list(d.joints, [&](std::size_t i) {
    const auto& j = d.joints[i];
    return "\"name\": " + quoted(j.name) + ", \"type\": " + quoted(j.type) + ", \"parent\": " + quoted(j.parent) +
           ", \"child\": " + quoted(j.child) + ", " + pose(j.origin) + ", \"axis\": " + array(j.axis);
  });
}

std::string sensors(const RobotDescription& d) {
  return list(d.sensors, [&](std::size_t i) {
    const auto& s = d.sensors[i];
    return "\"name\": " + quoted(s.name) + ", \"type\": " + quoted(s.type) + ", \"link\": " + quoted(s.link) + ", " +
           pose(s.pose) + ", \"rate\": " + number(s.rate) + ", \"params\": " + params(s.params) +
           ", \"text\": " + texts(s.text);
  });
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: description_twin <expanded robot description (URDF) file>\n";
    return 2;
  }
  std::ifstream in(argv[1]);
  if (!in) {
    std::cerr << "description_twin: cannot read " << argv[1] << "\n";
    return 2;
  }
  std::stringstream xml;
  xml << in.rdbuf();
  try {
    const RobotDescription d = unexmin::sim::parseRobotDescription(xml.str(), argv[1]);
    std::cout << "{\"name\": " << quoted(d.name) << ", \"base_link\": " << quoted(d.base_link)
              << ", \"hydrodynamics\": " << hydrodynamics(d) << ", \"joints\": " << joints(d)
              << ", \"thrusters\": " << thrusters(d) << ", \"fins\": " << fins(d) << ", " << actuators(d)
              << ", \"magnetics\": " << magnetics(d) << ", \"sensors\": " << sensors(d) << "}\n";
  } catch (const unexmin::ConfigError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}

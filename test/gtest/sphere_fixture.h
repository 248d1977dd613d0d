// Test fixture: a sphere robot described in URDF by the test itself, so the physics tests check the
// engine against closed-form answers for parameters they choose (not against the shipped defaults).
#pragma once

#include <unexmin/sim/robot_description.h>
#include <unexmin/sim/world.h>

#include <cmath>
#include <map>
#include <memory>
#include <sstream>
#include <string>

namespace unexmin {
namespace test {

struct SphereSpec {
  double rho = 1000.0;
  double radius = 0.3;
  double mass = 4.0 / 3.0 * M_PI * 0.3 * 0.3 * 0.3 * 1000.0;        // neutral in fresh water [kg]
  double added_mass = 2.0 / 3.0 * M_PI * 1000.0 * 0.3 * 0.3 * 0.3;  // 1/2 rho V [kg]
  double zg = -0.02;                                                // CoG of the vehicle less pendulum [m]
  double lin[6] = {0.00565, 0.00565, 0.00565, 0.000679, 0.000679, 0.000679};
  double quad[6] = {66.44, 66.44, 66.44, 0.54, 0.54, 0.54};
  double pendulum_mass = 10.0;
  double pendulum_arm = 0.12;
  double pendulum_speed = 0.2;
  std::string thruster_dynamics = "zero_order";
  std::string thruster_params;  // <param .../> lines
  std::string thruster_conversion = "identity";
  std::string conversion_params;  // <param .../> lines
  double thrust_limit = 100.0;

  double volume() const { return 4.0 / 3.0 * M_PI * radius * radius * radius; }
  double inertia() const { return 0.4 * mass * radius * radius; }
};

/// URDF with one +x thruster (id 0) and one +z thruster (id 1) at the centre, a pendulum and a VBS.
inline std::string sphereUrdf(const SphereSpec& s) {
  std::ostringstream o;
  o.precision(17);
  o << "<robot name='T'>\n"
    << "<link name='T/base_link'/><link name='T/t0'/><link name='T/t1'/><link name='T/pend'/>\n"
    << "<joint name='T/t0_joint' type='continuous'><parent link='T/base_link'/><child link='T/t0'/>"
    << "<origin xyz='0 0 0' rpy='0 0 0'/><axis xyz='1 0 0'/></joint>\n"
    << "<joint name='T/t1_joint' type='continuous'><parent link='T/base_link'/><child link='T/t1'/>"
    << "<origin xyz='0 0 0' rpy='0 -1.5707963267948966 0'/><axis xyz='1 0 0'/></joint>\n"
    << "<joint name='T/pendulum_joint' type='revolute'><parent link='T/base_link'/><child link='T/pend'/>"
    << "<axis xyz='0 1 0'/><limit lower='-0.6' upper='0.6' effort='10' velocity='1'/></joint>\n"
    << "<unexmin><hydrodynamics link='T/base_link'>"
    << "<mass value='" << s.mass << "'/><volume value='" << s.volume() << "'/><radius value='" << s.radius << "'/>"
    << "<center_of_gravity xyz='0 0 " << s.zg << "'/><center_of_buoyancy xyz='0 0 0'/>"
    << "<inertia ixx='" << s.inertia() << "' iyy='" << s.inertia() << "' izz='" << s.inertia() << "'/>"
    << "<added_mass value='";
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c)
      o << ((r == c && r < 3) ? s.added_mass : 0.0) << ' ';
  o << "'/><linear_damping value='";
  for (double v : s.lin)
    o << v << ' ';
  o << "'/><quadratic_damping value='";
  for (double v : s.quad)
    o << v << ' ';
  o << "'/></hydrodynamics>\n";
  for (int id = 0; id < 2; ++id)
    o << "<thruster id='" << id << "' joint='T/t" << id << "_joint'><dynamics type='" << s.thruster_dynamics << "'>"
      << s.thruster_params << "</dynamics><conversion type='" << s.thruster_conversion << "'>" << s.conversion_params
      << "</conversion><thrust min='" << -s.thrust_limit << "' max='" << s.thrust_limit
      << "'/><timeout value='0'/></thruster>\n";
  o << "<pendulum joint='T/pendulum_joint' mass='" << s.pendulum_mass << "' arm='" << s.pendulum_arm << "' speed='"
    << s.pendulum_speed << "' min='-0.6' max='0.6'/>\n"
    << "<vbs min='-2' max='2' xyz='0 0 0'/>\n"
    << "</unexmin></robot>\n";
  return o.str();
}

/// Open water (no meshes) deep enough for any test, one robot at `xyz`, optional current.
inline sim::WorldConfig openWater(const SphereSpec& s, const Eigen::Vector3d& xyz = Eigen::Vector3d(0, 0, -100)) {
  sim::WorldConfig w;
  w.file = "(test world)";
  w.name = "open_water";
  w.water_density = s.rho;
  w.surface_z = 0.0;
  w.current.speed = {0.0, 0.0, 1.0, 0.0, 0.0};
  w.current.horizontal_angle = {0.0, -M_PI, M_PI, 0.0, 0.0};
  w.current.vertical_angle = {0.0, -0.5, 0.5, 0.0, 0.0};
  sim::RobotSpawn spawn;
  spawn.name = "T";
  spawn.pose.translation() = xyz;
  w.robots.push_back(spawn);
  return w;
}

/// The world of `w` with the sphere of `s`, its thrusters' families looked up in `families`.
inline std::unique_ptr<sim::World> makeWorld(
    const sim::WorldConfig& w, const SphereSpec& s, std::uint64_t seed = 1, double dt = 0.002,
    const hydro::ThrusterFactory& families = hydro::ThrusterFactory::builtin()) {
  std::map<std::string, sim::RobotDescription> d;
  d.emplace("T", sim::parseRobotDescription(sphereUrdf(s), "(test sphere)", families));
  return std::make_unique<sim::World>(w, d, 1, dt, seed);
}

/// Run for `seconds` of sim time.
inline void runFor(sim::World& world, double seconds) {
  const auto n = static_cast<std::uint64_t>(std::llround(seconds / world.dt()));
  for (std::uint64_t i = 0; i < n; ++i)
    world.step();
}

}  // namespace test
}  // namespace unexmin

// The BlueROV2 Heavy and REMUS 100 descriptions (urdf/) in the simulator core, against closed forms computed here
// from the published parameters (written here, so that a wrong number in the xacro files fails too): von Benzon et
// al. 2022 for the ROV, Prestero 2001 for the AUV. No roscore; the descriptions are expanded with xacro.
#include "expect_error.h"
#include "xacro_fixture.h"

#include <unexmin/sim/robot_description.h>
#include <unexmin/sim/world.h>
#include <unexmin/sim/world_config.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

/// The message of the error of type `type` that `expr` throws equals `message`.
#define EXPECT_ERROR(expr, type, message) EXPECT_EQ(unexmin::test::thrownMessage<type>([&] { (void)(expr); }), message)

namespace {

using unexmin::sim::RobotDescription;
using unexmin::sim::World;
using unexmin::test::expand;

constexpr double kG = 9.81;

/// One robot `name` of description `xml` at 100 m depth in still water of density rho [kg/m^3].
std::unique_ptr<World> openWater(const std::string& xml, const std::string& name, double rho, double dt = 0.002) {
  unexmin::sim::WorldConfig w;
  w.file = "(test world)";
  w.name = "open_water";
  w.water_density = rho;
  w.surface_z = 0.0;
  unexmin::sim::RobotSpawn spawn;
  spawn.name = name;
  spawn.pose.translation() = Eigen::Vector3d(0, 0, -100);
  w.robots.push_back(spawn);
  std::map<std::string, RobotDescription> d;
  d.emplace(name, unexmin::sim::parseRobotDescription(xml, "(" + name + ")"));
  return std::make_unique<World>(w, d, 1, dt, 1);
}

/// Pitch angle [rad], positive nose down (a rotation about body +y), and the pitch rate [rad/s].
std::pair<double, double> pitchAndRate(const World& world) {
  const auto s = world.robot(0).state();
  const Eigen::Vector3d x = s.pose.linear().col(0);
  return {std::atan2(-x.z(), std::hypot(x.x(), x.y())), (s.pose.linear().transpose() * s.angular_velocity).y()};
}

/// T200 command: pulse width offset from neutral [us] (1500 us is 0) for a signed offset from the dead band
/// (-24..24 us), clamped to -400..400 (1100..1900 us).
double pulse(double offset) {
  return std::clamp(offset >= 0.0 ? 24.0 + offset : -24.0 + offset, -400.0, 400.0);
}

/// The ROV's four vertical thrusters (4, 5 front at x = +0.12 m; 6, 7 rear) holding the pitch at 0 by a PD law: the
/// hull's Munk moment (Z_wdot - X_udot) u w turns it over at speed otherwise (about 10 N m/rad at 0.9 m/s against
/// 1.3 N m/rad of buoyancy), and the paper's benchmark flies under attitude control as well. Gains [us/rad],
/// [us s/rad]: about 100 N m/rad and 14 N m s/rad.
void holdPitch(const World& world, std::vector<double>& thrusts) {
  const auto [pitch, rate] = pitchAndRate(world);
  const double u = std::clamp(2000.0 * pitch + 300.0 * rate, -370.0, 370.0);
  thrusts[4] = thrusts[5] = pulse(u);  // nose down: front thrusters up
  thrusts[6] = thrusts[7] = pulse(-u);
}

/// Run for `seconds`, re-sending thruster and fin commands (a pulse width offset [us] or rpm, an angle [rad]) every
/// step; with `pitch_hold` the ROV's vertical thrusters hold its pitch (holdPitch).
void run(World& world, double seconds, std::vector<double> thrusts, const std::vector<double>& fins = {},
         bool pitch_hold = false) {
  auto& robot = world.robot(0);
  const auto n = static_cast<long>(std::llround(seconds / world.dt()));
  for (long i = 0; i < n; ++i) {
    if (pitch_hold)
      holdPitch(world, thrusts);
    for (std::size_t k = 0; k < thrusts.size(); ++k)
      ASSERT_TRUE(robot.thruster(k).setCommand(thrusts[k], world.time()));
    for (std::size_t k = 0; k < fins.size(); ++k)
      ASSERT_TRUE(robot.fin(k).setCommand(fins[k], world.time()));
    world.step();
  }
}

Eigen::Vector3d bodyVelocity(const World& world) {
  const auto s = world.robot(0).state();
  return s.pose.linear().transpose() * s.linear_velocity;
}

/// Root of d_l x + d_q x^2 = f, x >= 0.
double terminal(double f, double dl, double dq) {
  return (-dl + std::sqrt(dl * dl + 4.0 * dq * f)) / (2.0 * dq);
}

// ---------------------------------------------------------------------------------------------- BlueROV2 Heavy
// von Benzon et al. 2022, parameter table.
constexpr double kRovMass = 13.5, kRovVolume = 0.0134, kRovIz = 0.37, kRovAddedR = 0.2215;
constexpr double kXu = 13.7, kXuu = 141.0, kZw = 33.0, kZww = 190.0, kNrr = 1.5;
// T200 at 16 V, full forward (1900 us, command +400) [N]; thruster placement x = 0.156, y = 0.111 m at 45 deg.
constexpr double kT200Max = 51.5;
const double kYawArm = (0.156 + 0.111) * std::sqrt(0.5);

TEST(BlueRov2Heavy, SteadySurgeAtFullForwardThrust) {
  auto world = openWater(expand("bluerov2_heavy.urdf.xacro", "name:=R"), "R", 1000.0);
  run(*world, 20.0, {400, 400, 400, 400, 0, 0, 0, 0}, {}, true);
  EXPECT_NEAR(pitchAndRate(*world).first, 0.0, 0.02) << "the pitch hold should keep the ROV level";
  const double force = 4.0 * kT200Max * std::sqrt(0.5);
  const double expected = terminal(force, kXu, kXuu);  // 0.969 m/s
  const Eigen::Vector3d v = bodyVelocity(*world);
  EXPECT_NEAR(v.x(), expected, 0.10 * expected);
  EXPECT_NEAR(v.x(), expected, 0.01 * expected) << "the closed form should hold far better than 10 %";
  EXPECT_NEAR(v.y(), 0.0, 0.01);
}

TEST(BlueRov2Heavy, SteadyHeaveAtFullUpwardThrust) {
  auto world = openWater(expand("bluerov2_heavy.urdf.xacro", "name:=R"), "R", 1000.0);
  run(*world, 20.0, {0, 0, 0, 0, 400, 400, 400, 400});
  const double net = 4.0 * kT200Max + (1000.0 * kRovVolume - kRovMass) * kG;  // thrust + buoyancy - weight
  const double expected = terminal(net, kZw, kZww);                           // 0.955 m/s
  const double w = bodyVelocity(*world).z();
  EXPECT_NEAR(w, expected, 0.10 * expected);
  EXPECT_NEAR(w, expected, 0.01 * expected);
}

TEST(BlueRov2Heavy, YawStepFollowsTheQuadraticDampingTimeConstant) {
  // The hull's yaw response: thruster lag removed (zero_order) so that the step in moment is a step.
  std::string xml = expand("bluerov2_heavy.urdf.xacro", "name:=R");
  int lags = 0;
  for (auto at = xml.find("<dynamics type=\"first_order\">"); at != std::string::npos;
       at = xml.find("<dynamics type=\"first_order\">"), ++lags)
    xml.replace(at, xml.find("</dynamics>", at) + 11 - at, "<dynamics type=\"zero_order\"/>");
  ASSERT_EQ(lags, 8);
  auto world = openWater(xml, "R", 1000.0, 0.001);
  // Thrusters 1, 3 at +7.5 N (1600 us: +100), 0, 2 at -7.5 N: 1379 us (-121) interpolates -5.4 N (1400 us) and
  // -15.4 N (1300 us).
  const double pulse_back = -100.0 - 100.0 * (7.5 - 5.4) / (15.4 - 5.4);
  const double moment = 4.0 * 7.5 * kYawArm;
  // (I_z + N_rdot) r' = N - N_rr r^2  ->  r = r_ss tanh(t / T), r_ss = sqrt(N / N_rr), T = (I_z + N_rdot) / sqrt(N
  // N_rr)
  const double r_ss = std::sqrt(moment / kNrr);
  const double time_constant = (kRovIz + kRovAddedR) / std::sqrt(moment * kNrr);  // 0.21 s
  double reached = -1.0;
  const std::vector<double> cmd = {pulse_back, 100, pulse_back, 100, 0, 0, 0, 0};
  for (int i = 0; i < 3000 && reached < 0.0; ++i) {
    run(*world, world->dt(), cmd);
    if (world->robot(0).state().angular_velocity.z() >= std::tanh(1.0) * r_ss)
      reached = world->time();
  }
  ASSERT_GT(reached, 0.0) << "yaw rate never reached tanh(1) r_ss = " << std::tanh(1.0) * r_ss;
  EXPECT_NEAR(reached, time_constant, 0.10 * time_constant);
  run(*world, 3.0, cmd);
  EXPECT_NEAR(world->robot(0).state().angular_velocity.z(), r_ss, 0.02 * r_ss);
}

// ------------------------------------------------------------------------------------------------- REMUS 100
// Prestero 2001, parameter tables (NED derivatives turned into positive FLU magnitudes).
constexpr double kAuvW = 299.0, kAuvB = 306.0, kXprop = 3.86, kAuvXuu = 1.62, kYvv = 1310.0, kNrr2 = 94.0;
constexpr double kM11 = 0.93, kM22 = 35.5, kM26 = -1.93;
constexpr double kCla = 3.12, kSfin = 0.00665, kXfin = -0.638, kD = 0.191, kCydb = 1.2, kXcp = -0.321;

TEST(Remus100, SteadySpeedAtThePapersPropellerSetting) {
  // Trimmed neutral (the thesis' speed runs hold depth with the elevators): water of density W / (V g).
  const double neutral = kAuvW / (kAuvB / 1030.0);
  auto world = openWater(expand("remus100.urdf.xacro", "name:=A"), "A", neutral);
  run(*world, 40.0, {1500.0});
  const double expected = std::sqrt(kXprop / kAuvXuu);  // 1.54 m/s, the speed Prestero states at 1500 rpm
  const double u = bodyVelocity(*world).x();
  EXPECT_NEAR(u, 1.54, 0.15 * 1.54);
  EXPECT_NEAR(u, expected, 0.02 * expected);
}

TEST(Remus100, CannotHoverItRisesInSeaWaterAndSinksInFreshWater) {
  const double volume = kAuvB / (1030.0 * kG);
  for (double rho : {1030.0, 1000.0}) {
    auto world = openWater(expand("remus100.urdf.xacro", "name:=A"), "A", rho);
    run(*world, 60.0, {0.0});
    const double net = rho * volume * kG - kAuvW;  // +7 N in sea water, -1.9 N in fresh water
    const double expected = std::copysign(std::sqrt(std::abs(net) / kYvv), net);  // cross-flow drag Z_ww
    const double vz = world->robot(0).state().linear_velocity.z();
    EXPECT_NEAR(vz, expected, 0.15 * std::abs(expected)) << "rho = " << rho;
    EXPECT_GT(std::abs(vz), 0.02) << "rho = " << rho << ": the AUV must not hover with the propeller stopped";
  }
}

/// Prestero's horizontal-plane steady turn (FLU): surge, sway and yaw balances of the propeller, axial and cross-flow
/// drag, added-mass (Munk) terms, body lift at x_cp and the rudder pair's lift, linearised in the fin angles.
Eigen::Vector3d turnResidual(const Eigen::Vector3d& x, double rudder, double rho, double mass) {
  const double u = x[0], v = x[1], r = x[2];
  const double fins = rho * kSfin * kCla * (u * u * rudder - u * (v + kXfin * r));
  const double lift = -0.5 * rho * kD * kD * kCydb * u * (v + kXcp * r);
  const double ay = kM22 * v + kM26 * r;
  Eigen::Vector3d res;
  res[0] = kXprop - kAuvXuu * u * std::abs(u) + ay * r + mass * v * r;
  res[1] = fins + lift - kYvv * v * std::abs(v) - kM11 * u * r - mass * u * r;
  res[2] = kXfin * fins + kXcp * lift + (kM11 - kM22) * u * v - kM26 * u * r - kNrr2 * r * std::abs(r);
  return res;
}

TEST(Remus100, TurningCircleAtFixedRudder) {
  const double mass = kAuvW / kG;
  const double rho = kAuvW / (kAuvB / 1030.0);  // neutral water, so that the turn stays level
  const double rudder = 10.0 * M_PI / 180.0;
  Eigen::Vector3d x(1.5, 0.0, 0.0);
  for (int it = 0; it < 50; ++it) {
    Eigen::Matrix3d jac;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d h = Eigen::Vector3d::Zero();
      h[k] = 1e-7;
      jac.col(k) = (turnResidual(x + h, rudder, rho, mass) - turnResidual(x - h, rudder, rho, mass)) / 2e-7;
    }
    x -= jac.colPivHouseholderQr().solve(turnResidual(x, rudder, rho, mass));
  }
  ASSERT_LT(turnResidual(x, rudder, rho, mass).norm(), 1e-9);
  const double expected = 2.0 * std::hypot(x[0], x[1]) / std::abs(x[2]);

  auto world = openWater(expand("remus100.urdf.xacro", "name:=A"), "A", rho);
  run(*world, 60.0, {1500.0}, {rudder, rudder, 0.0, 0.0, 0.0, 0.0});
  const auto s = world->robot(0).state();
  const double speed = s.linear_velocity.head<2>().norm();
  const double diameter = 2.0 * speed / std::abs(s.angular_velocity.z());
  EXPECT_NEAR(diameter, expected, 0.15 * expected) << "steady turn u, v, r = " << x.transpose();
  EXPECT_LT(s.angular_velocity.z(), 0.0) << "a positive rudder angle turns the nose to starboard";
}

// -------------------------------------------------------------------------------------------- bad descriptions
/// `xml` with the first `from` after `after` replaced by `to`.
std::string replaced(std::string xml, const std::string& from, const std::string& to, const std::string& after = "") {
  const auto at = xml.find(from, xml.find(after));
  if (at == std::string::npos)
    throw std::runtime_error("not in the description: " + from);
  return xml.replace(at, from.size(), to);
}

TEST(VehicleDescriptions, OutOfRangeParametersStopStartUpWithOneLine) {
  const std::string rov = expand("bluerov2_heavy.urdf.xacro", "name:=R");
  const std::string auv = expand("remus100.urdf.xacro", "name:=A");
  using unexmin::sim::parseRobotDescription;
  EXPECT_ERROR(parseRobotDescription(
                   replaced(rov, "<mass value=\"13.5\"/>", "<mass value=\"-13.5\"/>", "<hydrodynamics"), "rov.urdf"),
               unexmin::ConfigError, "rov.urdf: <hydrodynamics>: hydro: parameter 'mass' = -13.5 must be > 0 [kg]");
  EXPECT_ERROR(parseRobotDescription(replaced(rov, "xyz=\"0.156 0.111 0.0\"", "xyz=\"0.5 0.111 0.0\""), "rov.urdf"),
               unexmin::ConfigError,
               "rov.urdf: <thruster id=0>: position (0.5, 0.111, 0) [m] is outside the hull's bounding box "
               "(accepted: |x| <= 0.2285, |y| <= 0.2875, |z| <= 0.127 [m])");
  const auto open = auv.find("<angle ");
  ASSERT_NE(open, std::string::npos);
  std::string no_limits = auv;
  no_limits.erase(open, auv.find("/>", open) + 2 - open);
  EXPECT_ERROR(
      parseRobotDescription(no_limits, "auv.urdf"), unexmin::ConfigError,
      "auv.urdf: <fin id=0>: missing <angle min=... max=...> (limits [rad], -pi/2 <= min <= 0 <= max <= pi/2)");
  EXPECT_ERROR(parseRobotDescription(replaced(auv, "<rate value=\"1.0\"/>", "<rate value=\"0\"/>"), "auv.urdf"),
               unexmin::ConfigError, "auv.urdf: <fin id=0>: fin 0: parameter 'rate' = 0 must be > 0 [rad/s]");
  EXPECT_ERROR(parseRobotDescription(replaced(auv, "type=\"linear_lift\"", "type=\"flat_plate\""), "auv.urdf"),
               unexmin::ConfigError,
               "auv.urdf: <fin id=0>: fin 0: fin model: unknown type 'flat_plate'; expected one of: linear_lift");
}

TEST(VehicleDescriptions, FinCommandsAreCheckedAndRateLimited) {
  auto world = openWater(expand("remus100.urdf.xacro", "name:=A"), "A", 1030.0);
  auto& fin = world->robot(0).fin(0);
  const double max = fin.params().max_angle, rate = fin.params().rate;
  EXPECT_FALSE(fin.setCommand(std::nan(""), 0.0));
  EXPECT_FALSE(fin.setCommand(max + 0.01, 0.0));
  EXPECT_FALSE(world->robot(0).fin(4).setCommand(0.01, 0.0)) << "the body-lift surface is fixed at 0";
  ASSERT_TRUE(fin.setCommand(max, 0.0));
  fin.update(0.1, 0.1);
  EXPECT_NEAR(fin.angle(), rate * 0.1, 1e-12);
  fin.update(0.2, 10.0);
  EXPECT_NEAR(fin.angle(), max, 1e-12);
  fin.update(5.0, 10.0);  // no command for longer than the timeout: back to 0
  EXPECT_NEAR(fin.angle(), 0.0, 1e-12);
}

}  // namespace

namespace {

TEST(VehicleTeams, TheWorldsRobotsAreSelectedByNameInOrder) {
  auto config = unexmin::sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/tank_team.world");
  ASSERT_EQ(config.robots.size(), 3u);
  const Eigen::Vector3d ux_at = config.robots[2].pose.translation();
  unexmin::sim::selectRobots(config, {"UX_1", "AUV_1"});
  ASSERT_EQ(config.robots.size(), 3u);
  EXPECT_EQ(config.robots[0].name, "UX_1");
  EXPECT_EQ(config.robots[1].name, "AUV_1");
  EXPECT_EQ(config.robots[2].name, "ROV_1");
  EXPECT_TRUE(config.robots[0].pose.translation().isApprox(ux_at)) << "a robot keeps its spawn pose";
  EXPECT_ERROR(unexmin::sim::selectRobots(config, {"GLIDER_1"}), unexmin::ConfigError,
               config.file +
                   ": no robot 'GLIDER_1' in 'robots' (expected one of: UX_1, AUV_1, ROV_1, or <prefix>_<k> of a "
                   "listed robot's prefix)");
  EXPECT_ERROR(unexmin::sim::selectRobots(config, {"AUV_1", "AUV_1"}), unexmin::ConfigError,
               config.file + ": robot 'AUV_1' is selected twice");
}

}  // namespace

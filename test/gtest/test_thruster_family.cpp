// The worked example of docs/adding_a_thruster.md: a dynamics family and a conversion family that exist only in
// the tests (thruster_family_fixture.h: a slew-rate limited rotor, a conversion with a dead band) are registered on
// a copy of the built-in factory, named in a robot description, built with the robot and flown in open water; the
// thrust follows their closed form step by step and the robot reaches the terminal speed of that thrust. And: the same
// description parsed with the built-in families stops with one error naming the thruster, the unknown type and the
// known ones; the families' parameters are checked with errors naming the parameter, its value and the range.
#include "expect_error.h"
#include "sphere_fixture.h"
#include "thruster_family_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace {

using test::contains;
using test::deadbandParams;
using test::deadbandThrust;
using test::kDeadbandGain;
using test::kDeadbandWidth;
using test::kSlewRate;
using test::slewParams;
using test::slewState;
using test::thrownMessage;
using test::withTestFamilies;

/// The test sphere (sphere_fixture.h) whose two thrusters use the test families.
test::SphereSpec slewDeadbandSphere() {
  test::SphereSpec s;
  s.thruster_dynamics = "slew";
  s.thruster_params = slewParams();
  s.thruster_conversion = "deadband";
  s.conversion_params = deadbandParams();
  return s;
}

TEST(ThrusterFamily, ARegisteredFamilyIsNamedInTheDescriptionBuiltAndFlown) {
  const test::SphereSpec s = slewDeadbandSphere();
  const double dt = 0.002;  // [s]
  auto world = test::makeWorld(test::openWater(s), s, 1, dt, withTestFamilies());
  sim::Robot& robot = world->robot(0);
  ASSERT_EQ(robot.thrusterCount(), 2u);
  EXPECT_FALSE(robot.thruster(0).stateIsRotorSpeed());

  const double command = 30.0;  // [unit]: the slew reaches it after command / rate = 1.5 s
  ASSERT_TRUE(robot.thruster(0).setCommand(command, 0.0));
  const int ramp_steps = static_cast<int>(std::lround(command / kSlewRate / dt));
  for (int k = 1; k <= ramp_steps + 50; ++k) {
    world->step();
    const double x = slewState(command, k * dt);
    const double expected = deadbandThrust(x);
    ASSERT_NEAR(robot.thruster(0).state(), x, 1e-9) << "step " << k;
    ASSERT_NEAR(robot.thruster(0).thrust(), expected, 1e-9) << "step " << k;
    ASSERT_NEAR(robot.thrustWrench()[0], expected, 1e-9) << "thruster 0 pushes along body +x";
    ASSERT_EQ(robot.thruster(1).thrust(), 0.0) << "thruster 1 has no command";
  }

  // Flown at the plateau thrust F = gain (command - width) = 14 N: terminal speed d_q v^2 + d_l v = F.
  test::runFor(*world, 60.0);
  const double F = kDeadbandGain * (command - kDeadbandWidth);
  const double dq = s.quad[0], dl = s.lin[0];
  const double expected = (-dl + std::sqrt(dl * dl + 4.0 * dq * F)) / (2.0 * dq);
  EXPECT_NEAR(robot.state().linear_velocity.x(), expected, 0.001 * expected);

  robot.reset();
  EXPECT_EQ(robot.thruster(0).state(), 0.0);
  EXPECT_EQ(robot.thruster(0).thrust(), 0.0);
}

TEST(ThrusterFamily, AnUnknownTypeStopsParsingNamingThrusterTypeAndKnownTypes) {
  const std::string urdf = test::sphereUrdf(slewDeadbandSphere());
  const std::string m = thrownMessage<ConfigError>([&] { sim::parseRobotDescription(urdf, "(test sphere)"); });
  EXPECT_EQ(m,
            "(test sphere): <thruster id=0>: thruster dynamics: unknown type 'slew'; expected one of: "
            "first_order, zero_order");

  hydro::ThrusterFactory dynamics_only = hydro::ThrusterFactory::builtin();
  dynamics_only.dynamics.add<test::SlewDynamics>("slew");
  const std::string c =
      thrownMessage<ConfigError>([&] { sim::parseRobotDescription(urdf, "(test sphere)", dynamics_only); });
  EXPECT_EQ(c,
            "(test sphere): <thruster id=0>: thrust conversion: unknown type 'deadband'; expected one of: "
            "basic, identity, table");
}

TEST(ThrusterFamily, TheFamilyChecksItsParametersNamingParameterValueAndRange) {
  const hydro::ThrusterFactory families = withTestFamilies();
  const auto parse = [&](const test::SphereSpec& s) {
    return thrownMessage<ConfigError>([&] { sim::parseRobotDescription(test::sphereUrdf(s), "(s)", families); });
  };
  test::SphereSpec s = slewDeadbandSphere();
  s.thruster_params = "<param name='rate' value='-1'/>";
  EXPECT_EQ(parse(s), "(s): <thruster id=0>: thruster dynamics 'slew': parameter 'rate' = -1 must be in [1e-06, " +
                          formatNumber(1e6) + "] [unit/s]");

  s = slewDeadbandSphere();
  s.thruster_params = "";
  EXPECT_EQ(parse(s), "(s): <thruster id=0>: thruster dynamics 'slew': missing parameter 'rate' (expected one number)");

  s = slewDeadbandSphere();
  s.conversion_params += "<param name='offset' value='1'/>";
  EXPECT_EQ(parse(s),
            "(s): <thruster id=0>: thrust conversion 'deadband': unknown parameter 'offset' "
            "(accepted: gain, width)");

  s = slewDeadbandSphere();
  s.conversion_params = "<param name='gain' value='0.5 0.6'/><param name='width' value='2'/>";
  EXPECT_TRUE(contains(parse(s), "parameter 'gain' has 2 values, expected one number")) << parse(s);
}

}  // namespace
}  // namespace unexmin

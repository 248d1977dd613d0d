// Thruster dynamics, thrust conversions, their factories and the Thruster (saturation, command
// guard, watchdog, wrench). No ROS: links the hydro core, Eigen and gtest only.
#include <unexmin/hydro/thruster.h>
#include <unexmin/hydro/thruster_factory.h>

#include "expect_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace unexmin {
namespace hydro {
namespace {

/// Runs `f`, expects ParameterError, and returns its message ("" if nothing was thrown).
using unexmin::test::contains;
using unexmin::test::thrownMessage;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// A model of the simulator's families, by the name the robot description gives.
std::unique_ptr<ThrusterDynamics> builtinDynamics(const std::string& type, const ParamMap& params) {
  return ThrusterFactory::builtin().dynamics.create(type, params);
}
std::unique_ptr<ThrustConversion> builtinConversion(const std::string& type, const ParamMap& params) {
  return ThrusterFactory::builtin().conversion.create(type, params);
}

// -------------------------------------------------------------------------------------- dynamics

TEST(ThrusterDynamics, FirstOrderStepReachesOneMinusExpMinusOneAtTau) {
  const double tau = 0.2;
  const double dt = 0.001;
  FirstOrderDynamics dynamics(tau);
  const int steps = static_cast<int>(std::lround(tau / dt));
  double previous = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double x = dynamics.update(1.0, dt);
    ASSERT_GT(x, previous);  // monotonic rise
    ASSERT_LT(x, 1.0);       // no overshoot
    previous = x;
  }
  const double expected = 1.0 - std::exp(-1.0);
  EXPECT_NEAR(dynamics.state(), expected, 0.005 * expected);
  for (int i = 0; i < 2 * steps; ++i) {
    dynamics.update(1.0, dt);
  }
  EXPECT_NEAR(dynamics.state(), 1.0 - std::exp(-3.0), 0.005 * (1.0 - std::exp(-3.0)));
}

TEST(ThrusterDynamics, FirstOrderIsExactForOneBigStep) {
  const double tau = 0.2;
  FirstOrderDynamics one(tau);
  EXPECT_NEAR(one.update(1.0, tau), 1.0 - std::exp(-1.0), 1e-12);
  FirstOrderDynamics ten(tau);
  EXPECT_NEAR(ten.update(-3.0, 10.0 * tau), -3.0 * (1.0 - std::exp(-10.0)), 1e-12);
  // Stable for any step, even 1000 tau (an explicit Euler step would overshoot to -1997).
  FirstOrderDynamics huge(tau);
  EXPECT_NEAR(huge.update(2.0, 1000.0 * tau), 2.0, 1e-12);
  // dt = 0 changes nothing; negative or non-finite dt is a programming error.
  EXPECT_NEAR(huge.update(-5.0, 0.0), 2.0, 1e-12);
  EXPECT_THROW(huge.update(1.0, -0.1), ParameterError);
  EXPECT_THROW(huge.update(1.0, kNaN), ParameterError);
  huge.reset();
  EXPECT_EQ(huge.state(), 0.0);
}

TEST(ThrusterDynamics, FirstOrderDecaysFromAnyStateTowardsTheCommand) {
  // x(t) = u + (x0 - u) e^{-t/tau}
  const double tau = 0.5;
  FirstOrderDynamics d(tau);
  d.update(4.0, 100.0);  // settle at 4
  for (int i = 0; i < 300; ++i) {
    d.update(1.0, 0.001);
  }
  EXPECT_NEAR(d.state(), 1.0 + 3.0 * std::exp(-0.3 / tau), 1e-9);
}

TEST(ThrusterDynamics, ZeroOrderFollowsAtOnce) {
  ZeroOrderDynamics d;
  EXPECT_EQ(d.update(3.5, 0.001), 3.5);
  EXPECT_EQ(d.state(), 3.5);
  EXPECT_EQ(d.update(-1.25, 0.0), -1.25);
  d.reset();
  EXPECT_EQ(d.state(), 0.0);
}

TEST(ThrusterDynamics, FirstOrderRejectsBadTau) {
  const std::string m = thrownMessage([] { FirstOrderDynamics d(-1.0); });
  EXPECT_TRUE(contains(m, "thruster dynamics 'first_order': parameter 'tau' = -1 must be > 0 [s]")) << m;
  EXPECT_TRUE(contains(thrownMessage([] { FirstOrderDynamics d(0.0); }), "'tau'"));
  EXPECT_TRUE(contains(thrownMessage([] { FirstOrderDynamics d(kNaN); }), "'tau'"));
  EXPECT_TRUE(contains(thrownMessage([] { FirstOrderDynamics d(kInf); }), "'tau'"));
}

// ------------------------------------------------------------------------------------ conversion

TEST(ThrustConversion, BasicIsSignSymmetricQuadratic) {
  const double gain = 0.0025;  // N per (rad/s)^2
  BasicConversion c(gain);
  EXPECT_NEAR(c.thrust(100.0), 25.0, 1e-12);  // 0.0025 * 100 * 100
  EXPECT_NEAR(c.thrust(-100.0), -25.0, 1e-12);
  EXPECT_NEAR(c.thrust(0.0), 0.0, 1e-15);
  for (double w : {0.5, 3.0, 47.0, 180.0}) {
    EXPECT_NEAR(c.thrust(-w), -c.thrust(w), 1e-12);
    EXPECT_NEAR(c.thrust(2.0 * w), 4.0 * c.thrust(w), 1e-9);  // quadratic
  }
  // A negative gain reverses the thruster (a pusher mounted backwards).
  EXPECT_NEAR(BasicConversion(-gain).thrust(100.0), -25.0, 1e-12);
  EXPECT_TRUE(contains(thrownMessage([] { BasicConversion b(0.0); }), "'gain'"));
  EXPECT_TRUE(contains(thrownMessage([] { BasicConversion b(kNaN); }), "'gain'"));
}

TEST(ThrustConversion, TableInterpolatesLinearlyAndClamps) {
  TableConversion c({-100.0, 0.0, 50.0, 100.0}, {-40.0, 0.0, 10.0, 50.0});
  EXPECT_NEAR(c.thrust(25.0), 5.0, 1e-12);     // halfway 0 -> 10
  EXPECT_NEAR(c.thrust(75.0), 30.0, 1e-12);    // halfway 10 -> 50
  EXPECT_NEAR(c.thrust(-50.0), -20.0, 1e-12);  // halfway -40 -> 0
  EXPECT_NEAR(c.thrust(60.0), 18.0, 1e-12);    // 10 + 0.2 * 40
  EXPECT_NEAR(c.thrust(50.0), 10.0, 1e-12);    // on a node
  EXPECT_NEAR(c.thrust(-100.0), -40.0, 1e-12);
  EXPECT_NEAR(c.thrust(100.0), 50.0, 1e-12);
  EXPECT_NEAR(c.thrust(250.0), 50.0, 1e-12);  // clamped above
  EXPECT_NEAR(c.thrust(-1e6), -40.0, 1e-12);  // clamped below
}

TEST(ThrustConversion, TableRejectsBadTables) {
  EXPECT_TRUE(contains(thrownMessage([] { TableConversion t({0.0, 0.0, 1.0}, {0.0, 1.0, 2.0}); }), "input"));
  EXPECT_TRUE(
      contains(thrownMessage([] { TableConversion t({0.0, 2.0, 1.0}, {0.0, 1.0, 2.0}); }), "strictly increasing"));
  EXPECT_TRUE(contains(thrownMessage([] { TableConversion t({0.0, 1.0}, {0.0, 1.0, 2.0}); }), "output"));
  EXPECT_TRUE(contains(thrownMessage([] { TableConversion t({1.0}, {1.0}); }), "at least 2"));
  EXPECT_TRUE(contains(thrownMessage([] { TableConversion t({0.0, kNaN}, {0.0, 1.0}); }), "input[1]"));
  EXPECT_TRUE(contains(thrownMessage([] { TableConversion t({0.0, 1.0}, {kInf, 1.0}); }), "output[0]"));
}

// ------------------------------------------------------------------------------------- factories

TEST(ThrusterFactories, BuildEachFamilyByName) {
  auto zero = builtinDynamics("zero_order", {});
  EXPECT_EQ(zero->update(2.0, 0.01), 2.0);
  auto first = builtinDynamics("first_order", {{"tau", {0.1}}});
  EXPECT_NEAR(first->update(1.0, 0.1), 1.0 - std::exp(-1.0), 1e-12);

  EXPECT_NEAR(builtinConversion("identity", {})->thrust(7.5), 7.5, 1e-15);
  EXPECT_NEAR(builtinConversion("basic", {{"gain", {0.01}}})->thrust(-20.0), -4.0, 1e-12);
  auto table = builtinConversion("table", {{"input", {0.0, 10.0}}, {"output", {0.0, 5.0}}});
  EXPECT_NEAR(table->thrust(4.0), 2.0, 1e-12);
}

TEST(ThrusterFactories, UnknownNamesListTheAcceptedOnes) {
  const std::string d = thrownMessage([] { builtinDynamics("second_order", {}); });
  EXPECT_TRUE(contains(d, "'second_order'")) << d;
  EXPECT_TRUE(contains(d, "zero_order")) << d;
  EXPECT_TRUE(contains(d, "first_order")) << d;

  const std::string c = thrownMessage([] { builtinConversion("cubic", {}); });
  EXPECT_TRUE(contains(c, "'cubic'")) << c;
  EXPECT_TRUE(contains(c, "identity")) << c;
  EXPECT_TRUE(contains(c, "basic")) << c;
  EXPECT_TRUE(contains(c, "table")) << c;
}

TEST(ThrusterFactories, BadParametersNameTheParameter) {
  EXPECT_THROW(builtinDynamics("first_order", {}), ParameterError);
  EXPECT_TRUE(contains(thrownMessage([] { builtinDynamics("first_order", {}); }), "'tau'"));
  EXPECT_TRUE(contains(thrownMessage([] { builtinDynamics("first_order", {{"tau", {0.1, 0.2}}}); }), "'tau'"));
  EXPECT_TRUE(
      contains(thrownMessage([] { builtinDynamics("first_order", {{"tau", {-1.0}}}); }), "'tau' = -1 must be > 0 [s]"));
  EXPECT_TRUE(contains(thrownMessage([] { builtinDynamics("first_order", {{"tau", {kNaN}}}); }), "'tau'"));
  EXPECT_TRUE(contains(thrownMessage([] { builtinConversion("basic", {{"k", {0.1}}}); }), "'gain'"));
  EXPECT_TRUE(contains(thrownMessage([] { builtinConversion("basic", {{"gain", {}}}); }), "'gain'"));
  EXPECT_TRUE(contains(thrownMessage([] { builtinConversion("table", {{"input", {0.0, 1.0}}}); }), "'output'"));
  EXPECT_TRUE(contains(thrownMessage([] { builtinConversion("table", {{"output", {0.0, 1.0}}}); }), "'input'"));
}

TEST(ThrusterFactories, TheBuiltinFamiliesAreRegisteredByNameAndListedSorted) {
  const ThrusterFactory f = ThrusterFactory::builtin();
  EXPECT_EQ(f.dynamics.types(), (std::vector<std::string>{"first_order", "zero_order"}));
  EXPECT_EQ(f.conversion.types(), (std::vector<std::string>{"basic", "identity", "table"}));
  EXPECT_TRUE(f.conversion.has("table"));
  EXPECT_FALSE(f.conversion.has("zero_order"));
  EXPECT_EQ(thrownMessage([] { builtinDynamics("second_order", {}); }),
            "thruster dynamics: unknown type 'second_order'; expected one of: first_order, zero_order");
  EXPECT_EQ(thrownMessage([] { builtinConversion("cubic", {}); }),
            "thrust conversion: unknown type 'cubic'; expected one of: basic, identity, table");
  EXPECT_EQ(thrownMessage([] { ThrusterFactory{}.dynamics.create("zero_order", {}); }),
            "thruster dynamics: unknown type 'zero_order'; expected one of: none");
}

TEST(ThrusterFactories, AParameterTheFamilyDoesNotReadIsRejected) {
  EXPECT_EQ(thrownMessage([] { builtinDynamics("first_order", {{"tau", {0.1}}, {"taus", {0.2}}}); }),
            "thruster dynamics 'first_order': unknown parameter 'taus' (accepted: tau)");
  EXPECT_EQ(thrownMessage([] { builtinDynamics("zero_order", {{"tau", {0.1}}}); }),
            "thruster dynamics 'zero_order': unknown parameter 'tau' (accepted: none)");
  EXPECT_EQ(thrownMessage([] { builtinConversion("table", {{"input", {0, 1}}, {"output", {0, 1}}, {"gain", {1}}}); }),
            "thrust conversion 'table': unknown parameter 'gain' (accepted: input, output)");
}

TEST(ThrusterFactories, AnAddedFamilyIsBuiltByNameAndMayReplaceABuiltinOne) {
  ThrusterFactory f = ThrusterFactory::builtin();
  // "scaled": the basic law k w |w| under another name, k in [0, 2]: a family registered by a creator.
  f.conversion.add("scaled", [](ActuatorFamilyParams& p) -> std::unique_ptr<ThrustConversion> {
    return std::make_unique<BasicConversion>(p.scalar("k", 0.0, 2.0, "[N per unit]"));
  });
  EXPECT_EQ(f.conversion.types(), (std::vector<std::string>{"basic", "identity", "scaled", "table"}));
  EXPECT_NEAR(f.conversion.create("scaled", {{"k", {0.5}}})->thrust(4.0), 8.0, 1e-12);  // 0.5 * 4 * |4|
  EXPECT_EQ(thrownMessage([&] { f.conversion.create("scaled", {{"k", {3.0}}}); }),
            "thrust conversion 'scaled': parameter 'k' = 3 must be in [0, 2] [N per unit]");
  EXPECT_EQ(thrownMessage([&] { f.conversion.create("scaled", {}); }),
            "thrust conversion 'scaled': missing parameter 'k' (expected one number)");

  f.dynamics.add<ZeroOrderDynamics>("first_order");  // replaces the built-in family of that name
  EXPECT_EQ(f.dynamics.create("first_order", {})->update(3.0, 0.01), 3.0);
  EXPECT_EQ(ThrusterFactory::builtin().dynamics.create("first_order", {{"tau", {0.1}}})->update(3.0, 0.0), 0.0)
      << "a copy's registrations leave builtin() as it is";

  EXPECT_THROW(f.dynamics.add("", [](ActuatorFamilyParams&) { return std::make_unique<ZeroOrderDynamics>(); }),
               ConfigError);
  EXPECT_THROW(f.dynamics.add("none", ActuatorFamilyFactory<ThrusterDynamics>::Creator()), ConfigError);
}

TEST(RequireScalar, ReturnsTheValueOrNamesTheKey) {
  const ParamMap params{{"tau", {0.25}}, {"table", {1.0, 2.0}}, {"bad", {kInf}}};
  EXPECT_EQ(requireScalar(params, "tau", "model 'x'"), 0.25);
  const std::string missing = thrownMessage([&] { requireScalar(params, "gain", "model 'x'"); });
  EXPECT_TRUE(contains(missing, "model 'x'")) << missing;
  EXPECT_TRUE(contains(missing, "'gain'")) << missing;
  EXPECT_TRUE(contains(thrownMessage([&] { requireScalar(params, "table", "m"); }), "'table' has 2 values"));
  EXPECT_TRUE(contains(thrownMessage([&] { requireScalar(params, "bad", "m"); }), "'bad' = inf"));
}

// -------------------------------------------------------------------------------------- thruster

ThrusterParams identityThruster() {
  ThrusterParams p;
  p.id = 3;
  p.min_thrust = -30.0;
  p.max_thrust = 30.0;
  p.min_command = -50.0;
  p.max_command = 50.0;
  p.timeout = 0.5;
  return p;
}

TEST(Thruster, SaturatesAtTheThrustLimits) {
  Thruster t(identityThruster());
  ASSERT_TRUE(t.setCommand(45.0, 0.0));
  EXPECT_NEAR(t.update(0.01, 0.01), 30.0, 1e-12);
  ASSERT_TRUE(t.setCommand(-45.0, 0.02));
  EXPECT_NEAR(t.update(0.03, 0.01), -30.0, 1e-12);
  ASSERT_TRUE(t.setCommand(12.0, 0.04));
  EXPECT_NEAR(t.update(0.05, 0.01), 12.0, 1e-12);
  EXPECT_NEAR(t.thrust(), 12.0, 1e-12);
}

TEST(Thruster, RejectsNonFiniteAndOutOfRangeCommands) {
  ThrusterParams p = identityThruster();
  p.dynamics = "first_order";
  p.dynamics_params = {{"tau", {0.05}}};
  Thruster t(p);
  ASSERT_TRUE(t.setCommand(10.0, 0.0));
  for (double bad : {kNaN, kInf, -kInf, 50.5, -60.0, 1e300}) {
    EXPECT_FALSE(t.setCommand(bad, 0.001)) << bad;
    EXPECT_EQ(t.command(), 10.0) << bad;
  }
  EXPECT_FALSE(t.setCommand(5.0, kNaN));  // a non-finite stamp is rejected too
  EXPECT_EQ(t.command(), 10.0);
  double time = 0.0;
  for (int i = 0; i < 200; ++i) {
    time += 0.001;
    t.update(time, 0.001);
    ASSERT_TRUE(std::isfinite(t.thrust()));
    ASSERT_TRUE(std::isfinite(t.state()));
  }
  // 0.2 s = 4 tau of a step to 10.
  EXPECT_NEAR(t.thrust(), 10.0 * (1.0 - std::exp(-4.0)), 1e-9);
  EXPECT_TRUE(t.setCommand(50.0, time));  // the limits themselves are accepted
  EXPECT_TRUE(t.setCommand(-50.0, time));
}

TEST(Thruster, WatchdogZeroesTheCommandAfterTimeout) {
  Thruster t(identityThruster());  // zero-order, timeout 0.5 s
  ASSERT_TRUE(t.setCommand(10.0, 1.0));
  EXPECT_NEAR(t.update(1.2, 0.01), 10.0, 1e-12);
  EXPECT_NEAR(t.update(1.5, 0.01), 10.0, 1e-12);  // exactly at the timeout: still alive
  EXPECT_NEAR(t.update(1.51, 0.01), 0.0, 1e-12);
  EXPECT_EQ(t.command(), 0.0);
  // A fresh command revives it.
  ASSERT_TRUE(t.setCommand(-8.0, 2.0));
  EXPECT_NEAR(t.update(2.1, 0.01), -8.0, 1e-12);

  ThrusterParams p = identityThruster();
  p.timeout = 0.0;  // watchdog off
  Thruster forever(p);
  ASSERT_TRUE(forever.setCommand(7.0, 0.0));
  EXPECT_NEAR(forever.update(1000.0, 0.01), 7.0, 1e-12);
}

TEST(Thruster, WatchdogLetsAFirstOrderThrusterDecay) {
  ThrusterParams p = identityThruster();
  p.dynamics = "first_order";
  p.dynamics_params = {{"tau", {0.1}}};
  Thruster t(p);
  ASSERT_TRUE(t.setCommand(20.0, 0.0));
  t.update(0.5, 0.5);  // 5 tau: settled near 20
  const double settled = 20.0 * (1.0 - std::exp(-5.0));
  EXPECT_NEAR(t.thrust(), settled, 1e-9);
  t.update(0.6, 0.1);  // timed out: decays towards 0 for one tau
  EXPECT_NEAR(t.thrust(), settled * std::exp(-1.0), 1e-9);
}

TEST(Thruster, WrenchIsThrustAlongAxisAndPositionCrossForce) {
  ThrusterParams p = identityThruster();
  p.position = Eigen::Vector3d(0.2, 0.1, -0.05);
  p.axis = Eigen::Vector3d(0.0, 0.0, 2.0);  // normalised by the thruster
  Thruster t(p);
  ASSERT_TRUE(t.setCommand(10.0, 0.0));
  t.update(0.0, 0.01);
  const Vector6d w = t.wrench();
  // F = (0, 0, 10); r x F = (ry Fz - rz Fy, rz Fx - rx Fz, rx Fy - ry Fx) = (1, -2, 0).
  EXPECT_NEAR(w[0], 0.0, 1e-12);
  EXPECT_NEAR(w[1], 0.0, 1e-12);
  EXPECT_NEAR(w[2], 10.0, 1e-12);
  EXPECT_NEAR(w[3], 1.0, 1e-12);
  EXPECT_NEAR(w[4], -2.0, 1e-12);
  EXPECT_NEAR(w[5], 0.0, 1e-12);
  EXPECT_NEAR(t.params().axis.norm(), 1.0, 1e-15);

  // A horizontal thruster on the +y side pushing forward yaws the robot clockwise (negative N).
  ThrusterParams side = identityThruster();
  side.position = Eigen::Vector3d(0.0, 0.25, 0.0);
  side.axis = Eigen::Vector3d(1.0, 0.0, 0.0);
  Thruster s(side);
  ASSERT_TRUE(s.setCommand(4.0, 0.0));
  s.update(0.0, 0.01);
  EXPECT_NEAR(s.wrench()[5], -0.25 * 4.0, 1e-12);
  EXPECT_NEAR(s.wrench()[0], 4.0, 1e-12);
}

TEST(Thruster, BasicConversionReachesItsSteadyThrust) {
  ThrusterParams p = identityThruster();
  p.dynamics = "first_order";
  p.dynamics_params = {{"tau", {0.05}}};
  p.conversion = "basic";
  p.conversion_params = {{"gain", {0.002}}};
  p.min_command = -100.0;
  p.max_command = 100.0;
  p.min_thrust = -100.0;
  p.max_thrust = 100.0;
  p.timeout = 0.0;
  Thruster t(p);
  ASSERT_TRUE(t.setCommand(-80.0, 0.0));
  t.update(1.0, 1.0);  // 20 tau
  EXPECT_NEAR(t.thrust(), -0.002 * 80.0 * 80.0, 1e-6);
  EXPECT_NEAR(t.state(), -80.0, 1e-6);
}

TEST(Thruster, ResetZeroesEverything) {
  ThrusterParams p = identityThruster();
  p.dynamics = "first_order";
  p.dynamics_params = {{"tau", {0.1}}};
  Thruster t(p);
  ASSERT_TRUE(t.setCommand(20.0, 0.0));
  t.update(0.1, 0.1);
  ASSERT_GT(t.thrust(), 1.0);
  t.reset();
  EXPECT_EQ(t.command(), 0.0);
  EXPECT_EQ(t.thrust(), 0.0);
  EXPECT_EQ(t.state(), 0.0);
  EXPECT_EQ(t.wrench().cwiseAbs().maxCoeff(), 0.0);
}

TEST(Thruster, ConstructorValidatesGeometryLimitsAndFamilies) {
  ThrusterParams p = identityThruster();
  p.axis = Eigen::Vector3d::Zero();
  EXPECT_TRUE(contains(thrownMessage([&] { Thruster t(p); }), "thruster 3: parameter 'axis'"));

  p = identityThruster();
  p.min_thrust = 40.0;
  const std::string m = thrownMessage([&] { Thruster t(p); });
  EXPECT_TRUE(contains(m, "'min_thrust' = 40 must be <= 'max_thrust' = 30")) << m;

  p = identityThruster();
  p.min_command = 1.0;
  p.max_command = -1.0;
  EXPECT_TRUE(contains(thrownMessage([&] { Thruster t(p); }), "'min_command'"));

  p = identityThruster();
  p.position.x() = kNaN;
  EXPECT_TRUE(contains(thrownMessage([&] { Thruster t(p); }), "'position'"));

  p = identityThruster();
  p.dynamics = "first_order";  // tau missing
  EXPECT_TRUE(contains(thrownMessage([&] { Thruster t(p); }), "'tau'"));

  p = identityThruster();
  p.conversion = "lookup";
  EXPECT_TRUE(contains(thrownMessage([&] { Thruster t(p); }), "'lookup'"));

  Thruster ok(identityThruster());
  EXPECT_THROW(ok.update(kNaN, 0.01), ParameterError);
  EXPECT_THROW(ok.update(1.0, -0.01), ParameterError);
}

TEST(Thruster, BuildsItsModelsFromTheGivenFactory) {
  ThrusterFactory f = ThrusterFactory::builtin();
  f.dynamics.add<ZeroOrderDynamics>("instant");
  ThrusterParams p = identityThruster();
  p.dynamics = "instant";
  EXPECT_TRUE(contains(thrownMessage([&] { Thruster t(p); }), "unknown type 'instant'"));
  Thruster t(p, f);
  ASSERT_TRUE(t.setCommand(12.0, 0.0));
  EXPECT_EQ(t.update(0.01, 0.01), 12.0);
  EXPECT_FALSE(t.stateIsRotorSpeed());
  p.dynamics = "zero_order";
  p.conversion = "basic";
  p.conversion_params = {{"gain", {0.01}}};
  EXPECT_TRUE(Thruster(p).stateIsRotorSpeed()) << "the basic conversion reads a rotor speed";
}

}  // namespace
}  // namespace hydro
}  // namespace unexmin

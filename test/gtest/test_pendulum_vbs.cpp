// Pendulum (constant-speed travel to a target, limits, mass position) and Vbs (limits).
// No ROS: links the hydro core, Eigen and gtest only.
#include <unexmin/hydro/pendulum.h>

#include "expect_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace unexmin {
namespace hydro {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

using unexmin::test::contains;
using unexmin::test::thrownMessage;

PendulumParams ux1Pendulum() {
  PendulumParams p;
  p.mass = 8.0;
  p.arm = 0.1;
  p.speed = 0.1;
  p.min_angle = -0.5;
  p.max_angle = 0.5;
  return p;
}

/// Steps until the pendulum reaches its target; checks monotonic travel at the set speed on the way.
/// Returns the arrival time [s], or a negative number if it never arrives within `limit` [s].
double travel(Pendulum& pendulum, double dt, double limit) {
  const double start = pendulum.angle();
  const double target = pendulum.target();
  const double direction = target > start ? 1.0 : -1.0;
  double t = 0.0;
  double previous = start;
  while (t < limit) {
    pendulum.update(dt);
    t += dt;
    const double a = pendulum.angle();
    EXPECT_GE(direction * (a - previous), 0.0) << "moved backwards at t = " << t;
    EXPECT_LE(direction * (a - target), 0.0) << "overshot at t = " << t;
    EXPECT_LE(std::abs(pendulum.velocity()), pendulum.params().speed * (1.0 + 1e-12)) << "t = " << t;
    if (a == target)  // it lands exactly on the target by design
    {
      return t;
    }
    EXPECT_NEAR(pendulum.velocity(), direction * pendulum.params().speed, 1e-9) << "t = " << t;
    previous = a;
  }
  return -1.0;
}

// -------------------------------------------------------------------------------------- pendulum

TEST(Pendulum, ReachesTargetInAngleOverSpeedWithinOneStep) {
  for (double dt : {0.001, 0.01, 0.03}) {
    for (double target : {0.3, -0.45, 0.0123}) {
      Pendulum p(ux1Pendulum());
      ASSERT_TRUE(p.setTarget(target));
      const double expected = std::abs(target) / p.params().speed;
      const double arrival = travel(p, dt, 10.0);
      ASSERT_GT(arrival, 0.0) << "never arrived, dt = " << dt << " target = " << target;
      EXPECT_GE(arrival, expected - 1e-9) << "dt = " << dt << " target = " << target;  // not faster than speed
      EXPECT_LE(arrival, expected + dt + 1e-9) << "dt = " << dt << " target = " << target;
      // Locked: further updates keep it there with zero velocity.
      for (int i = 0; i < 10; ++i) {
        p.update(dt);
        EXPECT_EQ(p.angle(), target);
        EXPECT_EQ(p.velocity(), 0.0);
      }
    }
  }
}

TEST(Pendulum, LastStepVelocityIsTheActualRate) {
  Pendulum p(ux1Pendulum());  // 0.1 rad/s
  ASSERT_TRUE(p.setTarget(0.025));
  p.update(0.2);  // 0.02 rad
  EXPECT_NEAR(p.angle(), 0.02, 1e-15);
  EXPECT_NEAR(p.velocity(), 0.1, 1e-12);
  p.update(0.2);  // only 0.005 rad left: lands on the target
  EXPECT_EQ(p.angle(), 0.025);
  EXPECT_NEAR(p.velocity(), 0.005 / 0.2, 1e-12);
  p.update(0.0);  // no time, no motion
  EXPECT_EQ(p.velocity(), 0.0);
  EXPECT_THROW(p.update(kNaN), ParameterError);
}

TEST(Pendulum, ReversesWhenTheTargetChanges) {
  Pendulum p(ux1Pendulum());
  ASSERT_TRUE(p.setTarget(0.4));
  for (int i = 0; i < 100; ++i)  // 1 s at 0.1 rad/s
  {
    p.update(0.01);
  }
  EXPECT_NEAR(p.angle(), 0.1, 1e-12);
  ASSERT_TRUE(p.setTarget(-0.2));
  const double arrival = travel(p, 0.01, 10.0);
  EXPECT_NEAR(arrival, 0.3 / 0.1, 0.01 + 1e-9);
  EXPECT_EQ(p.angle(), -0.2);
}

TEST(Pendulum, TargetLimitsAreEnforced) {
  Pendulum p(ux1Pendulum());
  EXPECT_TRUE(p.setTarget(0.5));
  EXPECT_TRUE(p.setTarget(-0.5));
  for (double bad : {0.5001, -0.6, 3.0, kNaN, kInf, -kInf}) {
    EXPECT_FALSE(p.setTarget(bad)) << bad;
    EXPECT_EQ(p.target(), -0.5) << bad;
  }
  for (int i = 0; i < 2000; ++i) {
    p.update(0.01);
    ASSERT_GE(p.angle(), -0.5);
  }
  EXPECT_EQ(p.angle(), -0.5);
}

TEST(Pendulum, MassPositionAndItsPitchMoment) {
  Pendulum p(ux1Pendulum());
  const double arm = p.params().arm;
  EXPECT_LT((p.massPosition() - Eigen::Vector3d(0.0, 0.0, -arm)).norm(), 1e-15);  // hangs straight down
  ASSERT_TRUE(p.setTarget(0.3));
  travel(p, 0.01, 10.0);
  const Eigen::Vector3d r = p.massPosition();
  EXPECT_NEAR(r.x(), arm * std::sin(0.3), 1e-15);
  EXPECT_NEAR(r.y(), 0.0, 1e-15);
  EXPECT_NEAR(r.z(), -arm * std::cos(0.3), 1e-15);
  EXPECT_NEAR(r.norm(), arm, 1e-15);
  // Its weight (0, 0, -m g) about the pivot gives M = r_x m g about +y: positive, i.e. nose down in
  // a frame with y left and z up, as the header promises for positive angles.
  const double g = 9.81;
  const Eigen::Vector3d moment = r.cross(Eigen::Vector3d(0.0, 0.0, -p.params().mass * g));
  EXPECT_NEAR(moment.y(), p.params().mass * g * arm * std::sin(0.3), 1e-12);
  EXPECT_GT(moment.y(), 0.0);
  EXPECT_NEAR(moment.x(), 0.0, 1e-12);
}

TEST(Pendulum, ResetReturnsToRest) {
  Pendulum p(ux1Pendulum());
  ASSERT_TRUE(p.setTarget(0.2));
  p.update(1.0);
  p.reset();
  EXPECT_EQ(p.angle(), 0.0);
  EXPECT_EQ(p.target(), 0.0);
  EXPECT_EQ(p.velocity(), 0.0);
}

TEST(Pendulum, ConstructorValidatesParameters) {
  PendulumParams p = ux1Pendulum();
  p.speed = 0.0;
  const std::string m = thrownMessage([&] { Pendulum x(p); });
  EXPECT_TRUE(contains(m, "pendulum: parameter 'speed' = 0 must be > 0 [rad/s]")) << m;

  p = ux1Pendulum();
  p.mass = -1.0;
  EXPECT_TRUE(contains(thrownMessage([&] { Pendulum x(p); }), "'mass'"));
  p = ux1Pendulum();
  p.arm = -0.1;
  EXPECT_TRUE(contains(thrownMessage([&] { Pendulum x(p); }), "'arm'"));
  p = ux1Pendulum();
  p.min_angle = 0.6;
  EXPECT_TRUE(contains(thrownMessage([&] { Pendulum x(p); }), "'min_angle'"));
  p = ux1Pendulum();
  p.min_angle = 0.1;  // 0 outside [0.1, 0.5]
  EXPECT_TRUE(contains(thrownMessage([&] { Pendulum x(p); }), "'min_angle' = 0.1"));
  p = ux1Pendulum();
  p.max_angle = kNaN;
  EXPECT_TRUE(contains(thrownMessage([&] { Pendulum x(p); }), "'max_angle'"));
  p = ux1Pendulum();
  p.speed = kInf;
  EXPECT_TRUE(contains(thrownMessage([&] { Pendulum x(p); }), "'speed'"));
}

// ------------------------------------------------------------------------------------------- vbs

TEST(Vbs, MassLimitsAreEnforced) {
  VbsParams params;
  params.min_mass = -0.5;
  params.max_mass = 1.5;
  Vbs vbs(params);
  EXPECT_EQ(vbs.mass(), 0.0);
  EXPECT_TRUE(vbs.setMass(1.5));
  EXPECT_EQ(vbs.mass(), 1.5);
  EXPECT_TRUE(vbs.setMass(-0.5));
  EXPECT_TRUE(vbs.setMass(0.01));
  for (double bad : {1.5001, -0.51, kNaN, kInf, -kInf}) {
    EXPECT_FALSE(vbs.setMass(bad)) << bad;
    EXPECT_EQ(vbs.mass(), 0.01) << bad;
  }
  vbs.reset();
  EXPECT_EQ(vbs.mass(), 0.0);
}

TEST(Vbs, ConstructorValidatesLimits) {
  VbsParams p;
  p.min_mass = 1.0;
  p.max_mass = -1.0;
  const std::string m = thrownMessage([&] { Vbs v(p); });
  EXPECT_TRUE(contains(m, "vbs: parameter 'min_mass' = 1 must be <= 'max_mass' = -1 [kg]")) << m;

  p = VbsParams();
  p.max_mass = -0.1;  // 0 outside [-1, -0.1]
  EXPECT_TRUE(contains(thrownMessage([&] { Vbs v(p); }), "'max_mass'"));
  p = VbsParams();
  p.min_mass = 0.2;  // 0 outside [0.2, 1]
  EXPECT_TRUE(contains(thrownMessage([&] { Vbs v(p); }), "'min_mass'"));
  p = VbsParams();
  p.position.z() = kNaN;
  EXPECT_TRUE(contains(thrownMessage([&] { Vbs v(p); }), "'position[2]'"));
  EXPECT_NO_THROW(Vbs{VbsParams{}});
}

}  // namespace
}  // namespace hydro
}  // namespace unexmin

// Whole-vehicle physics of the simulator core against closed-form answers computed here.
#include "sphere_fixture.h"

#include <gtest/gtest.h>

using unexmin::test::makeWorld;
using unexmin::test::openWater;
using unexmin::test::runFor;
using unexmin::test::SphereSpec;

namespace {

constexpr double kG = 9.81;

double pitchOf(const Eigen::Isometry3d& pose) {
  // Rotation of the body x axis about world y: positive = nose down (ENU/FLU, right-handed about +y).
  const Eigen::Vector3d x = pose.linear().col(0);
  return std::atan2(-x.z(), std::hypot(x.x(), x.y()));
}

}  // namespace

TEST(WorldPhysics, TerminalSpeedUnderConstantThrust) {
  SphereSpec s;
  auto world = makeWorld(openWater(s), s);
  const double F = 20.0;
  ASSERT_TRUE(world->robot(0).thruster(0).setCommand(F, 0.0));
  runFor(*world, 60.0);
  // d_q v^2 + d_l v = F
  const double dq = s.quad[0], dl = s.lin[0];
  const double expected = (-dl + std::sqrt(dl * dl + 4.0 * dq * F)) / (2.0 * dq);
  const double v = world->robot(0).state().linear_velocity.x();
  EXPECT_NEAR(v, expected, 0.01 * expected);
  EXPECT_NEAR(v, expected, 0.001 * expected) << "terminal speed should be far better than 1 %";
  EXPECT_NEAR(world->robot(0).state().linear_velocity.y(), 0.0, 1e-4);
}

TEST(WorldPhysics, InitialAccelerationIncludesAddedMass) {
  SphereSpec s;
  auto world = makeWorld(openWater(s), s);
  const double F = 20.0;
  world->robot(0).thruster(0).setCommand(F, 0.0);
  world->step();
  const double a = world->robot(0).state().linear_acceleration.x();
  const double expected = F / (s.mass + s.added_mass);
  EXPECT_NEAR(a, expected, 0.01 * expected);
  // Without added mass the answer would be 50 % larger: make sure we are not there.
  EXPECT_LT(a, 0.8 * F / s.mass);
}

TEST(WorldPhysics, NeutralRobotHoldsStation) {
  SphereSpec s;
  auto world = makeWorld(openWater(s), s);
  const Eigen::Vector3d start = world->robot(0).state().pose.translation();
  runFor(*world, 60.0);
  const Eigen::Vector3d drift = world->robot(0).state().pose.translation() - start;
  EXPECT_LT(drift.norm(), 0.01) << "drift " << drift.transpose();
  EXPECT_NEAR(pitchOf(world->robot(0).state().pose), 0.0, 1e-4);
}

TEST(WorldPhysics, PendulumSetsStaticPitch) {
  SphereSpec s;
  s.lin[4] = 20.0;  // settle the pitch oscillation quickly; statics do not depend on damping
  auto world = makeWorld(openWater(s), s);
  const double alpha = 0.4;
  ASSERT_TRUE(world->robot(0).pendulum().setTarget(alpha));
  runFor(*world, 60.0);
  EXPECT_DOUBLE_EQ(world->robot(0).pendulum().angle(), alpha);
  // CoG of the whole vehicle with the pendulum mass at arm*(sin a, 0, -cos a); CoB at the origin.
  const double mp = s.pendulum_mass, L = s.pendulum_arm;
  const double xg = mp * L * std::sin(alpha) / s.mass;
  const double zg = ((s.mass - mp) * s.zg - mp * L * std::cos(alpha)) / s.mass;
  const double expected = std::atan2(xg, -zg);  // CoG straight below CoB
  double mean = 0.0;
  const int n = 1000;
  for (int i = 0; i < n; ++i) {
    world->step();
    mean += pitchOf(world->robot(0).state().pose) / n;
  }
  EXPECT_NEAR(mean, expected, 0.5 * M_PI / 180.0) << "expected " << expected * 180 / M_PI << " deg";
  EXPECT_GT(expected, 5.0 * M_PI / 180.0) << "test must use a pitch large enough to tell models apart";
}

TEST(WorldPhysics, BallastSinksAtPredictedRate) {
  SphereSpec s;
  auto world = makeWorld(openWater(s), s);
  const double mb = 1.0;
  ASSERT_TRUE(world->robot(0).vbs().setMass(mb));
  world->step();
  const double a0 = world->robot(0).state().linear_acceleration.z();
  EXPECT_NEAR(a0, -mb * kG / (s.mass + mb + s.added_mass), 0.01 * mb * kG / (s.mass + mb + s.added_mass));
  runFor(*world, 60.0);
  const double dq = s.quad[2], dl = s.lin[2], W = mb * kG;
  const double vt = (-dl + std::sqrt(dl * dl + 4.0 * dq * W)) / (2.0 * dq);
  EXPECT_NEAR(world->robot(0).state().linear_velocity.z(), -vt, 0.01 * vt);
}

TEST(WorldPhysics, RobotAtRestIsCarriedByCurrent) {
  SphereSpec s;
  for (double& d : s.lin)
    d = 0.0;  // pure quadratic drag has a closed-form spin-up
  auto config = openWater(s);
  const double vc = 0.2;
  config.current.speed = {vc, 0.0, 1.0, 0.0, 0.0};
  auto world = makeWorld(config, s);
  const double M = s.mass + s.added_mass, k = s.quad[0];
  double t = 0.0;
  for (double checkpoint : {5.0, 20.0, 60.0, 300.0}) {
    runFor(*world, checkpoint - t);
    t = checkpoint;
    // v_r(t) = v_r0 / (1 + k |v_r0| t / M), v_r0 = -vc
    const double expected = vc - vc / (1.0 + k * vc * t / M);
    EXPECT_NEAR(world->robot(0).state().linear_velocity.x(), expected, 0.01 * expected) << "t = " << t;
  }
  EXPECT_GT(world->robot(0).state().linear_velocity.x(), 0.95 * vc);
}

TEST(WorldPhysics, SameSeedSameTrajectory) {
  SphereSpec s;
  auto config = openWater(s);
  config.current.speed = {0.1, 0.0, 0.3, 0.05, 0.2};
  config.current.horizontal_angle = {0.5, -M_PI, M_PI, 0.2, 0.1};
  auto run = [&](std::uint64_t seed) {
    auto world = makeWorld(config, s, seed);
    world->robot(0).thruster(0).setCommand(5.0, 0.0);
    runFor(*world, 10.0);
    return world->robot(0).state().pose.translation();
  };
  const Eigen::Vector3d a = run(7), b = run(7), c = run(8);
  EXPECT_EQ(a, b);
  EXPECT_GT((a - c).norm(), 1e-4);

  auto world = makeWorld(config, s, 3);
  world->robot(0).thruster(0).setCommand(5.0, 0.0);
  runFor(*world, 3.0);
  world->reset(7);
  world->robot(0).thruster(0).setCommand(5.0, 0.0);
  runFor(*world, 10.0);
  EXPECT_EQ(world->robot(0).state().pose.translation(), a) << "reset(seed) must reproduce a fresh world";
}

TEST(WorldPhysics, PartlyEmergedSphereFloatsAtCapEquilibrium) {
  SphereSpec s;
  s.mass = 0.5 * s.rho * s.volume();  // half the displacement: floats half out
  s.lin[2] = 50.0;
  auto world = makeWorld(openWater(s, Eigen::Vector3d(0, 0, -1.0)), s);
  runFor(*world, 120.0);
  EXPECT_NEAR(world->robot(0).state().pose.translation().z(), 0.0, 0.01);
}

TEST(WorldPhysics, CommandsAreRejectedAndStateStaysFinite) {
  SphereSpec s;
  auto world = makeWorld(openWater(s), s);
  auto& r = world->robot(0);
  EXPECT_FALSE(r.thruster(0).setCommand(std::nan(""), 0.0));
  EXPECT_FALSE(r.thruster(0).setCommand(INFINITY, 0.0));
  EXPECT_FALSE(r.thruster(0).setCommand(1e9, 0.0));
  EXPECT_FALSE(r.pendulum().setTarget(std::nan("")));
  EXPECT_FALSE(r.pendulum().setTarget(10.0));
  EXPECT_FALSE(r.vbs().setMass(-INFINITY));
  EXPECT_FALSE(r.vbs().setMass(50.0));
  runFor(*world, 1.0);
  const auto st = r.state();
  EXPECT_TRUE(st.pose.matrix().allFinite());
  EXPECT_TRUE(st.linear_velocity.allFinite());
  EXPECT_LT(st.linear_velocity.norm(), 1e-6);
}

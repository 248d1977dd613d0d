// hydro::Fin and the linear_lift family against closed forms: lift and drag of a fin in a known flow, the flow a
// turning body makes at the fin, the rate and angle limits, and every parameter error.
#include "expect_error.h"

#include <unexmin/hydro/fin.h>

#include <gtest/gtest.h>

#include <cmath>

namespace {

using unexmin::ParameterError;
using unexmin::hydro::Fin;
using unexmin::hydro::FinParams;
using unexmin::hydro::Vector6d;
using unexmin::test::thrownMessage;

constexpr double kRho = 1025.0;  // [kg/m^3]

/// A vertical fin (span +z, chord +x) at x = -0.5 m: a rudder. lift slope 3 /rad, drag0 0.01, induced 0.1.
FinParams rudder() {
  FinParams p;
  p.id = 2;
  p.position = Eigen::Vector3d(-0.5, 0.0, 0.0);
  p.axis = Eigen::Vector3d(0, 0, 2);  // normalised by the fin
  p.chord = Eigen::Vector3d(1, 0, 0);
  p.model_params = {{"lift_slope", {3.0}}, {"drag0", {0.01}}, {"induced", {0.1}}};
  p.area = 0.01;
  p.min_angle = -0.3;
  p.max_angle = 0.3;
  p.rate = 0.5;
  p.timeout = 1.0;
  return p;
}

Vector6d surge(double u) {
  Vector6d nu = Vector6d::Zero();
  nu[0] = u;
  return nu;
}

/// Turn the fin to `angle` [rad] (rate-limited: long enough steps).
void turnTo(Fin& fin, double angle) {
  ASSERT_TRUE(fin.setCommand(angle, 0.0));
  fin.update(0.0, 10.0);
  ASSERT_DOUBLE_EQ(fin.angle(), angle);
}

TEST(Fin, LiftAndDragOfADeflectedFinInSurge) {
  Fin fin(rudder());
  const double d = 0.2, u = 2.0;
  turnTo(fin, d);
  EXPECT_NEAR(fin.angleOfAttack(surge(u)), d, 1e-12);
  const double q = 0.5 * kRho * u * u * 0.01;
  const double cl = 3.0 * d, cd = 0.01 + 0.1 * cl * cl;
  const Vector6d w = fin.wrench(surge(u), kRho);
  // The water moves along -x past the fin: drag along -x, lift along (-x) x z = +y.
  EXPECT_NEAR(w[0], -q * cd, 1e-9);
  EXPECT_NEAR(w[1], q * cl, 1e-9);
  EXPECT_NEAR(w[2], 0.0, 1e-12);
  // Moment about the origin of a side force at x = -0.5: N = x F_y.
  EXPECT_NEAR(w[5], -0.5 * q * cl, 1e-9);
  EXPECT_NEAR(w[3], 0.0, 1e-12);
  EXPECT_NEAR(w[4], 0.0, 1e-12);
}

TEST(Fin, SwayAndYawRateChangeTheAngleOfAttack) {
  Fin fin(rudder());
  // Local velocity at the fin (u, v + x r, 0): alpha = -atan((v + x r) / u) at angle 0.
  Vector6d nu = Vector6d::Zero();
  nu[0] = 1.5;
  nu[1] = 0.1;
  nu[5] = 0.4;
  EXPECT_NEAR(fin.angleOfAttack(nu), -std::atan2(0.1 - 0.5 * 0.4, 1.5), 1e-12);
  // Spanwise flow (heave) does not count; still water gives nothing.
  Vector6d heave = Vector6d::Zero();
  heave[2] = 1.0;
  EXPECT_NEAR(fin.wrench(heave, kRho).norm(), 0.0, 1e-12);
  EXPECT_NEAR(fin.wrench(Vector6d::Zero(), kRho).norm(), 0.0, 1e-12);
}

TEST(Fin, LiftIsNormalToTheFlowAndDragAlongIt) {
  Fin fin(rudder());
  turnTo(fin, -0.25);
  Vector6d nu = Vector6d::Zero();
  nu << 1.2, -0.3, 0.0, 0.0, 0.0, 0.1;
  const Eigen::Vector3d flow = -(nu.head<3>() + nu.tail<3>().cross(Eigen::Vector3d(-0.5, 0, 0)));
  const Eigen::Vector3d force = fin.wrench(nu, kRho).head<3>();
  const double alpha = fin.angleOfAttack(nu);
  const double q = 0.5 * kRho * flow.squaredNorm() * 0.01;
  EXPECT_NEAR(force.dot(flow.normalized()), q * (0.01 + 0.1 * std::pow(3.0 * alpha, 2)), 1e-9);
  EXPECT_NEAR(force.cross(flow.normalized()).norm(), q * std::abs(3.0 * alpha), 1e-9);
}

TEST(Fin, CommandsAreRateLimitedCheckedAndTimedOut) {
  Fin fin(rudder());
  EXPECT_FALSE(fin.setCommand(std::nan(""), 0.0));
  EXPECT_FALSE(fin.setCommand(0.31, 0.0));
  EXPECT_FALSE(fin.setCommand(-0.31, 0.0));
  EXPECT_TRUE(fin.setCommand(0.3, 0.0));
  fin.update(0.1, 0.1);
  EXPECT_NEAR(fin.angle(), 0.05, 1e-15);  // rate 0.5 rad/s
  fin.update(0.9, 0.8);
  EXPECT_NEAR(fin.angle(), 0.3, 1e-15);
  fin.update(1.5, 0.1);  // no command for more than 1 s: the command returns to 0
  EXPECT_NEAR(fin.command(), 0.0, 0.0);
  EXPECT_NEAR(fin.angle(), 0.25, 1e-15);
}

TEST(Fin, ParameterErrorsNameTheFinAndTheRange) {
  auto message = [](FinParams p) { return thrownMessage<ParameterError>([&] { Fin fin(p); }); };
  FinParams p = rudder();
  p.area = 0.0;
  EXPECT_EQ(message(p), "fin 2: parameter 'area' = 0 must be > 0 [m^2]");
  p = rudder();
  p.max_angle = -0.1;
  EXPECT_EQ(message(p),
            "fin 2: parameter 'min_angle' = -0.3 and max_angle = -0.1 must satisfy -pi/2 <= min <= 0 <= "
            "max <= pi/2 [rad]");
  p = rudder();
  p.chord = Eigen::Vector3d(0, 0, 1);
  EXPECT_EQ(message(p), "fin 2: parameter 'chord . axis' = 1 must be 0 (the chord is normal to the span axis)");
  p = rudder();
  p.model_params["lift_slope"] = {-1.0};
  EXPECT_EQ(message(p), "fin 2: fin model 'linear_lift': parameter 'lift_slope' = -1 must be finite and >= 0 [1/rad]");
  p = rudder();
  p.model_params["stall"] = {0.3};
  EXPECT_EQ(message(p).rfind("fin 2: fin model 'linear_lift': unknown parameter 'stall'", 0), 0u) << message(p);
}

}  // namespace

// FossenModel, submergedFraction and restoringWrench against closed-form physics.
// No ROS: links the hydro core, Eigen and gtest only.
#include <unexmin/hydro/fossen_model.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

namespace unexmin {
namespace hydro {
namespace {

constexpr double kRho = 1000.0;  // fresh water [kg/m^3]
constexpr double kG = 9.81;      // [m/s^2]
constexpr double kRadius = 0.3;  // UX-1 hull [m]

double sphereVolume(double r) {
  return 4.0 / 3.0 * M_PI * r * r * r;
}

/// A valid parameter set for a 0.6 m sphere; tests change what they need.
HydroParams sphereParams() {
  HydroParams p;
  p.volume = sphereVolume(kRadius);
  p.mass = kRho * p.volume;  // neutral
  p.radius = kRadius;
  p.center_of_gravity = Eigen::Vector3d(0.0, 0.0, -0.05);
  const double i_solid = 0.4 * p.mass * kRadius * kRadius;
  p.inertia = Eigen::Vector3d(i_solid, i_solid, i_solid);
  const double ma = 0.5 * kRho * p.volume;  // potential-flow added mass of a sphere
  p.added_mass.diagonal() << ma, ma, ma, 0.0, 0.0, 0.0;
  p.linear_damping << 1.0, 2.0, 3.0, 4.0, 5.0, 6.0;
  p.quadratic_damping << 10.0, 20.0, 30.0, 40.0, 50.0, 60.0;
  return p;
}

Vector6d randomVector(std::mt19937_64& rng, double half_range) {
  std::uniform_real_distribution<double> u(-half_range, half_range);
  Vector6d v;
  for (int i = 0; i < 6; ++i) {
    v[i] = u(rng);
  }
  return v;
}

/// Random symmetric positive-definite 6x6 matrix with entries of order 10.
Matrix6d randomSpd(std::mt19937_64& rng) {
  Matrix6d b;
  for (int i = 0; i < 6; ++i) {
    b.col(i) = randomVector(rng, 2.0);
  }
  return b * b.transpose() + Matrix6d::Identity();
}

/// Newton-Euler inertial terms of a body with mass m at the body origin and principal inertia i:
/// [m (v_dot + w x v); I w_dot + w x (I w)]. Written with cross products, independent of C_A.
Vector6d rigidBodyInertialTerms(double m, const Eigen::Vector3d& i, const Vector6d& nu, const Vector6d& nu_dot) {
  const Eigen::Vector3d v = nu.head<3>();
  const Eigen::Vector3d w = nu.tail<3>();
  const Eigen::Vector3d iw = i.cwiseProduct(w);
  Vector6d out;
  out.head<3>() = m * (nu_dot.head<3>() + w.cross(v));
  out.tail<3>() = i.cwiseProduct(nu_dot.tail<3>()) + w.cross(iw);
  return out;
}

std::string validationMessage(const HydroParams& p) {
  try {
    validate(p);
  } catch (const ParameterError& e) {
    return e.what();
  }
  return "";
}

// ------------------------------------------------------------------------------------------ C_A

TEST(CoriolisAddedMass, SkewSymmetricAndDoesNoWorkForRandomSpdAddedMass) {
  std::mt19937_64 rng(20240611);
  const Matrix6d ma = randomSpd(rng);
  ASSERT_LT((ma - ma.transpose()).norm(), 1e-12);
  double largest = 0.0;
  for (int k = 0; k < 100; ++k) {
    const Vector6d nu = randomVector(rng, 2.0);
    const Matrix6d c = FossenModel::coriolisAddedMass(ma, nu);
    EXPECT_LT((c + c.transpose()).cwiseAbs().maxCoeff(), 1e-9) << "sample " << k;
    // Kinetic energy T = 1/2 nu^T M_A nu is conserved by the Coriolis term: nu^T C_A(nu) nu = 0.
    EXPECT_NEAR(nu.dot(c * nu), 0.0, 1e-9) << "sample " << k;
    largest = std::max(largest, c.cwiseAbs().maxCoeff());
  }
  EXPECT_GT(largest, 1.0);  // the matrix is not trivially zero
}

TEST(CoriolisAddedMass, MatchesKirchhoffForm) {
  // Kirchhoff: with momenta p = A11 v + A12 w and h = A21 v + A22 w, the Coriolis-centripetal force
  // is C_A nu = [w x p; v x p + w x h] (Fossen 2011, sec. 6.3).
  std::mt19937_64 rng(7);
  const Matrix6d ma = randomSpd(rng);
  for (int k = 0; k < 20; ++k) {
    const Vector6d nu = randomVector(rng, 1.5);
    const Vector6d mnu = ma * nu;
    const Eigen::Vector3d v = nu.head<3>(), w = nu.tail<3>();
    const Eigen::Vector3d p = mnu.head<3>(), h = mnu.tail<3>();
    Vector6d expected;
    expected.head<3>() = w.cross(p);
    expected.tail<3>() = v.cross(p) + w.cross(h);
    const Vector6d got = FossenModel::coriolisAddedMass(ma, nu) * nu;
    EXPECT_LT((got - expected).cwiseAbs().maxCoeff(), 1e-9) << "sample " << k;
  }
}

TEST(CoriolisAddedMass, SphereGivesOmegaCrossMomentumAndNoMoment) {
  // Sphere: M_A = diag(ma, ma, ma, 0, 0, 0), ma = rho V / 2. Then a = ma v and b = 0, so
  // C_A nu = [-S(a) w; -S(a) v] = [-(ma v) x w; -(ma v) x v] = [ma (w x v); 0].
  const double ma = 0.5 * kRho * sphereVolume(kRadius);
  Matrix6d m = Matrix6d::Zero();
  m.diagonal() << ma, ma, ma, 0.0, 0.0, 0.0;
  std::mt19937_64 rng(3);
  for (int k = 0; k < 20; ++k) {
    const Vector6d nu = randomVector(rng, 1.0);
    const Vector6d got = FossenModel::coriolisAddedMass(m, nu) * nu;
    const Eigen::Vector3d v = nu.head<3>(), w = nu.tail<3>();
    // Component by component: ma (w x v) = ma (q w - r v, r u - p w, p v - q u).
    const Eigen::Vector3d expected(ma * (w.y() * v.z() - w.z() * v.y()), ma * (w.z() * v.x() - w.x() * v.z()),
                                   ma * (w.x() * v.y() - w.y() * v.x()));
    EXPECT_LT((got.head<3>() - expected).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LT(got.tail<3>().cwiseAbs().maxCoeff(), 1e-9);
  }
  // A concrete case: surge u = 1 m/s while yawing r = 0.5 rad/s gives ma * (0, 0.5, 0) (sway).
  Vector6d nu;
  nu << 1.0, 0.0, 0.0, 0.0, 0.0, 0.5;
  const Vector6d got = FossenModel::coriolisAddedMass(m, nu) * nu;
  EXPECT_NEAR(got[1], 0.5 * ma, 1e-9);
  EXPECT_NEAR(got[0], 0.0, 1e-12);
}

TEST(CoriolisAddedMass, MunkMomentOfSlenderBodyIsDestabilising) {
  // A body longer along x: m1 (surge) < m3 (heave). Moving with u > 0 and w > 0 (forward and up),
  // C_A nu has the angular part v x (A11 v) = (0, (m1 - m3) u w, 0); the hydrodynamic moment is its
  // negative, (m3 - m1) u w > 0 about +y (left), which pitches the nose down, away from the flow:
  // the classic destabilising Munk moment.
  const double m1 = 5.0, m2 = 40.0, m3 = 40.0, u = 2.0, w = 0.5;
  Matrix6d m = Matrix6d::Zero();
  m.diagonal() << m1, m2, m3, 1.0, 1.0, 1.0;
  Vector6d nu;
  nu << u, 0.0, w, 0.0, 0.0, 0.0;
  const Vector6d hydro_moment = -(FossenModel::coriolisAddedMass(m, nu) * nu);
  EXPECT_NEAR(hydro_moment[4], (m3 - m1) * u * w, 1e-9);
  EXPECT_NEAR(hydro_moment[3], 0.0, 1e-12);
  EXPECT_NEAR(hydro_moment[5], 0.0, 1e-12);
  EXPECT_LT(hydro_moment.head<3>().cwiseAbs().maxCoeff(), 1e-12);  // no force in pure translation
}

// -------------------------------------------------------------------------------------- damping

TEST(FossenModel, DampingMatchesHandComputedValues) {
  const FossenModel model(sphereParams());
  Vector6d nu;
  nu << 1.0, -2.0, 0.5, 0.0, -0.1, 3.0;
  // D_l = (1..6), D_q = (10..60): d_i = Dl_i nu_i + Dq_i |nu_i| nu_i
  Vector6d expected;
  expected << 1.0 * 1.0 + 10.0 * 1.0,  //  11
      2.0 * -2.0 + 20.0 * -4.0,        // -84
      3.0 * 0.5 + 30.0 * 0.25,         //   9
      0.0,                             //   0
      5.0 * -0.1 + 50.0 * -0.01,       //  -1
      6.0 * 3.0 + 60.0 * 9.0;          // 558
  const Vector6d got = model.damping(nu);
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(got[i], expected[i], 1e-12) << "dof " << i;
  }
  EXPECT_NEAR(got[1], -84.0, 1e-12);
  EXPECT_NEAR(got[5], 558.0, 1e-12);
}

TEST(FossenModel, DampingBalancesThrustAtTerminalVelocity) {
  // Steady surge with thrust T: Dl u + Dq u^2 = T, so u = (-Dl + sqrt(Dl^2 + 4 Dq T)) / (2 Dq).
  // With a sphere's quadratic drag Dq = 1/2 rho Cd A (Cd = 0.47 subcritical), A = pi R^2.
  HydroParams p = sphereParams();
  const double dq = 0.5 * kRho * 0.47 * M_PI * kRadius * kRadius;
  const double dl = 2.0;
  p.linear_damping.setConstant(dl);
  p.quadratic_damping.setConstant(dq);
  const FossenModel model(p);
  const double thrust = 40.0;
  const double u = (-dl + std::sqrt(dl * dl + 4.0 * dq * thrust)) / (2.0 * dq);
  Vector6d nu = Vector6d::Zero();
  nu[0] = u;
  EXPECT_NEAR(model.damping(nu)[0], thrust, 1e-9);
  nu[0] = -u;  // odd in the velocity
  EXPECT_NEAR(model.damping(nu)[0], -thrust, 1e-9);
  EXPECT_NEAR(u, 0.761, 1e-3);  // about 0.76 m/s for 40 N: the order of the UX-1's speed
}

// -------------------------------------------------------------------------------------- folding

TEST(FossenModel, SphereFoldsCompletelyAndWrenchIsDampingPlusCurrentInertia) {
  const HydroParams p = sphereParams();
  const FossenModel model(p);
  const double ma = 0.5 * kRho * p.volume;
  EXPECT_NEAR(model.foldedMass(), ma, 1e-9);
  EXPECT_LT(model.foldedInertia().cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(model.residualAddedMass().cwiseAbs().maxCoeff(), 1e-12);

  std::mt19937_64 rng(11);
  for (int k = 0; k < 10; ++k) {
    const Vector6d nu = randomVector(rng, 1.0);
    const Vector6d nu_dot = randomVector(rng, 5.0);
    const Vector6d w0 = model.wrench(nu, nu_dot, Eigen::Vector3d::Zero());
    EXPECT_LT((w0 + model.damping(nu)).cwiseAbs().maxCoeff(), 1e-9);

    // An accelerating current pushes with the added mass: + ma a_c (Froude-Krylov part is in buoyancy).
    const Eigen::Vector3d a_c(0.2, -0.1, 0.05);
    const Vector6d w1 = model.wrench(nu, nu_dot, a_c);
    EXPECT_LT((w1.head<3>() - (-model.damping(nu).head<3>() + ma * a_c)).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LT((w1.tail<3>() + model.damping(nu).tail<3>()).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST(FossenModel, AnisotropicAddedMassLeavesTheExpectedResidual) {
  HydroParams p = sphereParams();
  p.added_mass.setZero();
  p.added_mass.diagonal() << 10.0, 20.0, 30.0, 1.0, 2.0, 3.0;
  p.added_mass(0, 4) = p.added_mass(4, 0) = 0.5;  // surge-pitch coupling
  p.added_mass(1, 2) = p.added_mass(2, 1) = -0.25;
  const FossenModel model(p);

  EXPECT_NEAR(model.foldedMass(), 20.0, 1e-12);  // mean of 10, 20, 30
  EXPECT_LT((model.foldedInertia() - Eigen::Vector3d(1.0, 2.0, 3.0)).cwiseAbs().maxCoeff(), 1e-12);
  Matrix6d expected = Matrix6d::Zero();
  expected(0, 0) = -10.0;
  expected(2, 2) = 10.0;
  expected(0, 4) = expected(4, 0) = 0.5;
  expected(1, 2) = expected(2, 1) = -0.25;
  EXPECT_LT((model.residualAddedMass() - expected).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(FossenModel, FoldedEnginePlusWrenchReproducesFossenInAUniformCurrent) {
  // The folding argument, checked at random states. The engine integrates the rigid body with mass
  // m + m_f and inertia I + I_f, i.e. it supplies the Newton-Euler terms of the folded part on the
  // absolute velocity nu. With an irrotational current of body-frame velocity v_c and world
  // acceleration a_c (body axes: a_cb), nu_r = nu - [v_c; 0] and
  //   v_r_dot = v_dot - a_cb + w x v_c,  w_r_dot = w_dot.
  // Then  wrench(nu_r, nu_r_dot, a_cb) + D(nu_r) nu_r - NE_fold(nu, nu_dot)
  //   must equal Fossen's  -(M_A nu_r_dot + C_A(M_A, nu_r) nu_r).
  HydroParams p = sphereParams();
  std::mt19937_64 rng(99);
  p.added_mass = randomSpd(rng);
  const FossenModel model(p);
  for (int k = 0; k < 50; ++k) {
    const Vector6d nu = randomVector(rng, 1.0);
    const Vector6d nu_dot = randomVector(rng, 3.0);
    const Eigen::Vector3d v_c = randomVector(rng, 0.5).head<3>();
    const Eigen::Vector3d a_cb = randomVector(rng, 0.5).head<3>();
    const Eigen::Vector3d w = nu.tail<3>();

    Vector6d nu_r = nu;
    nu_r.head<3>() -= v_c;
    Vector6d nu_r_dot = nu_dot;
    nu_r_dot.head<3>() += -a_cb + w.cross(v_c);

    const Vector6d engine = -rigidBodyInertialTerms(model.foldedMass(), model.foldedInertia(), nu, nu_dot);
    const Vector6d applied = model.wrench(nu_r, nu_r_dot, a_cb) + model.damping(nu_r);
    const Vector6d fossen = -(p.added_mass * nu_r_dot + FossenModel::coriolisAddedMass(p.added_mass, nu_r) * nu_r);
    EXPECT_LT((engine + applied - fossen).cwiseAbs().maxCoeff(), 1e-9) << "sample " << k;
  }
}

// ---------------------------------------------------------------------------------- validation

TEST(FossenModel, ValidationNamesTheParameter) {
  EXPECT_NO_THROW(validate(sphereParams()));

  HydroParams p = sphereParams();
  p.mass = -1.0;
  EXPECT_THROW(FossenModel{p}, ParameterError);
  EXPECT_NE(validationMessage(p).find("'mass' = -1 must be > 0 [kg]"), std::string::npos) << validationMessage(p);

  p = sphereParams();
  p.volume = std::nan("");
  EXPECT_NE(validationMessage(p).find("'volume'"), std::string::npos);

  p = sphereParams();
  p.radius = -0.1;
  EXPECT_NE(validationMessage(p).find("'radius'"), std::string::npos);

  p = sphereParams();
  p.inertia[2] = 0.0;
  EXPECT_NE(validationMessage(p).find("'inertia[2]'"), std::string::npos);

  p = sphereParams();
  p.added_mass(0, 5) = 1.0;  // not mirrored
  EXPECT_NE(validationMessage(p).find("added_mass(0,5)"), std::string::npos) << validationMessage(p);
  EXPECT_NE(validationMessage(p).find("symmetric"), std::string::npos);

  p = sphereParams();
  p.added_mass(0, 5) = 1.0;
  p.added_mass(5, 0) = 1.0 + 1e-13;  // within the relative tolerance
  EXPECT_NO_THROW(validate(p));

  p = sphereParams();
  p.added_mass(3, 3) = -0.5;
  EXPECT_NE(validationMessage(p).find("added_mass(3,3)"), std::string::npos);

  p = sphereParams();
  p.linear_damping[4] = -1.0;
  EXPECT_NE(validationMessage(p).find("linear_damping[4]"), std::string::npos);

  p = sphereParams();
  p.quadratic_damping[0] = std::numeric_limits<double>::infinity();
  EXPECT_NE(validationMessage(p).find("quadratic_damping[0]"), std::string::npos);

  p = sphereParams();
  p.center_of_buoyancy[1] = std::nan("");
  EXPECT_NE(validationMessage(p).find("center_of_buoyancy[1]"), std::string::npos);
}

// ---------------------------------------------------------------------------- submerged fraction

/// Volume of the part of a sphere of radius r below a plane at height s above its centre, by
/// Simpson's rule on the disc areas pi (r^2 - z^2), z in [-r, min(s, r)].
double numericCapFraction(double s, double r) {
  const double top = std::min(s, r);
  if (top <= -r) {
    return 0.0;
  }
  const int n = 2000;  // even
  const double h = (top + r) / n;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double z = -r + i * h;
    const double area = M_PI * std::max(0.0, r * r - z * z);
    const double weight = (i == 0 || i == n) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    sum += weight * area;
  }
  return (sum * h / 3.0) / sphereVolume(r);
}

TEST(SubmergedFraction, LimitsAndHalf) {
  const double surface = 2.0;
  EXPECT_NEAR(submergedFraction(surface - 10.0, surface, kRadius), 1.0, 1e-12);     // deep
  EXPECT_NEAR(submergedFraction(surface - kRadius, surface, kRadius), 1.0, 1e-12);  // just under
  EXPECT_NEAR(submergedFraction(surface + kRadius, surface, kRadius), 0.0, 1e-12);  // just out
  EXPECT_NEAR(submergedFraction(surface + 5.0, surface, kRadius), 0.0, 1e-12);      // flying
  EXPECT_NEAR(submergedFraction(surface, surface, kRadius), 0.5, 1e-12);            // centre on the surface
}

TEST(SubmergedFraction, CapMatchesNumericalIntegration) {
  const double surface = 0.0;
  for (double s : {-0.29, -0.2, -0.1, -0.03, 0.05, 0.15, 0.25})  // surface height above the centre
  {
    const double z_centre = surface - s;
    const double expected = numericCapFraction(s, kRadius);
    EXPECT_NEAR(submergedFraction(z_centre, surface, kRadius), expected, 1e-9) << "s = " << s;
  }
  // Symmetry: fraction(s) + fraction(-s) = 1.
  EXPECT_NEAR(submergedFraction(-0.1, 0.0, kRadius) + submergedFraction(0.1, 0.0, kRadius), 1.0, 1e-12);
}

TEST(SubmergedFraction, PointHullIsAllOrNothing) {
  EXPECT_EQ(submergedFraction(-1.0, 0.0, 0.0), 1.0);
  EXPECT_EQ(submergedFraction(1.0, 0.0, 0.0), 0.0);
}

// ------------------------------------------------------------------------------------- restoring

TEST(RestoringWrench, UprightNeutralBodyIsInEquilibrium) {
  const double volume = sphereVolume(kRadius);
  const double mass = kRho * volume;
  const Eigen::Quaterniond upright = Eigen::Quaterniond::Identity();
  const Vector6d zero_offsets =
      restoringWrench(upright, mass, Eigen::Vector3d::Zero(), volume, Eigen::Vector3d::Zero(), kRho, kG);
  EXPECT_LT(zero_offsets.cwiseAbs().maxCoeff(), 1e-9);
  // CoG straight below the CoB: still no moment when upright.
  const Vector6d pendulous =
      restoringWrench(upright, mass, Eigen::Vector3d(0, 0, -0.05), volume, Eigen::Vector3d(0, 0, 0.01), kRho, kG);
  EXPECT_LT(pendulous.cwiseAbs().maxCoeff(), 1e-9);
}

TEST(RestoringWrench, RolledAndPitchedBodiesAreRighted) {
  // CoG a distance zg below the CoB (at the origin). Tilted by phi about x, gravity in body axes is
  // R^T (0, 0, -W) = (0, -W sin phi, -W cos phi) and the moment cog x f_w = (-W zg sin phi, 0, 0):
  // opposite to phi, it rights the robot. Same about y for pitch theta: M = -W zg sin theta.
  const double volume = sphereVolume(kRadius);
  const double mass = kRho * volume;
  const double weight = mass * kG;
  const double zg = 0.05;
  const Eigen::Vector3d cog(0.0, 0.0, -zg);
  for (double angle : {-1.0, -0.3, 0.1, 0.4, 1.2}) {
    const Eigen::Quaterniond roll(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()));
    const Vector6d r = restoringWrench(roll, mass, cog, volume, Eigen::Vector3d::Zero(), kRho, kG);
    EXPECT_NEAR(r[3], -weight * zg * std::sin(angle), 1e-9) << "roll " << angle;
    EXPECT_LT(r[3] * angle, 0.0) << "roll " << angle;  // righting, not capsizing
    EXPECT_NEAR(r[4], 0.0, 1e-9);
    EXPECT_NEAR(r[5], 0.0, 1e-9);
    EXPECT_LT(r.head<3>().cwiseAbs().maxCoeff(), 1e-9);  // neutral: no net force

    const Eigen::Quaterniond pitch(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()));
    const Vector6d q = restoringWrench(pitch, mass, cog, volume, Eigen::Vector3d::Zero(), kRho, kG);
    EXPECT_NEAR(q[4], -weight * zg * std::sin(angle), 1e-9) << "pitch " << angle;
    EXPECT_NEAR(q[3], 0.0, 1e-9);
  }
}

TEST(RestoringWrench, NetForceIsBuoyancyMinusWeightAlongWorldUp) {
  const double volume = sphereVolume(kRadius);
  const double mass = kRho * volume + 2.0;  // 2 kg heavy
  const Eigen::Quaterniond q = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(-0.4, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX());
  const Vector6d r = restoringWrench(q, mass, Eigen::Vector3d::Zero(), volume, Eigen::Vector3d::Zero(), kRho, kG);
  const Eigen::Vector3d world_force = q.toRotationMatrix() * r.head<3>();
  EXPECT_NEAR(world_force.x(), 0.0, 1e-9);
  EXPECT_NEAR(world_force.y(), 0.0, 1e-9);
  EXPECT_NEAR(world_force.z(), -2.0 * kG, 1e-9);
  EXPECT_LT(r.tail<3>().cwiseAbs().maxCoeff(), 1e-9);  // both act at the origin
}

TEST(RestoringWrench, HalfSubmergedSphereFloatsWithHalfItsVolume) {
  // A sphere of half the water's density floats with its centre on the surface.
  const double volume = sphereVolume(kRadius);
  const double mass = 0.5 * kRho * volume;
  const double submerged = submergedFraction(0.0, 0.0, kRadius) * volume;
  const Vector6d r = restoringWrench(Eigen::Quaterniond::Identity(), mass, Eigen::Vector3d::Zero(), submerged,
                                     Eigen::Vector3d::Zero(), kRho, kG);
  EXPECT_NEAR(r[2], 0.0, 1e-9);
}

}  // namespace
}  // namespace hydro
}  // namespace unexmin

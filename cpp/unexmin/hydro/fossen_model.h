// Fossen's 6-DOF hydrodynamic model of a rigid vehicle, on the velocity relative to the water.
//
//   M_RB nu_dot + C_RB(nu) nu + M_A nu_r_dot + C_A(nu_r) nu_r + D(nu_r) nu_r + g(eta) = tau
//
// The rigid body (M_RB, C_RB) and contacts are integrated by the physics engine. The diagonal part of
// the added mass M_A (isotropic translational part, diagonal rotational part) is folded into the
// engine's mass and inertia: for a sphere in a uniform current this is exact, and it keeps the
// integration stable where applying M_A nu_dot as an explicit force from a differentiated
// acceleration is not. Only the residual (off-diagonal / anisotropic) added mass is applied as a force.
#pragma once

#include <unexmin/hydro/types.h>

namespace unexmin {
namespace hydro {

/// Hydrodynamic and mass parameters of a vehicle, all in the body frame (x forward, y left, z up).
struct HydroParams {
  double mass = 0.0;                              ///< Dry mass, pendulum included, VBS empty [kg].
  double volume = 0.0;                            ///< Displaced volume when fully submerged [m^3].
  double radius = 0.0;                            ///< Hull radius for partial submersion at the surface [m].
  Eigen::Vector3d center_of_gravity{0, 0, 0};     ///< CoG of the vehicle less the pendulum [m].
  Eigen::Vector3d center_of_buoyancy{0, 0, 0};    ///< Centre of buoyancy [m].
  Eigen::Vector3d inertia{0, 0, 0};               ///< Principal rigid-body moments of inertia [kg m^2].
  Matrix6d added_mass = Matrix6d::Zero();         ///< M_A, symmetric positive semi-definite [kg, kg m, kg m^2].
  Vector6d linear_damping = Vector6d::Zero();     ///< Diagonal of D_l [N s/m | N m s/rad].
  Vector6d quadratic_damping = Vector6d::Zero();  ///< Diagonal of D_q [N s^2/m^2 | N m s^2/rad^2].
};

/// Throws ParameterError naming the first parameter that is not finite, not positive where it
/// must be, or (for M_A) not symmetric.
void validate(const HydroParams& params);

class FossenModel {
public:
  explicit FossenModel(const HydroParams& params);

  const HydroParams& params() const { return params_; }

  /// Added-mass Coriolis-centripetal matrix C_A(nu_r) (Fossen 2011, eq. 6.43; thesis eq. 5.9-5.10 with
  /// the hydrodynamic derivatives X_udot = -M_A(0,0), ...). Skew-symmetric for symmetric M_A.
  static Matrix6d coriolisAddedMass(const Matrix6d& added_mass, const Vector6d& nu_r);

  /// Damping force D(nu_r) nu_r = D_l nu_r + D_q |nu_r| nu_r [N | N m].
  Vector6d damping(const Vector6d& nu_r) const;

  /// Translational added mass folded into the engine's scalar mass [kg].
  double foldedMass() const { return folded_mass_; }
  /// Rotational added inertia folded into the engine's principal inertia [kg m^2].
  const Eigen::Vector3d& foldedInertia() const { return folded_inertia_; }
  /// M_A less the folded part; zero for a sphere.
  const Matrix6d& residualAddedMass() const { return residual_; }

  /// Body wrench [N | N m] that, added to the thrust, the restoring forces and an engine integrating
  /// the rigid body with the folded mass and inertia, reproduces Fossen's equation:
  ///   -D(nu_r) nu_r - C_A(M_res, nu_r) nu_r - M_res nu_r_dot + M_fold [a_c; 0]
  /// nu_r: body velocity relative to the water [m/s | rad/s];
  /// nu_r_dot: latest estimate of its derivative (used only for the residual added mass) [m/s^2 | rad/s^2];
  /// current_accel_body: acceleration of the water in body axes (world-frame rate, rotated) [m/s^2].
  Vector6d wrench(const Vector6d& nu_r, const Vector6d& nu_r_dot, const Eigen::Vector3d& current_accel_body) const;

private:
  HydroParams params_;
  double folded_mass_ = 0.0;
  Eigen::Vector3d folded_inertia_{0, 0, 0};
  Matrix6d folded_ = Matrix6d::Zero();
  Matrix6d residual_ = Matrix6d::Zero();
};

/// Fraction of the hull volume below the free surface for a sphere of `radius` whose centre is at
/// height `z_centre` in a water column whose surface is at `z_surface` (world z up) [0..1].
double submergedFraction(double z_centre, double z_surface, double radius);

/// Weight and buoyancy as a body wrench about the body origin [N | N m]: this is -g(eta).
/// q_world_body: attitude; weight_mass: total mass incl. pendulum and VBS [kg]; cog: its centre in the
/// body frame [m]; buoyancy_volume: submerged volume [m^3]; cob: centre of buoyancy [m];
/// rho: water density [kg/m^3]; gravity: magnitude of g [m/s^2], acting along world -z.
Vector6d restoringWrench(const Eigen::Quaterniond& q_world_body, double weight_mass, const Eigen::Vector3d& cog,
                         double buoyancy_volume, const Eigen::Vector3d& cob, double rho, double gravity);

}  // namespace hydro
}  // namespace unexmin

// Internal pendulum for pitch: a mass on an arm pivoting about the body y axis at the body origin.
#pragma once

#include <unexmin/hydro/types.h>

namespace unexmin {
namespace hydro {

struct PendulumParams {
  double mass = 0.0;        ///< Pendulum mass, part of the vehicle mass [kg].
  double arm = 0.0;         ///< Pivot-to-mass distance [m].
  double speed = 0.1;       ///< Constant angular speed towards the target [rad/s] > 0.
  double min_angle = -0.5;  ///< Limits of the command [rad].
  double max_angle = 0.5;
};

class Pendulum {
public:
  explicit Pendulum(const PendulumParams& params);  // throws ParameterError

  /// Set the target angle [rad]; false (target unchanged) if not finite or outside the limits.
  /// Positive angles swing the mass towards +x (body forward), which pitches the nose down.
  bool setTarget(double angle);
  /// Turn towards the target at constant speed for dt [s], locking on arrival.
  void update(double dt);

  double angle() const { return angle_; }        ///< [rad]
  double target() const { return target_; }      ///< [rad]
  double velocity() const { return velocity_; }  ///< [rad/s] during the last update
  /// Position of the pendulum mass in the body frame [m]: arm * (sin a, 0, -cos a).
  Eigen::Vector3d massPosition() const;
  const PendulumParams& params() const { return params_; }
  void reset();

private:
  PendulumParams params_;
  double angle_ = 0.0;
  double target_ = 0.0;
  double velocity_ = 0.0;
};

/// Variable ballast system: water mass [kg] added at `position` (body frame), within [min, max].
struct VbsParams {
  double min_mass = -1.0;             ///< [kg] (negative: lighter than the trim point)
  double max_mass = 1.0;              ///< [kg]
  Eigen::Vector3d position{0, 0, 0};  ///< [m]
};

class Vbs {
public:
  explicit Vbs(const VbsParams& params);  // throws ParameterError
  /// False (mass unchanged) if not finite or outside [min, max].
  bool setMass(double mass);
  double mass() const { return mass_; }
  const VbsParams& params() const { return params_; }
  void reset() { mass_ = 0.0; }

private:
  VbsParams params_;
  double mass_ = 0.0;
};

}  // namespace hydro
}  // namespace unexmin

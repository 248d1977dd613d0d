// A control surface (fin, rudder, elevator): a commanded angle reached at a limited rate within limits, and the lift
// and drag of the water flowing past it. The lift model is a family chosen by name (fin_lift_model.h).
//
// Geometry, body frame: the fin turns about its span axis `axis` (unit) at `position`; at angle 0 its chord points
// along `chord` (unit, normal to the axis, towards the leading edge). At angle d the chord is
// c(d) = cos d chord + sin d (axis x chord) and the normal n(d) = axis x c(d).
#pragma once

#include <unexmin/hydro/fin_factory.h>
#include <unexmin/hydro/types.h>

#include <memory>

namespace unexmin {
namespace hydro {

struct FinParams {
  int id = 0;
  Eigen::Vector3d position{0, 0, 0};  ///< Centre of pressure of the fin, body frame [m].
  Eigen::Vector3d axis{0, 0, 1};      ///< Span (rotation) axis, body frame; normalised.
  Eigen::Vector3d chord{1, 0, 0};     ///< Chord direction at angle 0, body frame; normal to `axis`; normalised.
  std::string model = "linear_lift";  ///< Lift model family.
  ParamMap model_params;
  double area = 0.0;       ///< Planform area [m^2] > 0.
  double min_angle = 0.0;  ///< Angle limits [rad], min <= 0 <= max (0 is the rest angle).
  double max_angle = 0.0;
  double rate = 0.0;     ///< Largest angular speed of the fin [rad/s] > 0.
  double timeout = 1.0;  ///< Command watchdog: the command returns to 0 after this [s]; <= 0 off.
};

class Fin {
public:
  /// Throws ParameterError naming the fin, the parameter, its value and the accepted range, or an unknown model.
  Fin(const FinParams& params, const FinFactory& families);
  explicit Fin(const FinParams& params);

  const FinParams& params() const { return params_; }

  /// Commanded angle [rad] at sim time t [s]. Returns false, keeping the previous command, when it is not finite or
  /// outside [min_angle, max_angle].
  bool setCommand(double angle, double t);
  /// Turn towards the command by at most rate * dt [rad]; the watchdog returns the command to 0 after `timeout`.
  void update(double t, double dt);

  double command() const { return command_; }
  double angle() const { return angle_; }  ///< Current angle [rad].

  /// Angle of attack [rad] of the fin at body velocity relative to the water nu_r [m/s | rad/s]; 0 in still water.
  double angleOfAttack(const Vector6d& nu_r) const;
  /// Lift and drag as a body wrench about the body origin [N | N m], water density rho [kg/m^3].
  Vector6d wrench(const Vector6d& nu_r, double rho) const;
  void reset();

private:
  FinParams params_;
  std::unique_ptr<FinLiftModel> model_;
  double command_ = 0.0;       ///< [rad]
  double command_time_ = 0.0;  ///< [s]
  double angle_ = 0.0;         ///< [rad]

  /// The flow past the fin (water velocity relative to it, spanwise part removed), body frame [m/s].
  Eigen::Vector3d flow(const Vector6d& nu_r) const;
};

}  // namespace hydro
}  // namespace unexmin

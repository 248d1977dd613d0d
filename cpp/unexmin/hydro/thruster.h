// Thruster model: command -> dynamics -> conversion -> saturation, with a command watchdog.
// Dynamics and conversion are families chosen by the name written in the robot description (thruster_models.h): a
// new model is one class and one line in a ThrusterFactory (thruster_factory.h, docs/adding_a_thruster.md).
#pragma once

#include <unexmin/hydro/thruster_models.h>
#include <unexmin/hydro/types.h>

#include <memory>

namespace unexmin {
namespace hydro {

struct ThrusterFactory;

struct ThrusterParams {
  int id = 0;
  Eigen::Vector3d position{0, 0, 0};  ///< Thruster origin in the body frame [m].
  Eigen::Vector3d axis{1, 0, 0};      ///< Unit thrust direction for positive thrust, body frame.
  std::string dynamics = "zero_order";
  ParamMap dynamics_params;
  std::string conversion = "identity";
  ParamMap conversion_params;
  double min_thrust = -50.0;   ///< Saturation [N].
  double max_thrust = 50.0;    ///< Saturation [N].
  double min_command = -50.0;  ///< Accepted command range (command unit); outside: rejected.
  double max_command = 50.0;
  double timeout = 1.0;  ///< Command watchdog: command set to zero after this [s]; <= 0 off.
};

class Thruster {
public:
  /// Dynamics and conversion built by `families` (by the names in `params`). Throws ParameterError naming the
  /// thruster, the parameter, its value and the accepted range, or an unknown family and the registered ones.
  Thruster(const ThrusterParams& params, const ThrusterFactory& families);
  /// With the simulator's families (ThrusterFactory::builtin()).
  explicit Thruster(const ThrusterParams& params);

  const ThrusterParams& params() const { return params_; }

  /// Set the command (command unit) at sim time `t` [s]. Returns false, leaving the command as it was,
  /// when it is not finite or outside [min_command, max_command].
  bool setCommand(double command, double t);
  /// Keep the current command alive at sim time `t` [s] (the watchdog counts from here).
  void holdCommand(double t) { command_time_ = t; }

  /// Advance to sim time `t` by `dt` [s]; returns the achieved thrust [N].
  double update(double t, double dt);

  double command() const { return command_; }
  double thrust() const { return thrust_; }  ///< Achieved thrust [N].
  double state() const { return dynamics_->state(); }
  /// Whether state() is a rotor speed [rad/s] (ThrustConversion::stateIsRotorSpeed).
  bool stateIsRotorSpeed() const { return conversion_->stateIsRotorSpeed(); }
  /// Body force [N] and moment about the body origin [N m] of the current thrust.
  Vector6d wrench() const;
  void reset();

private:
  ThrusterParams params_;
  std::unique_ptr<ThrusterDynamics> dynamics_;
  std::unique_ptr<ThrustConversion> conversion_;
  double command_ = 0.0;
  double command_time_ = 0.0;
  double thrust_ = 0.0;
};

}  // namespace hydro
}  // namespace unexmin

// Thruster model: command -> dynamics -> conversion -> saturation, with a command watchdog.
// Dynamics and conversion are families chosen by the name written in the robot description: a new
// model is one class and one line in a ThrusterFactory (thruster_factory.h, docs/adding_a_thruster.md).
#pragma once

#include <unexmin/hydro/thruster_family_params.h>
#include <unexmin/hydro/types.h>

#include <memory>

namespace unexmin {
namespace hydro {

/// Rotor/command dynamics: filters the commanded input (in the command's own unit).
class ThrusterDynamics {
public:
  virtual ~ThrusterDynamics() = default;
  /// Advance by dt [s] towards `command`; returns the new state (command unit).
  virtual double update(double command, double dt) = 0;
  virtual double state() const = 0;
  virtual void reset() = 0;
};

/// "zero_order": the state follows the command at once. No parameters.
class ZeroOrderDynamics : public ThrusterDynamics {
public:
  double update(double command, double dt) override;
  double state() const override { return state_; }
  void reset() override { state_ = 0.0; }

private:
  double state_ = 0.0;
};

/// "first_order": tau x_dot = u - x, discretised exactly: x += (1 - exp(-dt/tau)) (u - x).
/// Parameters: tau [s] > 0.
class FirstOrderDynamics : public ThrusterDynamics {
public:
  explicit FirstOrderDynamics(double tau);
  explicit FirstOrderDynamics(ThrusterFamilyParams& params);
  double update(double command, double dt) override;
  double state() const override { return state_; }
  void reset() override { state_ = 0.0; }

private:
  double tau_;
  double state_ = 0.0;
};

/// Maps the dynamics' state (command unit) to thrust [N] along the thruster axis.
class ThrustConversion {
public:
  virtual ~ThrustConversion() = default;
  virtual double thrust(double state) const = 0;
  /// Whether the state it reads is a rotor speed [rad/s] (the propeller visual then turns at it; otherwise at a
  /// speed derived from the thrust).
  virtual bool stateIsRotorSpeed() const { return false; }
};

/// "identity": the command is thrust [N]. No parameters.
class IdentityConversion : public ThrustConversion {
public:
  double thrust(double state) const override { return state; }
};

/// "basic": thrust = gain * w * |w|, w the rotor speed in the command's unit. Parameters: gain
/// [N per unit^2], non-zero.
class BasicConversion : public ThrustConversion {
public:
  explicit BasicConversion(double gain);
  explicit BasicConversion(ThrusterFamilyParams& params);
  double thrust(double state) const override;
  bool stateIsRotorSpeed() const override { return true; }

private:
  double gain_;
};

/// "table": linear interpolation in (input, output) pairs, clamped at the ends. Parameters: input
/// (command unit, strictly increasing, >= 2 entries), output [N], same length.
class TableConversion : public ThrustConversion {
public:
  TableConversion(std::vector<double> input, std::vector<double> output);
  explicit TableConversion(ThrusterFamilyParams& params);
  double thrust(double state) const override;

private:
  std::vector<double> input_;
  std::vector<double> output_;
};

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

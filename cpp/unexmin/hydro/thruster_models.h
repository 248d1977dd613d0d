// The two kinds of a thruster's models and their built-in families: the dynamics (command -> state) and the thrust
// conversion (state -> thrust [N]), each chosen by the name the robot description writes (ThrusterFactory,
// thruster_factory.h). A family reads its parameters through ActuatorFamilyParams. Knows no ROS.
#pragma once

#include <unexmin/hydro/actuator_family_params.h>

#include <vector>

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
  explicit FirstOrderDynamics(ActuatorFamilyParams& params);
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
  explicit BasicConversion(ActuatorFamilyParams& params);
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
  explicit TableConversion(ActuatorFamilyParams& params);
  double thrust(double state) const override;

private:
  std::vector<double> input_;
  std::vector<double> output_;
};

}  // namespace hydro
}  // namespace unexmin

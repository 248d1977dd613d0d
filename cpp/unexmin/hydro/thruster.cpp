#include <unexmin/hydro/thruster.h>

#include <unexmin/hydro/thruster_factory.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace unexmin {
namespace hydro {

namespace {

std::string vec(const Eigen::Vector3d& v) {
  return "(" + formatNumber(v.x()) + ", " + formatNumber(v.y()) + ", " + formatNumber(v.z()) + ")";
}

const char* const kFirstOrder = "thruster dynamics 'first_order'";
const char* const kBasic = "thrust conversion 'basic'";
const char* const kTable = "thrust conversion 'table'";

void requireTimeStep(double dt, const char* what) {
  if (!std::isfinite(dt) || dt < 0.0) {
    throw ParameterError(std::string(what) + ": time step dt = " + formatNumber(dt) + " must be finite and >= 0 [s]");
  }
}

}  // namespace

// ------------------------------------------------------------------------------------------ dynamics

double ZeroOrderDynamics::update(double command, double /*dt*/) {
  state_ = command;
  return state_;
}

FirstOrderDynamics::FirstOrderDynamics(double tau) : tau_(tau) {
  if (!std::isfinite(tau)) {
    throw ParameterError(std::string(kFirstOrder) + ": parameter 'tau' = " + formatNumber(tau) + " must be finite [s]");
  }
  if (!(tau > 0.0)) {
    throw ParameterError(std::string(kFirstOrder) + ": parameter 'tau' = " + formatNumber(tau) + " must be > 0 [s]");
  }
}

FirstOrderDynamics::FirstOrderDynamics(ThrusterFamilyParams& params) : FirstOrderDynamics(params.scalar("tau")) {}

double FirstOrderDynamics::update(double command, double dt) {
  requireTimeStep(dt, kFirstOrder);
  // Exact solution of tau x_dot = u - x over dt with u held constant.
  state_ += -std::expm1(-dt / tau_) * (command - state_);
  return state_;
}

// ---------------------------------------------------------------------------------------- conversion

BasicConversion::BasicConversion(double gain) : gain_(gain) {
  if (!std::isfinite(gain) || gain == 0.0) {
    throw ParameterError(std::string(kBasic) + ": parameter 'gain' = " + formatNumber(gain) +
                         " must be finite and non-zero [N per unit^2]");
  }
}

BasicConversion::BasicConversion(ThrusterFamilyParams& params) : BasicConversion(params.scalar("gain")) {}

double BasicConversion::thrust(double state) const {
  return gain_ * state * std::abs(state);
}

TableConversion::TableConversion(std::vector<double> input, std::vector<double> output)
    : input_(std::move(input)), output_(std::move(output)) {
  if (input_.size() < 2) {
    throw ParameterError(std::string(kTable) + ": parameter 'input' has " + formatNumber(input_.size()) +
                         " entries, expected at least 2");
  }
  if (output_.size() != input_.size()) {
    throw ParameterError(std::string(kTable) + ": parameter 'output' has " + formatNumber(output_.size()) +
                         " entries, expected " + formatNumber(input_.size()) + " (the length of 'input')");
  }
  for (std::size_t i = 0; i < input_.size(); ++i) {
    if (!std::isfinite(input_[i])) {
      throw ParameterError(std::string(kTable) + ": parameter 'input[" + formatNumber(i) +
                           "]' = " + formatNumber(input_[i]) + " must be finite");
    }
    if (!std::isfinite(output_[i])) {
      throw ParameterError(std::string(kTable) + ": parameter 'output[" + formatNumber(i) +
                           "]' = " + formatNumber(output_[i]) + " must be finite [N]");
    }
    if (i > 0 && !(input_[i] > input_[i - 1])) {
      throw ParameterError(std::string(kTable) + ": parameter 'input[" + formatNumber(i) +
                           "]' = " + formatNumber(input_[i]) + " must be > input[" + formatNumber(i - 1) +
                           "] = " + formatNumber(input_[i - 1]) + " (strictly increasing)");
    }
  }
}

TableConversion::TableConversion(ThrusterFamilyParams& params)
    : TableConversion(params.list("input"), params.list("output")) {}

double TableConversion::thrust(double state) const {
  if (state <= input_.front()) {
    return output_.front();
  }
  if (state >= input_.back()) {
    return output_.back();
  }
  // First node strictly above `state`; the segment is [hi - 1, hi].
  const auto it = std::upper_bound(input_.begin(), input_.end(), state);
  const std::size_t hi = static_cast<std::size_t>(it - input_.begin());
  const std::size_t lo = hi - 1;
  const double s = (state - input_[lo]) / (input_[hi] - input_[lo]);
  return output_[lo] + s * (output_[hi] - output_[lo]);
}

// ------------------------------------------------------------------------------------------ thruster

Thruster::Thruster(const ThrusterParams& params) : Thruster(params, ThrusterFactory::builtin()) {}

Thruster::Thruster(const ThrusterParams& params, const ThrusterFactory& families) : params_(params) {
  const std::string what = "thruster " + formatNumber(params_.id);
  if (!params_.position.allFinite()) {
    throw ParameterError(what + ": parameter 'position' = " + vec(params_.position) + " must be finite [m]");
  }
  const double length = params_.axis.norm();
  if (!std::isfinite(length) || !(length > 0.0)) {
    throw ParameterError(what + ": parameter 'axis' = " + vec(params_.axis) +
                         " must be a finite vector of non-zero length");
  }
  params_.axis /= length;

  const auto check_range = [&what](const char* lo_name, double lo, const char* hi_name, double hi, const char* unit) {
    if (!std::isfinite(lo) || !std::isfinite(hi)) {
      throw ParameterError(what + ": parameters '" + lo_name + "' = " + formatNumber(lo) + " and '" + hi_name +
                           "' = " + formatNumber(hi) + " must be finite " + unit);
    }
    if (lo > hi) {
      throw ParameterError(what + ": parameter '" + lo_name + "' = " + formatNumber(lo) + " must be <= '" + hi_name +
                           "' = " + formatNumber(hi) + " " + unit);
    }
  };
  check_range("min_thrust", params_.min_thrust, "max_thrust", params_.max_thrust, "[N]");
  check_range("min_command", params_.min_command, "max_command", params_.max_command, "[command unit]");
  if (std::isnan(params_.timeout)) {
    throw ParameterError(what + ": parameter 'timeout' = nan must be a number [s] (<= 0: off)");
  }

  dynamics_ = families.dynamics.create(params_.dynamics, params_.dynamics_params);
  conversion_ = families.conversion.create(params_.conversion, params_.conversion_params);
}

bool Thruster::setCommand(double command, double t) {
  if (!std::isfinite(command) || !std::isfinite(t) || command < params_.min_command || command > params_.max_command) {
    return false;
  }
  command_ = command;
  command_time_ = t;
  return true;
}

double Thruster::update(double t, double dt) {
  if (!std::isfinite(t) || !std::isfinite(dt) || dt < 0.0) {
    throw ParameterError("thruster " + formatNumber(params_.id) + ": time t = " + formatNumber(t) +
                         " and step dt = " + formatNumber(dt) + " must be finite, dt >= 0 [s]");
  }
  if (params_.timeout > 0.0 && t - command_time_ > params_.timeout) {
    command_ = 0.0;  // watchdog: no fresh command within `timeout`
  }
  const double state = dynamics_->update(command_, dt);
  thrust_ = std::clamp(conversion_->thrust(state), params_.min_thrust, params_.max_thrust);
  return thrust_;
}

Vector6d Thruster::wrench() const {
  const Eigen::Vector3d force = thrust_ * params_.axis;
  Vector6d w;
  w.head<3>() = force;
  w.tail<3>() = params_.position.cross(force);
  return w;
}

void Thruster::reset() {
  command_ = 0.0;
  command_time_ = 0.0;
  thrust_ = 0.0;
  dynamics_->reset();
}

}  // namespace hydro
}  // namespace unexmin

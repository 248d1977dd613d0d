#include <unexmin/hydro/thruster_models.h>

#include <unexmin/core/error.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace unexmin {
namespace hydro {
namespace {

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

FirstOrderDynamics::FirstOrderDynamics(ActuatorFamilyParams& params) : FirstOrderDynamics(params.scalar("tau")) {}

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

BasicConversion::BasicConversion(ActuatorFamilyParams& params) : BasicConversion(params.scalar("gain")) {}

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

TableConversion::TableConversion(ActuatorFamilyParams& params)
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

}  // namespace hydro
}  // namespace unexmin

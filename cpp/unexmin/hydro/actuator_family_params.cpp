#include <unexmin/hydro/actuator_family_params.h>

namespace unexmin {
namespace hydro {

ActuatorFamilyParams::ActuatorFamilyParams(std::string family, ParamMap params)
    : family_(std::move(family)), params_(std::move(params)) {}

bool ActuatorFamilyParams::has(const std::string& key) {
  read_.insert(key);
  return params_.count(key) > 0;
}

double ActuatorFamilyParams::scalar(const std::string& key) {
  read_.insert(key);
  return requireScalar(params_, key, family_);
}

double ActuatorFamilyParams::scalar(const std::string& key, double min, double max, const std::string& unit) {
  const double value = scalar(key);
  if (value < min || value > max) {
    throw ParameterError(family_ + ": parameter '" + key + "' = " + formatNumber(value) + " must be in [" +
                         formatNumber(min) + ", " + formatNumber(max) + "] " + unit);
  }
  return value;
}

const std::vector<double>& ActuatorFamilyParams::list(const std::string& key) {
  read_.insert(key);
  const auto it = params_.find(key);
  if (it == params_.end()) {
    throw ParameterError(family_ + ": missing parameter '" + key + "' (expected a list of numbers)");
  }
  return it->second;
}

void ActuatorFamilyParams::finish() const {
  for (const auto& kv : params_) {
    if (read_.count(kv.first))
      continue;
    std::string accepted;
    for (const auto& key : read_)
      accepted += (accepted.empty() ? "" : ", ") + key;
    throw ParameterError(family_ + ": unknown parameter '" + kv.first +
                         "' (accepted: " + (accepted.empty() ? "none" : accepted) + ")");
  }
}

}  // namespace hydro
}  // namespace unexmin

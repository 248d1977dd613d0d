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

}  // namespace

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

#include <unexmin/hydro/pendulum.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace unexmin {
namespace hydro {

namespace {

[[noreturn]] void fail(const std::string& what, const std::string& name, double value, const std::string& expected) {
  throw ParameterError(what + ": parameter '" + name + "' = " + formatNumber(value) + " " + expected);
}

void requireFinite(const std::string& what, const std::string& name, double value, const std::string& unit) {
  if (!std::isfinite(value)) {
    fail(what, name, value, "must be finite " + unit);
  }
}

/// min <= max and 0 in [min, max] (the reset state must be a legal one).
void requireRangeAroundZero(const std::string& what, const std::string& min_name, double min,
                            const std::string& max_name, double max, const std::string& unit) {
  requireFinite(what, min_name, min, unit);
  requireFinite(what, max_name, max, unit);
  if (min > max) {
    fail(what, min_name, min, "must be <= '" + max_name + "' = " + formatNumber(max) + " " + unit);
  }
  if (min > 0.0) {
    fail(what, min_name, min, "must be <= 0 " + unit + " (the rest position 0 must be within the limits)");
  }
  if (max < 0.0) {
    fail(what, max_name, max, "must be >= 0 " + unit + " (the rest position 0 must be within the limits)");
  }
}

}  // namespace

// ------------------------------------------------------------------------------------------ pendulum

Pendulum::Pendulum(const PendulumParams& params) : params_(params) {
  const std::string what = "pendulum";
  requireFinite(what, "mass", params_.mass, "[kg]");
  if (params_.mass < 0.0) {
    fail(what, "mass", params_.mass, "must be >= 0 [kg]");
  }
  requireFinite(what, "arm", params_.arm, "[m]");
  if (params_.arm < 0.0) {
    fail(what, "arm", params_.arm, "must be >= 0 [m]");
  }
  requireFinite(what, "speed", params_.speed, "[rad/s]");
  if (!(params_.speed > 0.0)) {
    fail(what, "speed", params_.speed, "must be > 0 [rad/s]");
  }
  requireRangeAroundZero(what, "min_angle", params_.min_angle, "max_angle", params_.max_angle, "[rad]");
}

bool Pendulum::setTarget(double angle) {
  if (!std::isfinite(angle) || angle < params_.min_angle || angle > params_.max_angle) {
    return false;
  }
  target_ = angle;
  return true;
}

void Pendulum::update(double dt) {
  if (!std::isfinite(dt)) {
    throw ParameterError("pendulum: time step dt = " + formatNumber(dt) + " must be finite [s]");
  }
  if (dt <= 0.0) {
    velocity_ = 0.0;
    return;
  }
  const double previous = angle_;
  const double remaining = target_ - angle_;
  const double max_step = params_.speed * dt;
  if (std::abs(remaining) <= max_step) {
    angle_ = target_;  // arrive and lock, no overshoot
  } else {
    angle_ += std::copysign(max_step, remaining);
  }
  velocity_ = (angle_ - previous) / dt;
}

Eigen::Vector3d Pendulum::massPosition() const {
  return params_.arm * Eigen::Vector3d(std::sin(angle_), 0.0, -std::cos(angle_));
}

void Pendulum::reset() {
  angle_ = 0.0;
  target_ = 0.0;
  velocity_ = 0.0;
}

// ----------------------------------------------------------------------------------------------- vbs

Vbs::Vbs(const VbsParams& params) : params_(params) {
  const std::string what = "vbs";
  requireRangeAroundZero(what, "min_mass", params_.min_mass, "max_mass", params_.max_mass, "[kg]");
  for (int i = 0; i < 3; ++i) {
    requireFinite(what, "position[" + formatNumber(i) + "]", params_.position[i], "[m]");
  }
}

bool Vbs::setMass(double mass) {
  if (!std::isfinite(mass) || mass < params_.min_mass || mass > params_.max_mass) {
    return false;
  }
  mass_ = mass;
  return true;
}

}  // namespace hydro
}  // namespace unexmin

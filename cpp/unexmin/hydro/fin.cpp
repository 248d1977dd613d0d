#include <unexmin/hydro/fin.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace hydro {
namespace {

/// Below this flow speed the fin sees no flow [m/s].
constexpr double kStill = 1e-9;

}  // namespace

Fin::Fin(const FinParams& params, const FinFactory& families) : params_(params) {
  const std::string who = "fin " + formatNumber(params.id);
  auto fail = [&](const std::string& key, double value, const std::string& expected) {
    throw ParameterError(who + ": parameter '" + key + "' = " + formatNumber(value) + " " + expected);
  };
  if (!params_.position.allFinite())
    fail("position", params_.position.norm(), "must be finite [m]");
  if (!params_.axis.allFinite() || params_.axis.norm() < 1e-9)
    fail("axis", params_.axis.norm(), "must be non-zero");
  if (!params_.chord.allFinite() || params_.chord.norm() < 1e-9)
    fail("chord", params_.chord.norm(), "must be non-zero");
  params_.axis.normalize();
  params_.chord.normalize();
  const double dot = params_.axis.dot(params_.chord);
  if (std::abs(dot) > 1e-6)
    fail("chord . axis", dot, "must be 0 (the chord is normal to the span axis)");
  if (!std::isfinite(params_.area) || !(params_.area > 0.0))
    fail("area", params_.area, "must be > 0 [m^2]");
  if (!std::isfinite(params_.min_angle) || !std::isfinite(params_.max_angle) || params_.min_angle > 0.0 ||
      params_.max_angle < 0.0 || params_.max_angle > M_PI / 2 || params_.min_angle < -M_PI / 2)
    fail("min_angle", params_.min_angle,
         "and max_angle = " + formatNumber(params_.max_angle) + " must satisfy -pi/2 <= min <= 0 <= max <= pi/2 [rad]");
  if (!std::isfinite(params_.rate) || !(params_.rate > 0.0))
    fail("rate", params_.rate, "must be > 0 [rad/s]");
  if (!std::isfinite(params_.timeout))
    fail("timeout", params_.timeout, "must be finite [s]");
  try {
    model_ = families.model.create(params_.model, params_.model_params);
  } catch (const ParameterError& e) {
    throw ParameterError(who + ": " + e.what());
  }
}

Fin::Fin(const FinParams& params) : Fin(params, FinFactory::builtin()) {}

bool Fin::setCommand(double angle, double t) {
  if (!std::isfinite(angle) || !std::isfinite(t) || angle < params_.min_angle || angle > params_.max_angle)
    return false;
  command_ = angle;
  command_time_ = t;
  return true;
}

void Fin::update(double t, double dt) {
  if (params_.timeout > 0.0 && t - command_time_ > params_.timeout)
    command_ = 0.0;
  const double step = params_.rate * std::max(dt, 0.0);
  angle_ += std::clamp(command_ - angle_, -step, step);
}

Eigen::Vector3d Fin::flow(const Vector6d& nu_r) const {
  const Eigen::Vector3d v = nu_r.head<3>() + nu_r.tail<3>().cross(params_.position);
  const Eigen::Vector3d u = -v;
  return u - u.dot(params_.axis) * params_.axis;
}

double Fin::angleOfAttack(const Vector6d& nu_r) const {
  const Eigen::Vector3d u = flow(nu_r);
  if (u.norm() < kStill)
    return 0.0;
  const Eigen::Vector3d& s = params_.axis;
  const Eigen::Vector3d c = std::cos(angle_) * params_.chord + std::sin(angle_) * s.cross(params_.chord);
  const Eigen::Vector3d n = s.cross(c);
  return std::atan2(u.dot(n), -u.dot(c));
}

Vector6d Fin::wrench(const Vector6d& nu_r, double rho) const {
  Vector6d w = Vector6d::Zero();
  const Eigen::Vector3d u = flow(nu_r);
  const double speed = u.norm();
  if (speed < kStill)
    return w;
  const double alpha = angleOfAttack(nu_r);
  const Eigen::Vector3d e = u / speed;  // direction the water moves past the fin: drag acts along it
  const double q = 0.5 * rho * speed * speed * params_.area;
  const Eigen::Vector3d force = q * (model_->lift(alpha) * e.cross(params_.axis) + model_->drag(alpha) * e);
  w.head<3>() = force;
  w.tail<3>() = params_.position.cross(force);
  return w;
}

void Fin::reset() {
  command_ = 0.0;
  command_time_ = 0.0;
  angle_ = 0.0;
}

}  // namespace hydro
}  // namespace unexmin

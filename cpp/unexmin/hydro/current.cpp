#include <unexmin/hydro/current.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace unexmin {
namespace hydro {

namespace {

void validateChannel(const GaussMarkovParams& p, const std::string& channel, const std::string& unit) {
  const std::string prefix = "current." + channel + ".";
  const auto fail = [&prefix](const std::string& field, double value, const std::string& expected) {
    throw ParameterError("parameter '" + prefix + field + "' = " + formatNumber(value) + " " + expected);
  };
  const std::pair<const char*, double> fields[] = {
      {"mean", p.mean}, {"min", p.min}, {"max", p.max}, {"noise", p.noise}, {"mu", p.mu}};
  for (const auto& field : fields) {
    if (!std::isfinite(field.second)) {
      fail(field.first, field.second, "must be finite");
    }
  }
  if (p.min > p.max) {
    fail("min", p.min, "must be <= '" + prefix + "max' = " + formatNumber(p.max) + " " + unit);
  }
  if (p.mean < p.min || p.mean > p.max) {
    fail("mean", p.mean, "must be within [" + formatNumber(p.min) + ", " + formatNumber(p.max) + "] " + unit);
  }
  if (p.noise < 0.0) {
    fail("noise", p.noise, "must be >= 0 " + unit.substr(0, unit.size() - 1) + "/sqrt(s)]");
  }
  if (p.mu < 0.0) {
    fail("mu", p.mu, "must be >= 0 [1/s]");
  }
}

}  // namespace

void validate(const CurrentParams& params) {
  validateChannel(params.speed, "speed", "[m/s]");
  validateChannel(params.horizontal_angle, "horizontal_angle", "[rad]");
  validateChannel(params.vertical_angle, "vertical_angle", "[rad]");
}

CurrentModel::CurrentModel(const CurrentParams& params, std::uint64_t seed) : params_(params) {
  validate(params_);
  reset(seed);
}

double CurrentModel::step(const GaussMarkovParams& p, double x, double dt) {
  // One normal per channel and update, whatever the parameters, so that a seed gives one sequence.
  const double n = normal_(rng_);
  if (dt <= 0.0) {
    return x;
  }
  double next;
  if (p.mu > 0.0) {
    // Exact Ornstein-Uhlenbeck transition over dt.
    const double decay = std::exp(-p.mu * dt);
    const double sigma = p.noise * std::sqrt(-std::expm1(-2.0 * p.mu * dt) / (2.0 * p.mu));
    next = p.mean + decay * (x - p.mean) + sigma * n;
  } else {
    next = x + p.noise * std::sqrt(dt) * n;  // Wiener process
  }
  return std::clamp(next, p.min, p.max);
}

void CurrentModel::update(double dt) {
  if (!std::isfinite(dt)) {
    throw ParameterError("current: time step dt = " + formatNumber(dt) + " must be finite [s]");
  }
  const Eigen::Vector3d before = velocity();
  speed_ = step(params_.speed, speed_, dt);
  horizontal_ = step(params_.horizontal_angle, horizontal_, dt);
  vertical_ = step(params_.vertical_angle, vertical_, dt);
  if (dt > 0.0) {
    acceleration_ = (velocity() - before) / dt;
  } else {
    acceleration_.setZero();
  }
}

Eigen::Vector3d CurrentModel::velocity() const {
  const double cv = std::cos(vertical_);
  return speed_ * Eigen::Vector3d(cv * std::cos(horizontal_), cv * std::sin(horizontal_), std::sin(vertical_));
}

void CurrentModel::reset(std::uint64_t seed) {
  rng_.seed(seed);
  normal_.reset();  // drop the cached second Box-Muller value so the sequence restarts exactly
  speed_ = params_.speed.mean;
  horizontal_ = params_.horizontal_angle.mean;
  vertical_ = params_.vertical_angle.mean;
  acceleration_.setZero();
}

}  // namespace hydro
}  // namespace unexmin

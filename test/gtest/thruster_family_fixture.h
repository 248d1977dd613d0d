// The worked example of docs/adding_a_thruster.md: a thruster dynamics family and a thrust conversion family that
// exist only in the tests (test_thruster_family.cpp flies them in the core, test/rostest/test_thruster_family_ros.cpp
// through the simulator node), their parameters and closed form, and the factory that knows them.
#pragma once

#include <unexmin/core/error.h>
#include <unexmin/hydro/thruster_factory.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace unexmin {
namespace test {

/// "slew": the state moves towards the command at `rate` [command unit/s] at most:
/// x += clamp(u - x, -rate dt, +rate dt).
class SlewDynamics : public hydro::ThrusterDynamics {
public:
  explicit SlewDynamics(hydro::ActuatorFamilyParams& params) : rate_(params.scalar("rate", 1e-6, 1e6, "[unit/s]")) {}
  double update(double command, double dt) override {
    state_ += std::clamp(command - state_, -rate_ * dt, rate_ * dt);
    return state_;
  }
  double state() const override { return state_; }
  void reset() override { state_ = 0.0; }

private:
  double rate_;
  double state_ = 0.0;
};

/// "deadband": no thrust within `width` [command unit] of zero, `gain` [N per unit] beyond it:
/// T = gain (x - width sign(x)).
class DeadbandConversion : public hydro::ThrustConversion {
public:
  explicit DeadbandConversion(hydro::ActuatorFamilyParams& params)
      : gain_(params.scalar("gain", -1e3, 1e3, "[N per unit]")), width_(params.scalar("width", 0.0, 1e3, "[unit]")) {}
  double thrust(double x) const override {
    return std::abs(x) <= width_ ? 0.0 : gain_ * (x - std::copysign(width_, x));
  }

private:
  double gain_;
  double width_;
};

/// The built-in families and the two above: the registration lines.
inline hydro::ThrusterFactory withTestFamilies() {
  hydro::ThrusterFactory families = hydro::ThrusterFactory::builtin();
  families.dynamics.add<SlewDynamics>("slew");
  families.conversion.add<DeadbandConversion>("deadband");
  return families;
}

constexpr double kSlewRate = 20.0;      // [unit/s]
constexpr double kDeadbandGain = 0.5;   // [N per unit]
constexpr double kDeadbandWidth = 2.0;  // [unit]

/// <param> elements of the two families with the values above.
inline std::string slewParams() {
  return "<param name='rate' value='" + formatNumber(kSlewRate) + "'/>";
}
inline std::string deadbandParams() {
  return "<param name='gain' value='" + formatNumber(kDeadbandGain) + "'/><param name='width' value='" +
         formatNumber(kDeadbandWidth) + "'/>";
}

/// Closed form of the two families for a step command `u` [unit] at t = 0: the state [unit] and the thrust [N]
/// at sim time `t` [s].
inline double slewState(double u, double t) {
  return std::min(kSlewRate * t, u);
}
inline double deadbandThrust(double x) {
  return std::abs(x) <= kDeadbandWidth ? 0.0 : kDeadbandGain * (x - std::copysign(kDeadbandWidth, x));
}

}  // namespace test
}  // namespace unexmin

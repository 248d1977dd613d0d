#include <unexmin/sensors/science/probe_channel.h>

#include <unexmin/sensors/noise_factory.h>

#include <cmath>

namespace unexmin {
namespace sensors {
namespace science {

ProbeChannel::ProbeChannel(const std::string& family, const ProbeChannelParams& params, double interval)
    : params_(params) {
  NoiseParams n;
  n.white = params.noise;
  n.bias_random_walk = params.drift;
  n.interval = interval;
  noise_ = createNoise(family, n);
  const double q = params.resolution;
  variance_ = noise_->whiteStd() * noise_->whiteStd() + q * q / 12.0;
}

void ProbeChannel::reset(Random& random) {
  noise_->reset(random);
  lagged_ = 0.0;
}

void ProbeChannel::track(double x, double dt) {
  if (dt != dt_) {
    dt_ = dt;
    gain_ = params_.tau > 0.0 ? -std::expm1(-dt / params_.tau) : 1.0;
  }
  lagged_ = params_.tau > 0.0 ? lagged_ + (x - lagged_) * gain_ : x;
}

double ProbeChannel::read(Random& random) {
  const double v = noise_->apply(lagged_, random);
  const double q = params_.resolution;
  return q > 0.0 ? q * std::round(v / q) : v;
}

}  // namespace science
}  // namespace sensors
}  // namespace unexmin

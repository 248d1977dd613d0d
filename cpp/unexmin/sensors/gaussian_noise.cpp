#include <unexmin/sensors/gaussian_noise.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace unexmin {
namespace sensors {
namespace {

void checkFigure(const char* name, double v) {
  if (!std::isfinite(v) || v < 0.0)
    throw ParameterError(std::string("noise figure ") + name + " = " + formatNumber(v) + " must be >= 0");
}

}  // namespace

GaussianNoise::GaussianNoise(const NoiseParams& params) : params_(params) {
  checkFigure("white", params.white);
  checkFigure("bias_random_walk", params.bias_random_walk);
  checkFigure("turn_on_bias", params.turn_on_bias);
  if (!(params.interval > 0.0) || !std::isfinite(params.interval))
    throw ParameterError("noise sample interval " + formatNumber(params.interval) + " s must be > 0");
  walk_step_ = params.bias_random_walk * std::sqrt(params.interval);
}

void GaussianNoise::reset(Random& random) {
  // Draw even a zero-sigma term, so that the streams of all channels stay aligned whatever the figures.
  bias_ = params_.turn_on_bias * random.gauss();
}

double GaussianNoise::apply(double truth, Random& random) {
  bias_ += walk_step_ * random.gauss();
  return truth + bias_ + params_.white * random.gauss();
}

}  // namespace sensors
}  // namespace unexmin

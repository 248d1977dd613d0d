// The "gaussian" noise family: y_k = x_k + b_k + s_w n_k with b_0 ~ N(0, s_on^2) at turn-on and
// b_k = b_(k-1) + K sqrt(T) m_k (n, m standard normal, T the sample interval). Its Allan deviation
// is sqrt(s_w^2 T / tau + K^2 tau / 3): white noise of density s_w sqrt(T) and a rate random walk K.
#pragma once

#include <unexmin/core/error.h>

#include <unexmin/sensors/noise_model.h>

namespace unexmin {
namespace sensors {

class GaussianNoise : public NoiseModel {
public:
  /// Throws ParameterError when a figure is negative or not finite, or interval <= 0.
  explicit GaussianNoise(const NoiseParams& params);

  void reset(Random& random) override;
  double apply(double truth, Random& random) override;
  double bias() const override { return bias_; }
  double whiteStd() const override { return params_.white; }

private:
  NoiseParams params_;
  double walk_step_ = 0.0;  ///< K sqrt(T) [u]
  double bias_ = 0.0;       ///< [u]
};

}  // namespace sensors
}  // namespace unexmin

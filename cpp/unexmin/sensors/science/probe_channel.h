// One channel of a water-quality probe (water_probe_sensor.h): the electrode's first-order lag, integrated every
// physics step by its exact discretisation, then at each sample the channel's noise (white + offset random walk, a
// NoiseModel of sensors/noise_factory.h) and its resolution (quantisation step). Knows no ROS.
#pragma once

#include <unexmin/sensors/noise_model.h>

#include <memory>
#include <string>

namespace unexmin {
namespace sensors {
namespace science {

/// The figures of one channel, in the channel's unit u.
struct ProbeChannelParams {
  double tau = 0.0;         ///< time constant of the lag y' = (x - y) / tau [s] >= 0; 0: no lag (y = x)
  double noise = 0.0;       ///< white noise, one standard deviation per sample [u] >= 0
  double drift = 0.0;       ///< offset random walk [u/sqrt(s)] >= 0: the offset's std grows as drift sqrt(t)
  double resolution = 0.0;  ///< quantisation step of the reading [u] >= 0; 0: none
};

class ProbeChannel {
public:
  /// `family`: noise family (noise_factory.h); `interval`: time between two samples [s] > 0. Throws ParameterError
  /// for a bad family or figure.
  ProbeChannel(const std::string& family, const ProbeChannelParams& params, double interval);

  /// Turn-on: the offset restarts at 0 (one draw from `random`, whatever the figures).
  void reset(Random& random);
  /// The electrode settled in water of value `x` [u] (y = x).
  void settle(double x) { lagged_ = x; }
  /// One physics step of `dt` [s] > 0 in water of value `x` [u] held over the step (zero-order hold):
  /// y += (x - y) (1 - exp(-dt / tau)), exact for a held input.
  void track(double x, double dt);
  /// One sample: the lagged value plus the noise (two draws from `random`), rounded to the resolution [u].
  double read(Random& random);

  double lagged() const { return lagged_; }  ///< [u] the electrode's state y
  /// [u^2] of a reading about the lagged value: white noise plus quantisation, noise^2 + resolution^2 / 12.
  double variance() const { return variance_; }
  const ProbeChannelParams& params() const { return params_; }

private:
  ProbeChannelParams params_;
  std::unique_ptr<NoiseModel> noise_;
  double lagged_ = 0.0;
  double dt_ = 0.0;    ///< [s] the step `gain_` is for
  double gain_ = 1.0;  ///< 1 - exp(-dt_ / tau)
  double variance_ = 0.0;
};

}  // namespace science
}  // namespace sensors
}  // namespace unexmin

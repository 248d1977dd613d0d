// A noise model of one scalar channel (one axis) sampled at a fixed interval; the families that implement it are
// chosen by name in the robot description (sensors/noise_factory.h).
#pragma once

#include <unexmin/core/error.h>

#include <unexmin/sensors/random.h>

#include <memory>
#include <string>
#include <vector>

namespace unexmin {
namespace sensors {

/// Noise of one channel, in the channel's unit u.
struct NoiseParams {
  double white = 0.0;             ///< white noise, one standard deviation per sample [u]
  double bias_random_walk = 0.0;  ///< bias random-walk density [u/sqrt(s)]: the bias's std grows as K sqrt(t)
  double turn_on_bias = 0.0;      ///< bias drawn at every reset (turn-on), one standard deviation [u]
  double interval = 0.0;          ///< time between two samples [s] > 0
};

class NoiseModel {
public:
  virtual ~NoiseModel() = default;
  /// Turn-on: draws a new turn-on bias; the random walk restarts from it.
  virtual void reset(Random& random) = 0;
  /// One sample: advances the bias by one interval and returns truth + bias + white noise [u].
  virtual double apply(double truth, Random& random) = 0;
  /// Current bias [u].
  virtual double bias() const = 0;
  /// Per-sample standard deviation of the white part [u] (what a message's covariance reports).
  virtual double whiteStd() const = 0;
};

}  // namespace sensors
}  // namespace unexmin

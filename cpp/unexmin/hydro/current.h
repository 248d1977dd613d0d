// Water current: speed, horizontal and vertical angle as bounded first-order Gauss-Markov processes,
//   dx = -mu (x - mean) dt + noise dW,   clamped to [min, max],
// discretised exactly (Ornstein-Uhlenbeck), seeded.
#pragma once

#include <unexmin/hydro/types.h>

#include <cstdint>
#include <random>

namespace unexmin {
namespace hydro {

struct GaussMarkovParams {
  double mean = 0.0;
  double min = 0.0;
  double max = 0.0;
  double noise = 0.0;  ///< Diffusion sigma [unit/sqrt(s)]; 0 makes the channel constant at `mean`.
  double mu = 0.0;     ///< Return rate to the mean [1/s] >= 0.
};

struct CurrentParams {
  GaussMarkovParams speed;             ///< [m/s]
  GaussMarkovParams horizontal_angle;  ///< Direction in the world x-y plane from +x, CCW [rad].
  GaussMarkovParams vertical_angle;    ///< Elevation above the horizontal [rad].
};

/// Throws ParameterError naming the channel and field when min > max, the mean is outside,
/// or noise/mu are negative or not finite.
void validate(const CurrentParams& params);

class CurrentModel {
public:
  CurrentModel(const CurrentParams& params, std::uint64_t seed);

  /// Advance the processes by dt [s].
  void update(double dt);
  /// Current velocity in the world frame [m/s].
  Eigen::Vector3d velocity() const;
  /// Rate of change of the velocity over the last update, world frame [m/s^2].
  const Eigen::Vector3d& acceleration() const { return acceleration_; }
  double speed() const { return speed_; }
  double horizontalAngle() const { return horizontal_; }
  double verticalAngle() const { return vertical_; }
  /// Back to the means, with a new seed.
  void reset(std::uint64_t seed);
  const CurrentParams& params() const { return params_; }

private:
  double step(const GaussMarkovParams& p, double x, double dt);

  CurrentParams params_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  double speed_ = 0.0;
  double horizontal_ = 0.0;
  double vertical_ = 0.0;
  Eigen::Vector3d acceleration_{0, 0, 0};
};

}  // namespace hydro
}  // namespace unexmin

// Silt raised by the robots' own thrusters: a turbidity field in the world, as a set of Gaussian puffs of extra
// scattering coefficient (the silt adds to the water's b; docs/worlds.md "sediment", docs/vision.md "Silt-out").
//
// A puff k, centre x_k [m], spread sigma_k [m] and strength Q_k = integral of its extra scattering over space [m^2],
// adds at point x
//   db(x) = Q_k / ((2 pi)^(3/2) sigma_k^3) exp(-|x - x_k|^2 / (2 sigma_k^2))   [1/m]
// and along a ray from o in unit direction d to length L the optical depth (closed form, Phi the standard normal CDF,
// t0 = (x_k - o).d, rho the ray's distance from the centre)
//   tau = Q_k / (2 pi sigma_k^2) exp(-rho^2 / (2 sigma_k^2)) (Phi((L - t0) / sigma_k) - Phi(-t0 / sigma_k)).
//
// Raising: every `interval` each thruster's jet (from the thruster, against its thrust: the water it pushes) is cast
// against the static meshes up to `reach`; where it meets a surface at distance d the thruster raises
//   Q = raise |T| dt (1 - d / reach)^2
// over the interval (|T| the thrust [N]; a jet that meets nothing within reach raises nothing), as a puff of spread
// `puff_size` centred puff_size off the surface along its normal, merged into a puff already there (nearer than
// puff_size; strengths add, centre and spread by moments).
// Afterwards every puff drifts with the current, its centre sinks at the settling speed w_s (the silt grains fall
// through the water) and it spreads by turbulent diffusion, sigma^2 grows by 2 K dt. The part of a puff below the
// floor is out of the water: rays end at the floor and never see it. A puff goes when its centre is more than
// kGone sigma below the floor under the place it was raised (found once, by a ray down), or its strength is below
// kFaint.
// Knows no ROS.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

class btCollisionWorld;

namespace unexmin {
namespace sim {

class Robot;

/// The world file's `sediment:` block.
struct SedimentParams {
  bool enabled = false;          ///< thrusters raise silt
  double settling_speed = 2e-3;  ///< w_s [m/s] (silt of about 50 um; Stokes) [assumed]
  double raise = 0.05;           ///< Q per newton of thrust per second at the surface [m^2 / (N s)] [assumed]
  double reach = 1.0;            ///< [m] a jet stirs surfaces nearer than this [assumed]
  double puff_size = 0.3;        ///< sigma of a new puff [m] [assumed]
  double diffusivity = 1e-4;     ///< K, turbulent diffusion [m^2/s] [assumed]
  double interval = 0.25;        ///< [s] between two puffs of one thruster
  int max_puffs = 128;           ///< the faintest goes beyond this
};

/// Throws ConfigError naming the key (sediment.<key>), its value and the accepted range.
void validate(const SedimentParams& params, const std::string& file);

struct SedimentPuff {
  Eigen::Vector3d centre{0, 0, 0};  ///< world frame [m]
  double sigma = 0.3;               ///< spread [m]
  double strength = 0.0;            ///< Q [m^2]
  double floor_z = -1e9;            ///< world z of the floor under the place it was raised [m]
};

class SedimentField {
public:
  static constexpr double kGone = 3.0;    ///< [sigma] a puff this far below its floor is gone
  static constexpr double kFaint = 1e-6;  ///< [m^2] a puff weaker than this is gone

  explicit SedimentField(const SedimentParams& params = SedimentParams()) : params_(params) {}

  const SedimentParams& params() const { return params_; }
  const std::vector<SedimentPuff>& puffs() const { return puffs_; }
  bool empty() const { return puffs_.empty(); }

  /// One physics step of dt [s] at time t [s] (after it): the robots' thrusters raise silt (cast against the static
  /// bodies of `collision`), the puffs drift with `current` (world [m/s]), sink and spread. Nothing when disabled.
  void step(double t, double dt, const std::vector<Robot*>& robots, const btCollisionWorld& collision,
            const Eigen::Vector3d& current);
  /// Adds a puff of strength q [m^2] at `centre` (merged into one nearer than puff_size); floor_z as SedimentPuff.
  void add(const Eigen::Vector3d& centre, double q, double floor_z);
  /// Drift, sinking and spreading of every puff over dt [s]; the gone ones removed.
  void evolve(double dt, const Eigen::Vector3d& current);
  void clear();

  /// Extra scattering coefficient at world point x [1/m].
  double scattering(const Eigen::Vector3d& x) const;
  /// Optical depth of the silt along the ray from `origin` in unit `direction` (world) over [0, length] [m] [-].
  double opticalDepth(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double length) const;
  /// The same at the `n` increasing lengths `lengths` [m] at once, into `out` (one pass over the puffs).
  void opticalDepths(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, const float* lengths, int n,
                     double* out) const;
  /// Whether some puff reaches within `radius` [m] of `point` (its 4 sigma included).
  bool near(const Eigen::Vector3d& point, double radius) const;

private:
  SedimentParams params_;
  std::vector<SedimentPuff> puffs_;
  std::vector<double> impulse_;  ///< per thruster of every robot: integral of |T| dt since its last puff [N s]
  double next_ = 0.0;            ///< time of the next raising [s]
};

}  // namespace sim
}  // namespace unexmin

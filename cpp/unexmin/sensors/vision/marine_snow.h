// Suspended particles ("marine snow": aggregates and flocs of 0.5 mm and more, Alldredge & Silver 1988) as one camera
// sees them: bright specks near the lens lit by the robot's own LEDs, drawn as short streaks where the particle moves
// across the image during the exposure.
//
// The particles are points fixed in the world, seeded, in a cube of half side kHalfSize around the lens (axes of the
// world), at the number density of the visibility level (density()). Each frame they move with the water's current
// over the time since the last frame; one that leaves the cube (the robot moved, or the current carried it) comes
// back through the opposite face with its two other coordinates drawn afresh, so the density stays uniform and the
// robot moves through the particles.
//
// Light (the image formation's lights and water): a particle of radius a and albedo rho is a Lambertian sphere; lit
// by irradiance E_L = I_L(theta) exp(-c r_L) / r_L^2 from light L (I_L the LED's beam, theta off its axis, r_L the
// distance; no shadows) it sends towards the lens the intensity
//   J = sum_L rho E_L a^2 (2 / (3 pi)) (sin alpha + (pi - alpha) cos alpha)   [W/sr]
// (Lambert's sphere, alpha the phase angle between the directions to the light and to the lens), and its image holds,
// summed over pixels, S = J exp(-c R) fx fy / R^2 [W m^-2 sr^-1 px^2] at range R from the lens. S is spread along the
// image of the particle's path during the exposure (exposure_time [s]; its velocity relative to the camera from the
// current and the robot's linear and angular velocity) with a round Gaussian spot of standard deviation
// max(kSpot, a fx / R) [px], where nothing nearer hides it (the pixel's range). Knows no ROS.
#pragma once

#include <unexmin/sensors/vision/camera_model.h>
#include <unexmin/sensors/vision/image_formation.h>
#include <unexmin/sensors/vision/water_optics.h>

#include <Eigen/Geometry>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace unexmin {
namespace sensors {
namespace vision {

class MarineSnow {
public:
  static constexpr double kHalfSize = 1.5;    ///< [m] half side of the cube of particles around the lens [assumed]
  static constexpr double kRadius = 0.25e-3;  ///< [m] particle radius (0.5 mm: marine snow's lower bound)
  static constexpr double kAlbedo = 0.5;      ///< [-] particle albedo [assumed]
  static constexpr double kSpot = 0.6;        ///< [px] smallest spot (the lens's blur) [assumed]
  static constexpr double kNear = 0.05;       ///< [m] nearer than this (in depth) a particle is not drawn [assumed]

  /// Number density of the particles at visibility `level` [1/m^3]: none 0, low 50, medium 200, high 500 (0, 0.05,
  /// 0.2, 0.5 per litre) [assumed]. Throws ConfigError on another level.
  static double density(const std::string& level);
  /// The same for `level`, or for level "water" 130 per NTU of `turbidity` (opticalTurbidity(), water_optics.h),
  /// at most 1000: 1.5 NTU gives about medium's 200 (assumed, as the optics per NTU).
  static double density(const std::string& level, double turbidity);

  /// Particles at `density` [1/m^3] >= 0 around the lens at `lens` (world frame [m]), from `seed`.
  MarineSnow(double density, std::uint64_t seed, const Eigen::Vector3d& lens);

  std::size_t size() const { return particles_.size(); }
  /// Particle positions, world frame [m].
  const std::vector<Eigen::Vector3d>& particles() const { return particles_; }
  /// Moves every particle by current * dt (world frame [m/s], [s] >= 0), then brings back into the cube around `lens`
  /// those that left it.
  void advance(const Eigen::Vector3d& lens, const Eigen::Vector3d& current, double dt);

  /// The camera's motion during an exposure: its optical frame `pose` (world), the base link's position, linear
  /// velocity and angular velocity (world frame [m], [m/s], [rad/s]), the water's `current` [m/s] and the exposure
  /// time [s].
  struct Motion {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    Eigen::Vector3d base{0, 0, 0}, velocity{0, 0, 0}, angular{0, 0, 0}, current{0, 0, 0};
    double exposure_time = 0.0;
  };
  /// Adds the particles' light (`formation`'s lights and water) to `radiance` (3 floats per pixel, row-major,
  /// [W m^-2 sr^-1]) of image `camera` where `range` (per pixel [m], +inf: none) does not hide them; appends the
  /// pixels it changed to `touched`. Returns the number of particles drawn.
  std::size_t draw(const CameraModel& camera, const ImageFormation& formation, const Motion& motion,
                   const std::vector<float>& range, std::vector<float>& radiance,
                   std::vector<std::size_t>& touched) const;
  /// Intensity towards the lens per channel [W/sr] of a particle at `p` (camera optical frame [m]).
  Eigen::Array3d intensity(const ImageFormation& formation, const Eigen::Vector3d& p) const;

private:
  /// A uniform draw in [-kHalfSize, kHalfSize).
  double draw();

  std::vector<Eigen::Vector3d> particles_;
  std::mt19937_64 rng_;
};

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin

// The green line an SLS unit's laser draws on the walls, as its camera sees it (visual mode). The fan is the SLS
// model's own (SlsSensor: fan angle, head pose at the motor angle of the frame's time, the plane through its first
// and last rays), cast again with enough rays that neighbouring hits land about 0.5 px apart in the image.
// A hit is drawn where the camera sees it: it projects into the (distorted) image and it is not behind the surface
// the pixel sees (its distance from the lens at most that pixel's range + 2 % + 1 cm).
//
// Radiometry (a line of laser light on a Lambertian wall, both legs attenuated at the laser's wavelength, i.e.
// the water's green c): the power P dθ / fan of a fan slice lands on a strip of the wall; the image of that strip
// holds, summed over its pixels, the radiance x pixel area
//     S = (rho_g / pi) (P dθ / fan) J exp(-c_g (R_L + R_C))   [W m^-2 sr^-1 px^2]
// with rho_g the green albedo of the material at the hit (SurfaceMaterials: the texture's, where it has one),
// with J the image area per unit wall area at the hit [px^2 / m^2] (from the camera model, distortion and
// obliquity included), R_L the laser range and R_C the camera range (times exp(-tau_L - tau_C) where the thrusters
// raised silt: its optical depths along both legs, sim::SedimentField). S is spread evenly along the segment between
// neighbouring hits with a Gaussian profile across it of standard deviation `width` [px] (the lens and the sheet
// thickness blur it), and added to channel k with weight colour_k (the camera's response to 532 nm light per
// channel relative to green). Knows no ROS.
#pragma once

#include <unexmin/raycast/ray_caster.h>
#include <unexmin/sensors/sensor.h>
#include <unexmin/sensors/vision/camera_model.h>
#include <unexmin/sensors/vision/sls_sensor.h>
#include <unexmin/sensors/vision/surface_materials.h>
#include <unexmin/sensors/vision/water_optics.h>

#include <Eigen/Geometry>

#include <memory>
#include <vector>

namespace unexmin {
namespace sensors {
namespace vision {

class LaserLine {
public:
  /// `sls`: the unit whose laser this camera sees; `camera_pose`: the camera's optical frame in the base frame;
  /// `camera`: the rendered image; `power` [W] > 0; `width` [px] > 0; `colour` >= 0 per channel; `clip_far` [m]:
  /// how far the fan is cast; `hull_albedo` [-]: green albedo of a robot hull the line lands on.
  LaserLine(std::unique_ptr<SlsSensor> sls, const Eigen::Isometry3d& camera_pose, const CameraModel& camera,
            double power, double width, const Eigen::Vector3d& colour, double clip_far, double hull_albedo);

  const SlsSensor& sls() const { return *sls_; }
  int rays() const { return static_cast<int>(fan_.size()); }
  /// Unit direction of fan ray j of this line in the head frame.
  const Eigen::Vector3d& direction(int j) const { return fan_.at(static_cast<std::size_t>(j)); }

  /// Adds the line of the frame at ctx's time to `radiance` (3 floats per pixel, row-major [W m^-2 sr^-1]) where
  /// `range` (the camera's distance to the surface per pixel [m], +inf on none) shows it; appends the index of
  /// every pixel it changed to `touched` (possibly more than once).
  void draw(const SensorContext& ctx, const WaterOptics& water, const std::vector<float>& range,
            std::vector<float>& radiance, std::vector<std::size_t>& touched);

private:
  /// Distorted pixel of a point in the optical frame (z > 0), inside the image or not.
  Eigen::Vector2d pixel(const Eigen::Vector3d& p) const;
  void splat(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double total, std::vector<float>& radiance,
             std::vector<std::size_t>& touched) const;

  std::unique_ptr<SlsSensor> sls_;
  Eigen::Isometry3d camera_pose_;
  CameraModel camera_;
  double power_, width_;
  Eigen::Vector3f colour_;
  double clip_far_, hull_albedo_;
  double dtheta_ = 0.0;               ///< [rad] between neighbouring fan rays
  std::vector<Eigen::Vector3d> fan_;  ///< head frame
  std::vector<raycast::Ray> rays_;
  std::vector<raycast::Hit> hits_;
  std::unique_ptr<SurfaceMaterials> materials_;  ///< the world's, for the green albedo at each hit
};

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin

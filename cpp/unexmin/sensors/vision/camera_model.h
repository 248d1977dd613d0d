// A camera's geometry as ROS describes it (sensor_msgs/CameraInfo, distortion model "plumb_bob"): image size,
// pinhole intrinsics K and distortion D = (k1, k2, p1, p2, k3), in the REP-103 optical frame (z forward, x
// right, y down). Projects points to pixels and pixels to rays, so the rendered image, the published
// CameraInfo and every sensor that asks "can camera i see this point?" (the SLS) agree exactly. Knows no ROS.
//
// Parameters of a <sensor type="camera"> (and read by the SLS from its camera's element):
//   width, height  [px]  full resolution (default 2054 x 1544, thesis 5.4.5)
//   hfov           [rad] horizontal field of view of the undistorted pinhole: fx = fy = (width/2) / tan(hfov/2)
//   distortion     [-]   k1 k2 p1 p2 k3 (default 0 0 0 0 0)
//   render_scale   [-]   (0, 1]: the published image is round(scale * width) x round(scale * height) and K is
//                        scaled with it (D is unchanged: it acts on normalised coordinates)
#pragma once

#include <unexmin/sensors/sensor_params.h>

#include <Eigen/Core>

#include <array>

namespace unexmin {
namespace sensors {
namespace vision {

class CameraModel {
public:
  CameraModel() = default;
  /// width x height [px], focal lengths and principal point [px], plumb_bob D. Throws ParameterError on a
  /// non-positive size or focal length.
  CameraModel(int width, int height, double fx, double fy, double cx, double cy, const std::array<double, 5>& d);
  /// From a sensor's parameters (above, each name preceded by `prefix`, e.g. "camera_" for the SLS's camera),
  /// at its render_scale (or at full resolution when `apply_render_scale` is false); `p` names the sensor in
  /// errors.
  static CameraModel fromParams(SensorParams& p, const std::string& prefix = "", bool apply_render_scale = true);

  int width() const { return width_; }
  int height() const { return height_; }
  double fx() const { return fx_; }
  double fy() const { return fy_; }
  double cx() const { return cx_; }
  double cy() const { return cy_; }
  const std::array<double, 5>& distortion() const { return d_; }
  /// Row-major 3x3 K and 3x4 P (P = [K | 0], no rectification), as CameraInfo holds them.
  std::array<double, 9> K() const;
  std::array<double, 12> P() const;

  /// Normalised undistorted (x, y) = (X/Z, Y/Z) -> distorted normalised coordinates (plumb_bob).
  Eigen::Vector2d distort(const Eigen::Vector2d& xy) const;
  /// Inverse of distort() by fixed-point iteration (converges for the mild distortion of real lenses; residual
  /// below 1e-9 in normalised units within the image).
  Eigen::Vector2d undistort(const Eigen::Vector2d& xy_distorted) const;

  /// Pixel (u, v) [px] of point `p` in the optical frame [m] (u right, v down; pixel centres at integers,
  /// ROS convention). False when p is not in front of the lens (Z <= 0) or the pixel is outside
  /// [-0.5, width - 0.5] x [-0.5, height - 0.5].
  bool project(const Eigen::Vector3d& p, Eigen::Vector2d& uv) const;
  /// Unit direction in the optical frame of the ray through pixel (u, v) (distortion undone).
  Eigen::Vector3d ray(double u, double v) const;

private:
  int width_ = 1, height_ = 1;
  double fx_ = 1.0, fy_ = 1.0, cx_ = 0.0, cy_ = 0.0;
  std::array<double, 5> d_{{0, 0, 0, 0, 0}};
  /// Largest r^2 = x^2 + y^2 (normalised) up to which the radial distortion is monotonic: beyond it a point
  /// could fold back into the image, so project() refuses it.
  double r2_max_ = 1e6;
};

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin

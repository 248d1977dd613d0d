#include <unexmin/sensors/vision/camera_model.h>

#include <cmath>

namespace unexmin {
namespace sensors {
namespace vision {

CameraModel::CameraModel(int width, int height, double fx, double fy, double cx, double cy,
                         const std::array<double, 5>& d)
    : width_(width), height_(height), fx_(fx), fy_(fy), cx_(cx), cy_(cy), d_(d) {
  if (width < 1 || height < 1)
    throw ParameterError("camera: image size " + formatNumber(width) + " x " + formatNumber(height) +
                         " px must be at least 1 x 1");
  if (!(fx > 0.0) || !(fy > 0.0) || !std::isfinite(fx) || !std::isfinite(fy))
    throw ParameterError("camera: focal lengths fx = " + formatNumber(fx) + ", fy = " + formatNumber(fy) +
                         " px must be finite and > 0");
  // d/dr [r (1 + k1 r^2 + k2 r^4 + k3 r^6)] = 1 + 3 k1 t + 5 k2 t^2 + 7 k3 t^3 with t = r^2: first t where it
  // stops being positive.
  for (double t = 0.0; t < 1e6; t = t < 1.0 ? t + 1e-3 : t * 1.001)
    if (1.0 + 3.0 * d_[0] * t + 5.0 * d_[1] * t * t + 7.0 * d_[4] * t * t * t <= 0.0) {
      r2_max_ = t;
      break;
    }
}

CameraModel CameraModel::fromParams(SensorParams& p, const std::string& prefix, bool apply_render_scale) {
  const double w = p.number(prefix + "width", 2054.0, 1.0, 20000.0, "px");
  const double h = p.number(prefix + "height", 1544.0, 1.0, 20000.0, "px");
  if (w != std::floor(w))
    p.fail(prefix + "width", formatNumber(w), "a whole number of pixels");
  if (h != std::floor(h))
    p.fail(prefix + "height", formatNumber(h), "a whole number of pixels");
  const double hfov = p.number(prefix + "hfov", 80.0 * M_PI / 180.0, 1e-3, M_PI, "rad", true);
  const std::vector<double> d = p.numbers(prefix + "distortion", {0, 0, 0, 0, 0});
  const double scale = apply_render_scale ? p.number(prefix + "render_scale", 1.0, 1e-3, 1.0, "") : 1.0;
  const int sw = std::max(1, static_cast<int>(std::lround(scale * w)));
  const int sh = std::max(1, static_cast<int>(std::lround(scale * h)));
  // Focal length from the full-resolution field of view, scaled with the image (so a scaled image sees the
  // same scene); the principal point at the centre of the scaled image.
  const double f = (w / 2.0) / std::tan(hfov / 2.0) * (sw / w);
  const double fy = f * (sh / h) / (sw / w);
  return CameraModel(sw, sh, f, fy, (sw - 1) / 2.0, (sh - 1) / 2.0, {d[0], d[1], d[2], d[3], d[4]});
}

std::array<double, 9> CameraModel::K() const {
  return {fx_, 0, cx_, 0, fy_, cy_, 0, 0, 1};
}

std::array<double, 12> CameraModel::P() const {
  return {fx_, 0, cx_, 0, 0, fy_, cy_, 0, 0, 0, 1, 0};
}

Eigen::Vector2d CameraModel::distort(const Eigen::Vector2d& xy) const {
  const double x = xy.x(), y = xy.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + d_[0] * r2 + d_[1] * r2 * r2 + d_[4] * r2 * r2 * r2;
  const double k1 = d_[2], k2 = d_[3];  // p1, p2 (tangential)
  return Eigen::Vector2d(x * radial + 2.0 * k1 * x * y + k2 * (r2 + 2.0 * x * x),
                         y * radial + k1 * (r2 + 2.0 * y * y) + 2.0 * k2 * x * y);
}

Eigen::Vector2d CameraModel::undistort(const Eigen::Vector2d& xy_distorted) const {
  Eigen::Vector2d xy = xy_distorted;
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector2d err = distort(xy) - xy_distorted;
    if (err.squaredNorm() < 1e-24)
      break;
    xy -= err;
  }
  return xy;
}

bool CameraModel::project(const Eigen::Vector3d& p, Eigen::Vector2d& uv) const {
  if (!(p.z() > 0.0))
    return false;
  const Eigen::Vector2d xy(p.x() / p.z(), p.y() / p.z());
  if (xy.squaredNorm() >= r2_max_)
    return false;
  const Eigen::Vector2d d = distort(xy);
  uv = Eigen::Vector2d(fx_ * d.x() + cx_, fy_ * d.y() + cy_);
  return uv.x() >= -0.5 && uv.x() <= width_ - 0.5 && uv.y() >= -0.5 && uv.y() <= height_ - 0.5;
}

Eigen::Vector3d CameraModel::ray(double u, double v) const {
  const Eigen::Vector2d xy = undistort(Eigen::Vector2d((u - cx_) / fx_, (v - cy_) / fy_));
  return Eigen::Vector3d(xy.x(), xy.y(), 1.0).normalized();
}

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin

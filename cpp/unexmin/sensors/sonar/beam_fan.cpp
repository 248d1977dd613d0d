#include <unexmin/sensors/sonar/beam_fan.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace sensors {
namespace sonar {

BeamFan::BeamFan(const Eigen::Matrix3d& axis, double aperture, double width, int rays)
    : aperture_(aperture), width_(width), ray_angle_(aperture / std::max(1, rays)) {
  for (int j = 0; j < rays; ++j) {
    const double e = elevation(static_cast<std::size_t>(j));
    dirs_.push_back(axis * Eigen::Vector3d(std::cos(e), 0.0, std::sin(e)));
    along_.push_back(axis * Eigen::Vector3d(-std::sin(e), 0.0, std::cos(e)));
  }
  across_ = axis * Eigen::Vector3d::UnitY();
}

double BeamFan::elevation(std::size_t j) const {
  return -aperture_ / 2.0 + (static_cast<double>(j) + 0.5) * ray_angle_;
}

double BeamFan::extent(std::size_t j, double r, const Eigen::Vector3d& n) const {
  const double facing = std::max(std::abs(dirs_[j].dot(n)), 1e-3);
  return r * (ray_angle_ * std::abs(along_[j].dot(n)) + width_ * std::abs(across_.dot(n))) / facing;
}

double BeamFan::solidAngle() const {
  return width_ * 2.0 * std::sin(aperture_ / 2.0);
}

void BeamFan::aim(const Eigen::Isometry3d& sensor, double range_max, double surface_z, raycast::Ray* out) const {
  const Eigen::Vector3d origin = sensor.translation();
  const Eigen::Vector3f origin_f = origin.cast<float>();
  const Eigen::Matrix3d rotation = sensor.linear();  // a plain 3 x 3 for the loop
  const bool wet = origin.z() < surface_z;
  for (std::size_t j = 0; j < dirs_.size(); ++j) {
    // Components within 1e-9 of zero (rounding of the rotations) are zero: Embree's robust traversal loses rays
    // with a component of ~1e-17 whose origin lies on a bound of its hierarchy (a level sensor at x = 0 over a floor).
    Eigen::Vector3d d = rotation * dirs_[j];
    for (int c = 0; c < 3; ++c)
      d[c] = std::abs(d[c]) < 1e-9 ? 0.0 : d[c];
    d.normalize();
    double reach = range_max;
    if (!wet)
      reach = 1e-6;
    else if (d.z() > 1e-9)
      reach = std::min(range_max, (surface_z - origin.z()) / d.z());
    out[j].origin = origin_f;
    out[j].direction = d.cast<float>();
    out[j].max_range = static_cast<float>(std::max(reach, 1e-6));
  }
}

void BeamFan::listen(const Eigen::Matrix3d& rotation, const raycast::Hit* hits, const BeamReceiver& receiver,
                     double scale, std::vector<double>& energy) const {
  const std::size_t n = dirs_.size();
  for (std::size_t j = 0; j < n; ++j) {
    const raycast::Hit& hit = hits[j];
    if (!hit.hit())
      continue;
    const Eigen::Vector3d normal = rotation.transpose() * hit.normal.cast<double>();  // sensor frame
    const double r = static_cast<double>(hit.range);
    // The plane's footprint, at most twice the range step to a neighbour that hit (where the surface curves away or
    // ends, as at a sphere's rim, the plane would reach too far), or r (de + dw) with no neighbour hit.
    double bound = 0.0;
    for (const std::size_t m : {j - 1, j + 1})
      if (m < n && hits[m].hit())
        bound = std::max(bound, 2.0 * std::abs(static_cast<double>(hits[m].range) - r));
    if (!(j > 0 && hits[j - 1].hit()) && !(j + 1 < n && hits[j + 1].hit()))
      bound = r * (ray_angle_ + width_);
    const Echo echo{r, std::min(1.0, std::abs(dirs_[j].dot(normal)))};
    receiver.add(echo, std::min(extent(j, r, normal), bound), n, scale, energy);
  }
}

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

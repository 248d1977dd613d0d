#include <unexmin/sensors/vision/marine_snow.h>

#include <unexmin/core/error.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace sensors {
namespace vision {

double MarineSnow::density(const std::string& level) {
  if (level == "none")
    return 0.0;
  if (level == "low")
    return 50.0;
  if (level == "medium")
    return 200.0;
  if (level == "high")
    return 500.0;
  throw ConfigError("visibility level '" + level + "': expected none|low|medium|high");
}

double MarineSnow::density(const std::string& level, double turbidity) {
  if (level == "water")
    return std::min(1000.0, 130.0 * std::max(0.0, turbidity));
  return density(level);
}

MarineSnow::MarineSnow(double density, std::uint64_t seed, const Eigen::Vector3d& lens) : rng_(seed) {
  if (!(density >= 0.0) || !std::isfinite(density))
    throw ParameterError("marine snow: density " + formatNumber(density) + " 1/m^3: expected a finite number >= 0");
  const double side = 2.0 * kHalfSize;
  const auto n = static_cast<std::size_t>(std::llround(density * side * side * side));
  particles_.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = draw(), y = draw(), z = draw();
    particles_.push_back(lens + Eigen::Vector3d(x, y, z));
  }
}

double MarineSnow::draw() {
  return (2.0 * std::generate_canonical<double, 53>(rng_) - 1.0) * kHalfSize;
}

void MarineSnow::advance(const Eigen::Vector3d& lens, const Eigen::Vector3d& current, double dt) {
  const Eigen::Vector3d shift = current * std::max(0.0, dt);
  const double side = 2.0 * kHalfSize;
  for (auto& p : particles_) {
    p += shift;
    Eigen::Vector3d d = p - lens;
    for (int a = 0; a < 3; ++a) {
      if (d[a] >= -kHalfSize && d[a] < kHalfSize)
        continue;
      // Out through one face: in again through the opposite one, at the same depth past it; the other two
      // coordinates anew (the water that comes in is not the water that left).
      d[a] -= side * std::floor((d[a] + kHalfSize) / side);
      d[(a + 1) % 3] = draw();
      d[(a + 2) % 3] = draw();
    }
    p = lens + d;
  }
}

Eigen::Array3d MarineSnow::intensity(const ImageFormation& formation, const Eigen::Vector3d& p) const {
  const WaterOptics& water = formation.water();
  const Eigen::Array3d c = water.c().array();
  const double range = p.norm();
  const Eigen::Vector3d to_lens = -p / range;
  Eigen::Array3d j = Eigen::Array3d::Zero();
  for (int k : formation.activeLights()) {
    const LedLight& l = formation.lights()[static_cast<std::size_t>(k)];
    const Eigen::Vector3d w = p - l.position;
    const double r = w.norm();
    if (!(r > 1e-6))
      continue;
    const double profile = l.profile(l.axis.dot(w / r));
    if (profile <= 0.0)
      continue;
    const Eigen::Array3d irradiance = l.intensity.array() * profile * (-c * r).exp() / (r * r);
    const double alpha = std::acos(std::max(-1.0, std::min(1.0, (-w / r).dot(to_lens))));
    const double phase = (2.0 / (3.0 * M_PI)) * (std::sin(alpha) + (M_PI - alpha) * std::cos(alpha));
    j += kAlbedo * irradiance * kRadius * kRadius * phase;
  }
  return j;
}

std::size_t MarineSnow::draw(const CameraModel& camera, const ImageFormation& formation, const Motion& motion,
                             const std::vector<float>& range, std::vector<float>& radiance,
                             std::vector<std::size_t>& touched) const {
  const int w = camera.width(), h = camera.height();
  const Eigen::Matrix3d to_camera = motion.pose.linear().transpose();
  const Eigen::Vector3d lens = motion.pose.translation();
  const Eigen::Array3d c = formation.water().c().array();
  const double fx = camera.fx(), fy = camera.fy(), margin = 4.0;
  std::size_t drawn = 0;
  for (const auto& world : particles_) {
    const Eigen::Vector3d p = to_camera * (world - lens);
    if (p.z() < kNear)
      continue;
    Eigen::Vector2d a(-1e9, -1e9);  // left there when the point is beyond the lens's field
    if (!camera.project(p, a) && !(a.x() > -margin && a.x() < w + margin && a.y() > -margin && a.y() < h + margin))
      continue;
    const double r = p.norm();
    // Where it is at the end of the exposure: the water's velocity relative to the moving camera.
    const Eigen::Vector3d relative = motion.current - motion.velocity - motion.angular.cross(world - motion.base);
    const Eigen::Vector3d q = p + motion.exposure_time * (to_camera * relative);
    Eigen::Vector2d b = a;
    if (q.z() >= kNear)
      camera.project(q, b);
    const Eigen::Array3d total = intensity(formation, p) * (-c * r).exp() * (fx * fy / (r * r));
    if (!(total.maxCoeff() > 0.0))
      continue;
    const double sigma = std::max(kSpot, kRadius * fx / r);
    const double len = (b - a).norm();
    if (!(len < 0.5 * (w + h)))
      continue;  // a particle swept across half the image (q behind the lens, or a spin): not a speck
    const int steps = std::max(1, static_cast<int>(std::ceil(len / 0.5)));
    const double reach = 3.0 * sigma, inv2s2 = 1.0 / (2.0 * sigma * sigma);
    const Eigen::Array3d share = total / steps;
    bool seen = false;
    for (int s = 0; s < steps; ++s) {
      // One spot of the streak: its Gaussian weights over the pixels within 3 sigma, normalised to sum to 1 (a
      // spot cut by the image's edge or hidden by a surface loses its share there).
      const Eigen::Vector2d centre = a + (b - a) * ((s + 0.5) / steps);
      const int u0 = static_cast<int>(std::floor(centre.x() - reach)),
                u1 = static_cast<int>(std::ceil(centre.x() + reach));
      const int v0 = static_cast<int>(std::floor(centre.y() - reach)),
                v1 = static_cast<int>(std::ceil(centre.y() + reach));
      double sum = 0.0;
      for (int v = v0; v <= v1; ++v)
        for (int u = u0; u <= u1; ++u)
          sum += std::exp(-((u - centre.x()) * (u - centre.x()) + (v - centre.y()) * (v - centre.y())) * inv2s2);
      for (int v = std::max(0, v0); v <= std::min(h - 1, v1); ++v)
        for (int u = std::max(0, u0); u <= std::min(w - 1, u1); ++u) {
          const std::size_t i = static_cast<std::size_t>(v) * w + u;
          if (!(range[i] > r))
            continue;  // a surface nearer than the particle hides it
          const double d2 = (u - centre.x()) * (u - centre.x()) + (v - centre.y()) * (v - centre.y());
          const Eigen::Array3d add = share * (std::exp(-d2 * inv2s2) / sum);
          float* px = &radiance[3 * i];
          for (int k = 0; k < 3; ++k)
            px[k] += static_cast<float>(add[k]);
          touched.push_back(i);
          seen = true;
        }
    }
    drawn += seen ? 1 : 0;
  }
  return drawn;
}

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin

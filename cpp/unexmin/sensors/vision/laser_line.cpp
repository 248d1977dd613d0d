#include <unexmin/sensors/vision/laser_line.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace sensors {
namespace vision {
namespace {

/// Neighbouring hits farther apart than this in the image [px] are not joined (a depth jump between them).
constexpr double kMaxSegment = 6.0;

}  // namespace

LaserLine::LaserLine(std::unique_ptr<SlsSensor> sls, const Eigen::Isometry3d& camera_pose, const CameraModel& camera,
                     double power, double width, const Eigen::Vector3d& colour, double clip_far, double hull_albedo)
    : sls_(std::move(sls)),
      camera_pose_(camera_pose),
      camera_(camera),
      power_(power),
      width_(width),
      colour_(colour.cast<float>()),
      clip_far_(clip_far),
      hull_albedo_(hull_albedo) {
  // The fan plane through the model's first and last rays; rays spaced so that neighbouring hits are about
  // 0.5 px apart where the line crosses the image centre.
  const Eigen::Vector3d first = sls_->rayDirection(0).normalized();
  const Eigen::Vector3d last = sls_->rayDirection(sls_->rays() - 1).normalized();
  const double fan = std::acos(std::max(-1.0, std::min(1.0, first.dot(last))));
  const double pixel_angle = 1.0 / camera_.fx();  // [rad] at the image centre
  const int n = std::max(16, std::min(20000, static_cast<int>(std::ceil(2.0 * fan / pixel_angle)) + 1));
  dtheta_ = fan / (n - 1);
  Eigen::Vector3d normal = first.cross(last);
  if (normal.norm() < 1e-9)
    normal = first.unitOrthogonal();  // a fan of 180 deg: SlsSensor's x-z plane
  normal.normalize();
  for (int j = 0; j < n; ++j)
    fan_.push_back(Eigen::AngleAxisd(j * dtheta_, normal) * first);
  rays_.resize(fan_.size());
}

Eigen::Vector2d LaserLine::pixel(const Eigen::Vector3d& p) const {
  const Eigen::Vector2d d = camera_.distort(Eigen::Vector2d(p.x() / p.z(), p.y() / p.z()));
  return {camera_.fx() * d.x() + camera_.cx(), camera_.fy() * d.y() + camera_.cy()};
}

void LaserLine::draw(const SensorContext& ctx, const WaterOptics& water, const std::vector<float>& range,
                     std::vector<float>& radiance, std::vector<std::size_t>& touched) {
  const double t = ctx.world.time();
  const Eigen::Isometry3d head = ctx.state.pose * sls_->headPose(sls_->motorAngle(t));
  const Eigen::Isometry3d cam_inv = (ctx.state.pose * camera_pose_).inverse();
  for (std::size_t j = 0; j < fan_.size(); ++j) {
    rays_[j].origin = head.translation().cast<float>();
    rays_[j].direction = (head.linear() * fan_[j]).normalized().cast<float>();
    rays_[j].max_range = static_cast<float>(clip_far_);
  }
  if (ctx.rays)
    ctx.rays->cast(rays_, hits_, ctx.robot_index, raycast::Incidence::skip,
                   raycast::SeenBy::cameras);  // the normal is enough
  else
    hits_.assign(rays_.size(), raycast::Hit());

  const double c = water.c().y();
  const sim::SedimentField& silt = ctx.world.sediment();
  const int w = camera_.width(), h = camera_.height();
  // Per hit: pixel, visible, and S / dθ (the slice's image signal per radian of fan).
  struct Spot {
    Eigen::Vector2d uv;
    bool seen = false;
    double density = 0.0;
  };
  std::vector<Spot> spots(fan_.size());
  const SurfaceMaterials& materials = SurfaceMaterials::of(ctx.world, materials_);
  for (std::size_t j = 0; j < fan_.size(); ++j) {
    const raycast::Hit& hit = hits_[j];
    if (!hit.hit())
      continue;
    const Eigen::Vector3d p = cam_inv * hit.point(rays_[j]).cast<double>();
    Eigen::Vector2d uv;
    if (!camera_.project(p, uv))
      continue;
    const double rc = p.norm();
    const int iu = std::min(w - 1, std::max(0, static_cast<int>(std::lround(uv.x()))));
    const int iv = std::min(h - 1, std::max(0, static_cast<int>(std::lround(uv.y()))));
    if (rc > range[static_cast<std::size_t>(iv) * w + iu] * 1.02 + 0.01)
      continue;  // hidden behind that surface
    // Image area per unit wall area at the hit, from two tangent steps on the surface.
    const Eigen::Vector3d n = cam_inv.linear() * hit.normal.cast<double>();
    const Eigen::Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    const double eps = 1e-3 * rc;
    const Eigen::Vector3d q1 = p + eps * t1, q2 = p + eps * t2;
    if (!(q1.z() > 0.0) || !(q2.z() > 0.0))
      continue;
    const Eigen::Vector2d a = pixel(p), d1 = pixel(q1) - a, d2 = pixel(q2) - a;
    const double jacobian = std::abs(d1.x() * d2.y() - d1.y() * d2.x()) / (eps * eps);  // [px^2 / m^2]
    double albedo = hull_albedo_;
    if (hit.kind == raycast::HitKind::mesh)
      albedo = materials.albedo(hit, hit.point(rays_[j])).y();
    spots[j].uv = uv;
    spots[j].seen = true;
    spots[j].density = albedo / M_PI * power_ / (dtheta_ * (fan_.size() - 1)) * jacobian *
                       std::exp(-c * (static_cast<double>(hit.range) + rc));
    if (!silt.empty()) {  // the thrusters' silt on both legs
      const Eigen::Vector3d lens = cam_inv.inverse().translation(), point = hit.point(rays_[j]).cast<double>();
      spots[j].density *=
          std::exp(-silt.opticalDepth(rays_[j].origin.cast<double>(), rays_[j].direction.cast<double>(), hit.range) -
                   silt.opticalDepth(lens, (point - lens) / rc, rc));
    }
  }
  for (std::size_t j = 0; j + 1 < spots.size(); ++j) {
    const Spot& a = spots[j];
    const Spot& b = spots[j + 1];
    if (!a.seen || !b.seen || (b.uv - a.uv).norm() > kMaxSegment)
      continue;
    splat(a.uv, b.uv, 0.5 * (a.density + b.density) * dtheta_, radiance, touched);
  }
}

void LaserLine::splat(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double total, std::vector<float>& radiance,
                      std::vector<std::size_t>& touched) const {
  const int w = camera_.width(), h = camera_.height();
  const Eigen::Vector2d ab = b - a;
  const double len = ab.norm();
  const double reach = 3.0 * width_;
  const int u0 = std::max(0, static_cast<int>(std::floor(std::min(a.x(), b.x()) - reach)));
  const int u1 = std::min(w - 1, static_cast<int>(std::ceil(std::max(a.x(), b.x()) + reach)));
  const int v0 = std::max(0, static_cast<int>(std::floor(std::min(a.y(), b.y()) - reach)));
  const int v1 = std::min(h - 1, static_cast<int>(std::ceil(std::max(a.y(), b.y()) + reach)));
  const double s2 = 2.0 * width_ * width_;
  for (int v = v0; v <= v1; ++v)
    for (int u = u0; u <= u1; ++u) {
      const Eigen::Vector2d q(u - a.x(), v - a.y());
      double value;
      if (len < 0.5) {  // seen end-on: a round spot
        value = total * std::exp(-q.squaredNorm() / s2) / (M_PI * s2);
      } else {
        // This segment's share of the line: pixels whose foot falls on [a, b) (the next segment takes b).
        const double along = q.dot(ab) / len;
        if (along < 0.0 || along >= len)
          continue;
        const double across2 = q.squaredNorm() - along * along;
        value = total / len * std::exp(-std::max(0.0, across2) / s2) / std::sqrt(M_PI * s2);
      }
      const std::size_t i = static_cast<std::size_t>(v) * w + u;
      float* px = &radiance[3 * i];
      for (int k = 0; k < 3; ++k)
        px[k] += static_cast<float>(value) * colour_[k];
      touched.push_back(i);
    }
}

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin

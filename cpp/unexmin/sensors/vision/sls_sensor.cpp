#include <unexmin/sensors/vision/sls_sensor.h>

#include <unexmin/sensors/vision/water_optics.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace sensors {
namespace vision {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kInf = std::numeric_limits<double>::infinity();
/// A sight line shorter than the camera range by more than this [m] is blocked (the point's own surface is
/// at the end of the line).
constexpr double kSightSlack = 0.005;

}  // namespace

SlsSensor::SlsSensor(const sim::SensorSpec& spec, const SensorSetup& setup) : Sensor(spec, setup) {
  SensorParams p(spec, setup.robot);
  fan_ = p.number("fan", 100.0 * kDeg, 1e-3, M_PI, "rad", true);
  const double rays = p.number("rays", 200.0, 2.0, 100000.0, "rays");
  if (rays != std::floor(rays))
    p.fail("rays", formatNumber(rays), "a whole number of rays");
  range_min_ = p.number("range_min", 0.1, 0.0, 1000.0, "m");
  range_max_ = p.number("range_max", 5.0, 0.01, 1000.0, "m");
  if (!(range_max_ > range_min_))
    p.fail("range_max", formatNumber(range_max_), "more than range_min");
  motor_min_ = p.number("motor_min", -45.0 * kDeg, -2.0 * M_PI, 2.0 * M_PI, "rad");
  motor_max_ = p.number("motor_max", 45.0 * kDeg, -2.0 * M_PI, 2.0 * M_PI, "rad");
  if (motor_max_ < motor_min_)
    p.fail("motor_max", formatNumber(motor_max_), "at least motor_min");
  motor_speed_ = p.number("motor_speed", 10.0 * kDeg, 0.0, 100.0, "rad/s");
  motor_start_ =
      p.number("motor_start", std::min(std::max(0.0, motor_min_), motor_max_), motor_min_, motor_max_, "rad");
  subpixel_ = p.number("subpixel_noise", 0.2, 0.0, 100.0, "px");
  threshold_ = p.number("threshold", 1e-3, 0.0, 1e6, "(line strength)");
  backscatter_length_ = p.number("backscatter_length", 1.0, 0.0, 1000.0, "m");
  noise_ = p.text("noise", "gaussian", {"gaussian", "none"}) == "gaussian";
  camera_frame_ = p.text("camera_frame", "");
  scan_frame_ = p.text("scan_frame", spec.link);
  camera_ = CameraModel::fromParams(p, "camera_", false);
  const sim::JointInfo& joint = p.movingJoint(setup.description);
  p.finish();
  bool known = false;
  for (const auto& j : setup.description.joints)
    known = known || j.child == camera_frame_ || j.parent == camera_frame_;
  if (!known)
    p.fail("camera_frame", "'" + camera_frame_ + "'", "a link of the robot (the optical frame of the unit's camera)");
  camera_pose_ = setup.description.linkPose(camera_frame_);

  joint_ = joint.name;  // the motor joint
  axis_ = joint.axis.normalized();

  const int n = static_cast<int>(rays);
  for (int j = 0; j < n; ++j) {
    const double e = -fan_ / 2.0 + j * fan_ / (n - 1);
    dirs_.emplace_back(std::cos(e), 0.0, std::sin(e));
  }
  rays_.resize(dirs_.size());
  baseline_ = (camera_pose_.translation() - spec.pose.translation()).norm();
}

double SlsSensor::motorAngle(double t) const {
  const double span = motor_max_ - motor_min_;
  if (motor_speed_ <= 0.0 || span <= 0.0)
    return motor_start_;
  const double m = std::fmod(motor_start_ - motor_min_ + motor_speed_ * t, 2.0 * span);
  return motor_min_ + (m <= span ? m : 2.0 * span - m);
}

double SlsSensor::motorVelocity(double t) const {
  const double span = motor_max_ - motor_min_;
  if (motor_speed_ <= 0.0 || span <= 0.0)
    return 0.0;
  const double m = std::fmod(motor_start_ - motor_min_ + motor_speed_ * t, 2.0 * span);
  return m < span ? motor_speed_ : -motor_speed_;
}

Eigen::Isometry3d SlsSensor::headPose(double a) const {
  return spec().pose * Eigen::AngleAxisd(a, axis_);
}

Eigen::Vector3d SlsSensor::rayDirection(int j) const {
  return dirs_.at(static_cast<std::size_t>(j));
}

double SlsSensor::depthSigma(double z) const {
  if (!noise_ || baseline_ <= 0.0)
    return 0.0;
  return z * z * subpixel_ / (camera_.fx() * baseline_);
}

void SlsSensor::movedJoints(std::vector<MovedJoint>& out) const {
  out.push_back({joint_, motorAngle(now_), motorVelocity(now_)});
}

void SlsSensor::sample(const SensorContext& ctx) {
  const double t = ctx.world.time();
  SlsScan& out = last_;
  out.time = t;
  out.motor_angle = motorAngle(t);
  const Eigen::Isometry3d head = ctx.state.pose * headPose(out.motor_angle);
  const Eigen::Isometry3d cam = ctx.state.pose * camera_pose_;
  const Eigen::Isometry3d cam_inv = cam.inverse();
  for (std::size_t j = 0; j < dirs_.size(); ++j) {
    rays_[j].origin = head.translation().cast<float>();
    rays_[j].direction = (head.linear() * dirs_[j]).normalized().cast<float>();
    rays_[j].max_range = static_cast<float>(range_max_);
  }
  // Laser light lands on what the cameras see; the incidence is needed only for the points the camera sees.
  castRays(ctx, rays_, hits_, raycast::Incidence::skip, raycast::SeenBy::cameras);

  const double turbidity = opticalTurbidity(ctx.world.config(), head.translation(), ctx.world.time());
  if (water_world_ != &ctx.world || turbidity != water_turbidity_) {  // the world's water, or the column's here
    water_ = WaterOptics::fromWorld(ctx.world.config(), turbidity);
    water_world_ = &ctx.world;
    water_turbidity_ = turbidity;
  }
  const double c = water_.c().y(), b = water_.b.y();
  const double level = threshold_ * (1.0 + b * backscatter_length_);

  // Laser points inside the image: candidates for the sight lines.
  out.ranges.assign(dirs_.size(), static_cast<float>(kInf));
  candidates_.clear();
  sight_.clear();
  for (std::size_t j = 0; j < dirs_.size(); ++j) {
    const raycast::Hit& h = hits_[j];
    if (!h.hit())
      continue;
    if (h.range < range_min_) {
      out.ranges[j] = static_cast<float>(-kInf);
      continue;
    }
    out.ranges[j] = h.range;
    const Eigen::Vector3d point = h.point(rays_[j]).cast<double>();
    Eigen::Vector2d uv;
    if (!camera_.project(cam_inv * point, uv))
      continue;
    raycast::Ray sight;
    const Eigen::Vector3d to = point - cam.translation();
    const double rc = to.norm();
    sight.origin = cam.translation().cast<float>();
    sight.direction = (to / rc).cast<float>();
    sight.max_range = static_cast<float>(std::max(1e-4, rc - kSightSlack));
    sight_.push_back(sight);
    candidates_.push_back(static_cast<int>(j));
  }
  castRays(ctx, sight_, sight_hits_, raycast::Incidence::skip,
           raycast::SeenBy::cameras);  // only whether something is in the way

  out.points.clear();
  out.intensity.clear();
  for (std::size_t k = 0; k < candidates_.size(); ++k) {
    // One noise draw per candidate, visible or not, so the stream does not depend on occluders.
    const double draw = noise_ ? random().gauss() : 0.0;
    if (sight_hits_[k].hit())
      continue;  // something between the point and the lens
    const std::size_t j = static_cast<std::size_t>(candidates_[k]);
    const raycast::Hit& h = hits_[j];
    const double rl = h.range;
    const double rc = sight_[k].max_range + kSightSlack;
    double albedo = SurfaceMaterials::kHullAlbedo.y();  // the hull's green, as camera i sees the 532 nm line
    if (h.kind == raycast::HitKind::mesh)
      albedo = SurfaceMaterials::of(ctx.world, materials_).albedo(h, h.point(rays_[j])).y();
    double strength = albedo * std::cos(static_cast<double>(raycast::RayCaster::incidence(rays_[j], h))) *
                      std::exp(-c * (rl + rc)) / rl;
    double detect = level;
    const sim::SedimentField& silt = ctx.world.sediment();
    if (!silt.empty()) {
      // The thrusters' silt: both legs attenuated, and its glow over the first backscatter_length of the sight line
      // raises the background as the water's b does.
      const Eigen::Vector3d lens = sight_[k].origin.cast<double>(), to = sight_[k].direction.cast<double>();
      strength *= std::exp(-silt.opticalDepth(rays_[j].origin.cast<double>(), rays_[j].direction.cast<double>(), rl) -
                           silt.opticalDepth(lens, to, rc));
      detect += threshold_ * silt.opticalDepth(lens, to, std::min(rc, backscatter_length_));
    }
    if (!(strength >= detect) || strength <= 0.0)
      continue;
    // Triangulated point in the camera frame, its depth off by sigma_Z along the camera ray.
    const Eigen::Vector3d p = cam_inv * h.point(rays_[j]).cast<double>();
    const double dz = depthSigma(p.z()) * draw;
    out.points.push_back((p * ((p.z() + dz) / p.z())).cast<float>());
    out.intensity.push_back(static_cast<float>(detect > 0.0 ? strength / detect : 1.0));
  }
}

void SlsSensor::describeSample(SampleWriter& out) const {
  out.scalar("motor_angle", "rad", last_.motor_angle);
  out.array("ranges", "m", last_.ranges);
  std::vector<float> points;
  points.reserve(3 * last_.points.size());
  for (const auto& p : last_.points)
    points.insert(points.end(), {p[0], p[1], p[2]});
  out.array("points", "m", points, {last_.points.size(), 3});
  out.array("intensity", "-", last_.intensity);
}

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin

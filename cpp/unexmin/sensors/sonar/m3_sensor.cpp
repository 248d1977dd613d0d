#include <unexmin/sensors/sonar/m3_sensor.h>

#include <unexmin/sensors/sensor_params.h>
#include <unexmin/sensors/sonar/equation_params.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace unexmin {
namespace sonar {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr float kInf = std::numeric_limits<float>::infinity();

int wholeNumber(sensors::SensorParams& p, const std::string& key, double fallback, double lo, double hi)
{
  const double v = p.number(key, fallback, lo, hi, "(whole number)");
  if (v != std::floor(v)) p.fail(key, formatNumber(v), "a whole number");
  return static_cast<int>(v);
}

}  // namespace

M3Sensor::M3Sensor(const sim::SensorSpec& spec, const sensors::SensorSetup& setup) : Sensor(spec, setup)
{
  sensors::SensorParams p(spec, setup.robot);
  const bool noise = p.text("noise", "gaussian", {"gaussian", "none"}) == "gaussian";
  beams_ = wholeNumber(p, "beams", 256.0, 1.0, 4096.0);
  rays_per_beam_ = wholeNumber(p, "rays_per_beam", 4.0, 1.0, 64.0);
  fov_h_ = p.number("fov_h", 120.0 * kDeg, 0.0, 2.0 * M_PI, "rad");
  fov_v_ = p.number("fov_v", 3.0 * kDeg, 0.0, M_PI, "rad");
  range_min_ = p.number("range_min", 0.2, 0.0, 1000.0, "m");
  range_max_ = p.number("range_max", 150.0, 0.0, 1000.0, "m");
  if (!(range_max_ > range_min_)) p.fail("range_max", formatNumber(range_max_), "more than range_min");
  resolution_ = p.number("range_resolution", 0.01, 1e-6, 10.0, "m");
  range_noise_ = p.number("range_noise", 0.0, 0.0, 10.0, "m");
  if (!noise) range_noise_ = 0.0;
  EchoParams e;  // the sonar equation of the intensities (echo_model.h): one bin over the range window
  e.range_min = range_min_;
  e.range_max = range_max_;
  e.nbins = 1;
  e.gain = p.number("gain", 0.5, 0.0, 1.0, "(0 low .. 1 high)");
  readEquationParams(p, e, 210.0);
  p.finish();
  // Solid angle of one beam: its share of the fan's azimuth x elevation rectangle.
  e.beam_solid_angle = fov_h_ / beams_ * 2.0 * std::sin(fov_v_ / 2.0);
  if (!(e.beam_solid_angle > 0.0)) p.fail("fov_h", formatNumber(fov_h_), "a fan with a solid angle (fov_h, fov_v > 0)");
  echo_ = EchoModel(e);

  for (int k = 0; k < beams_; ++k)
    for (int j = 0; j < rays_per_beam_; ++j) dirs_.push_back(rayDirection(k, j));
  rays_.resize(dirs_.size());
}

Eigen::Vector3d M3Sensor::rayDirection(std::size_t k, int j) const
{
  const double a = beamAngle(k);
  const double e = -fov_v_ / 2.0 + (j + 0.5) * fov_v_ / rays_per_beam_;
  return Eigen::Vector3d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
}

void M3Sensor::onReset() { last_ = M3Scan(); }

void M3Sensor::sample(const sensors::SensorContext& ctx)
{
  const Eigen::Isometry3d sonar = ctx.state.pose * spec().pose;
  const Eigen::Matrix3d R = sonar.linear();
  const double surface_z = ctx.world.water().surface_z;
  for (std::size_t i = 0; i < dirs_.size(); ++i) {
    const Eigen::Vector3d d = (R * dirs_[i]).normalized();
    rays_[i].origin = sonar.translation().cast<float>();
    rays_[i].direction = d.cast<float>();
    // Sound does not cross the free surface: a ray stops there (the surface's grazing echo is not a return;
    // its reflection comes after the direct returns, so the first return keeps to the direct paths).
    const double to_surface = d.z() > 1e-9 ? (surface_z - sonar.translation().z()) / d.z() : range_max_;
    rays_[i].max_range = static_cast<float>(std::clamp(to_surface, 0.0, range_max_));
  }
  castRays(ctx, rays_, hits_, raycast::Incidence::skip);  // only each beam's first return needs it

  M3Scan& out = last_;
  out.time = ctx.world.time();
  out.ranges.assign(beams_, kInf);
  out.intensities.assign(beams_, 0.0f);
  for (int k = 0; k < beams_; ++k) {
    int first = -1;
    for (int j = 0; j < rays_per_beam_; ++j) {
      const std::size_t i = static_cast<std::size_t>(k) * rays_per_beam_ + j;
      if (hits_[i].hit() && (first < 0 || hits_[i].range < hits_[static_cast<std::size_t>(k) * rays_per_beam_ + first].range))
        first = j;
    }
    // One draw per beam, return or not, so the stream does not depend on the geometry.
    const double n = range_noise_ > 0.0 ? range_noise_ * random().gauss() : 0.0;
    if (first < 0) continue;
    const std::size_t i = static_cast<std::size_t>(k) * rays_per_beam_ + first;
    const double r = std::round((hits_[i].range + n) / resolution_) * resolution_;
    if (r > range_max_) continue;  // +inf: no detection within range
    if (r < range_min_) {
      out.ranges[k] = -kInf;  // detected, but nearer than the blanking range
      continue;
    }
    out.ranges[k] = static_cast<float>(r);
    // The return's level by the sonar equation, the beam's whole footprint at the return's incidence (computed
    // for the first returns only: the cast skipped it).
    const double c = std::cos(static_cast<double>(raycast::RayCaster::incidence(rays_[i], hits_[i])));
    const Echo echo{hits_[i].range, c};
    out.intensities[k] = static_cast<float>(static_cast<double>(echo_.echoCode(echo, 1)) / echo_.params().levels);
  }
}

}  // namespace sonar
}  // namespace unexmin

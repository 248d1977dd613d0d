#include <unexmin/sensors/sonar/m3_sensor.h>

#include <unexmin/sensors/sensor_params.h>
#include <unexmin/sensors/sonar/equation_params.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace unexmin {
namespace sensors {
namespace sonar {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr float kInf = std::numeric_limits<float>::infinity();

int wholeNumber(sensors::SensorParams& p, const std::string& key, double fallback, double lo, double hi) {
  const double v = p.number(key, fallback, lo, hi, "(whole number)");
  if (v != std::floor(v))
    p.fail(key, formatNumber(v), "a whole number");
  return static_cast<int>(v);
}

}  // namespace

M3Sensor::M3Sensor(const sim::SensorSpec& spec, const sensors::SensorSetup& setup) : Sensor(spec, setup) {
  sensors::SensorParams p(spec, setup.robot);
  const bool noise = p.text("noise", "gaussian", {"gaussian", "none"}) == "gaussian";
  beams_ = wholeNumber(p, "beams", 256.0, 1.0, 4096.0);
  rays_per_beam_ = wholeNumber(p, "rays_per_beam", 4.0, 1.0, 64.0);
  fov_h_ = p.number("fov_h", 120.0 * kDeg, 0.0, 2.0 * M_PI, "rad");
  fov_v_ = p.number("fov_v", 3.0 * kDeg, 0.0, M_PI, "rad");
  range_min_ = p.number("range_min", 0.2, 0.0, 1000.0, "m");
  range_max_ = p.number("range_max", 150.0, 0.0, 1000.0, "m");
  if (!(range_max_ > range_min_))
    p.fail("range_max", formatNumber(range_max_), "more than range_min");
  resolution_ = p.number("range_resolution", 0.01, 1e-6, 10.0, "m");
  sound_speed_ = SoundSpeed::read(p);
  range_noise_ = p.number("range_noise", 0.0, 0.0, 10.0, "m");
  if (!noise)
    range_noise_ = 0.0;
  EchoParams e;  // the sonar equation of the intensities (echo_model.h): one bin over the range window
  e.range_min = range_min_;
  e.range_max = range_max_;
  e.nbins = 1;
  e.gain = p.number("gain", 0.5, 0.0, 1.0, "(0 low .. 1 high)");
  readEquationParams(p, e, 210.0);
  reflector_ = readSurfaceParams(p, e);
  // Detection: the receiver's noise in its band [dB re 1 uPa] (assumed: with the defaults a wall of
  // backscatter_strength seen head-on is detected out to the datasheet's 150 m, EL = 82.8 dB there) and the
  // signal-to-noise ratio of a detection [dB] (Albersheim's equation, one sample, Pd 0.5 at Pfa 1e-5: 10.4 dB).
  detection_level_ = p.number("noise_level", 72.0, 0.0, 300.0, "dB re 1 uPa") +
                     p.number("detection_threshold", 10.0, 0.0, 100.0, "dB");
  detection_power_ = std::pow(10.0, detection_level_ / 10.0);
  p.finish();
  // Solid angle of one beam: its share of the fan's azimuth x elevation rectangle.
  e.beam_solid_angle = fov_h_ / beams_ * 2.0 * std::sin(fov_v_ / 2.0);
  if (!(e.beam_solid_angle > 0.0))
    p.fail("fov_h", formatNumber(fov_h_), "a fan with a solid angle (fov_h, fov_v > 0)");
  echo_ = EchoModel(e);

  for (int k = 0; k < beams_; ++k)
    for (int j = 0; j < rays_per_beam_; ++j)
      dirs_.push_back(rayDirection(k, j));
  rays_.resize(dirs_.size());
  surface_.resize(dirs_.size());
}

Eigen::Vector3d M3Sensor::rayDirection(std::size_t k, int j) const {
  const double a = beamAngle(k);
  const double e = -fov_v_ / 2.0 + (j + 0.5) * fov_v_ / rays_per_beam_;
  return Eigen::Vector3d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
}

void M3Sensor::onReset() {
  last_ = M3Scan();
}

void M3Sensor::sample(const sensors::SensorContext& ctx) {
  const Eigen::Isometry3d sonar = ctx.state.pose * spec().pose;
  const Eigen::Matrix3d R = sonar.linear();
  const Eigen::Vector3d origin = sonar.translation();
  const double surface_z = ctx.world.water().surface_z;
  const bool multipath = reflector_.multipath && origin.z() < surface_z;
  // ranges as the sonar reports them: the path in the water times c_configured / c_water; in faster water it hears
  // range_max from farther away
  scale_ = sound_speed_.rangeFactor(ctx.world, origin);
  reach_ = range_max_ / std::min(1.0, scale_);
  for (std::size_t i = 0; i < dirs_.size(); ++i) {
    const Eigen::Vector3d d = (R * dirs_[i]).normalized();
    rays_[i].origin = origin.cast<float>();
    rays_[i].direction = d.cast<float>();
    // Sound does not cross the free surface: a ray stops there (its echo and reflection below, with multipath).
    const double to_surface = d.z() > 1e-9 ? (surface_z - origin.z()) / d.z() : reach_;
    rays_[i].max_range = static_cast<float>(std::clamp(to_surface, 1e-6, reach_));
    surface_[i] = multipath && d.z() > 1e-9 && to_surface < reach_ ? to_surface : -1.0;
  }
  castRays(ctx, rays_, hits_, raycast::Incidence::skip);  // the incidence of the few echoes that need it

  mirrored_.clear();
  mirror_of_.clear();
  first_.assign(beams_, Return());
  for (int k = 0; k < beams_; ++k)
    directAndSurface(k, surface_z);
  if (!mirrored_.empty()) {
    castRays(ctx, mirrored_, mirror_hits_, raycast::Incidence::skip);
    for (std::size_t m = 0; m < mirrored_.size(); ++m) {
      if (!mirror_hits_[m].hit())
        continue;
      const std::size_t i = mirror_of_[m];
      Return& best = first_[i / rays_per_beam_];
      const double range = surface_[i] + mirror_hits_[m].range;  // unfolded: out and back the same way
      if (range >= best.range)
        continue;
      const double c = std::cos(static_cast<double>(raycast::RayCaster::incidence(mirrored_[m], mirror_hits_[m])));
      const Echo ghost{range, c, reflector_.ghost_extra};
      if (detected(ghost))
        best = Return{range, ghost};
    }
  }

  M3Scan& out = last_;
  out.time = ctx.world.time();
  out.ranges.assign(beams_, kInf);
  out.intensities.assign(beams_, 0.0f);
  for (int k = 0; k < beams_; ++k) {
    // One draw per beam, return or not, so the stream does not depend on the geometry.
    const double n = range_noise_ > 0.0 ? range_noise_ * random().gauss() : 0.0;
    const Return& first = first_[k];
    if (!std::isfinite(first.range))
      continue;
    const double r = std::round((scale_ * first.range + n) / resolution_) * resolution_;
    if (r > range_max_)
      continue;  // +inf: no detection within range
    if (r < range_min_) {
      out.ranges[k] = -kInf;  // detected, but nearer than the blanking range
      continue;
    }
    out.ranges[k] = static_cast<float>(r);
    out.intensities[k] = static_cast<float>(static_cast<double>(echo_.echoCode(first.echo, 1)) / echo_.params().levels);
  }
}

void M3Sensor::directAndSurface(int k, double surface_z) {
  const std::size_t base = static_cast<std::size_t>(k) * rays_per_beam_;
  const std::size_t end = base + rays_per_beam_;
  Return& best = first_[k];
  // The nearest direct hit is nearly always a detection: its incidence and level only, then.
  std::size_t nearest = end;
  bool surface = false;  // some ray meets the surface first
  for (std::size_t i = base; i < end; ++i) {
    if (hits_[i].hit()) {
      if (nearest == end || hits_[i].range < hits_[nearest].range)
        nearest = i;
    } else {
      surface = surface || surface_[i] >= 0.0;
    }
  }
  if (nearest != end) {
    const auto direct = [&](std::size_t i) {
      return Echo{hits_[i].range, std::cos(static_cast<double>(raycast::RayCaster::incidence(rays_[i], hits_[i])))};
    };
    const Echo echo = direct(nearest);
    if (detected(echo)) {
      best = Return{echo.range, echo};
    } else {  // the others by range: the first detected one
      order_.clear();
      for (std::size_t i = base; i < end; ++i)
        if (hits_[i].hit() && i != nearest)
          order_.push_back(i);
      std::sort(order_.begin(), order_.end(),
                [&](std::size_t a, std::size_t b) { return hits_[a].range < hits_[b].range; });
      for (const std::size_t i : order_) {
        const Echo e = direct(i);
        if (detected(e)) {
          best = Return{e.range, e};
          break;
        }
      }
    }
  }
  if (!surface)
    return;
  // The surface's own echo where a ray meets it first (its normal is the vertical: cos(incidence) = d_z).
  for (std::size_t i = base; i < end; ++i) {
    if (surface_[i] < 0.0 || hits_[i].hit() || surface_[i] >= best.range)
      continue;
    const Echo echo{surface_[i], static_cast<double>(rays_[i].direction.z()), reflector_.surface_extra};
    if (detected(echo))
      best = Return{surface_[i], echo};
  }
  // The reflected rays, only where a ghost could still be the first detection: the ray's surface echo is not
  // one (else best.range <= its surface range) and nothing nearer is; cast no farther than the detection so far.
  for (std::size_t i = base; i < end; ++i) {
    const double s = surface_[i];
    if (s < 0.0 || hits_[i].hit() || s >= best.range)
      continue;
    const double reach = std::min(reach_, best.range) - s;
    if (reach <= 1e-6)
      continue;
    mirrored_.push_back(reflectedRay(rays_[i], rays_[i].origin.cast<double>(), s, surface_z, reach));
    mirror_of_.push_back(i);
  }
}

void M3Sensor::describeSample(SampleWriter& out) const {
  out.array("ranges", "m", last_.ranges);
  out.array("intensities", "-", last_.intensities);
  std::vector<double> angles(beams());
  for (std::size_t k = 0; k < angles.size(); ++k)
    angles[k] = beamAngle(k);
  out.array("beam_angles", "rad", angles);
}

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

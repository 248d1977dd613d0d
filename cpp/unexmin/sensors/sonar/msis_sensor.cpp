#include <unexmin/sensors/sonar/msis_sensor.h>

#include <unexmin/sensors/sensor_params.h>
#include <unexmin/sensors/sonar/equation_params.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace unexmin {
namespace sensors {
namespace sonar {
namespace {

constexpr double kDeg = M_PI / 180.0;

/// Defaults of the parameters a preset sets.
struct Preset {
  double range_max, nbins, gain;
};

Preset preset(const std::string& name) {
  if (name == "thesis_tank")
    return {3.0, 400.0, 0.2};  // thesis 6.1.1: 3 m, 400 bins, gain "Low"
  return {20.0, 200.0, 0.5};   // none: a medium range, medium gain
}

double wrap(double a) {
  a = std::remainder(a, 2.0 * M_PI);  // [-pi, pi]
  return a <= -M_PI ? a + 2.0 * M_PI : a;
}

}  // namespace

const std::map<std::string, double>& MsisSensor::gainSettings() {
  // The Micron's low / medium / high gain as shares of gain_span: low = the thesis's 0.2 (6.1.1); medium and
  // high are assumed.
  static const std::map<std::string, double> settings = {{"low", 0.2}, {"medium", 0.5}, {"high", 0.8}};
  return settings;
}

const std::vector<double>& MsisSensor::mechanicalSteps() {
  static const std::vector<double> steps = {0.225, 0.45, 0.9, 1.8, 3.6};
  return steps;
}

MsisSensor::MsisSensor(const sim::SensorSpec& spec, const sensors::SensorSetup& setup) : Sensor(spec, setup) {
  sensors::SensorParams p(spec, setup.robot);
  const std::string preset_name = p.text("preset", "none", {"none", "thesis_tank"});
  const Preset pre = preset(preset_name);
  const bool noise = p.text("noise", "gaussian", {"gaussian", "none"}) == "gaussian";

  EchoParams e;
  e.range_min = p.number("range_min", 0.3, 0.0, 1000.0, "m");
  e.range_max = p.number("range_max", pre.range_max, 0.0, 1000.0, "m");
  if (!(e.range_max > e.range_min))
    p.fail("range_max", formatNumber(e.range_max), "more than range_min");
  const double nbins = p.number("nbins", pre.nbins, 1.0, 10000.0, "bins");
  if (nbins != std::floor(nbins))
    p.fail("nbins", formatNumber(nbins), "a whole number of bins");
  e.nbins = static_cast<int>(nbins);
  // The gain: a number in [0, 1] or the Micron's named settings.
  const std::string gain_word = p.text("gain", "");
  const auto named = gainSettings().find(gain_word);
  e.gain = named != gainSettings().end()
               ? named->second
               : p.number("gain", pre.gain, 0.0, 1.0, "(0 low .. 1 high, or low/medium/high)");
  readEquationParams(p, e, 200.0);

  const double step_deg = p.number("step", 0.9 * kDeg, 0.0, M_PI, "rad") / kDeg;
  const auto& steps = mechanicalSteps();
  const auto match = std::find_if(steps.begin(), steps.end(), [&](double s) { return std::abs(s - step_deg) < 1e-6; });
  if (match == steps.end()) {
    p.fail("step", formatNumber(step_deg) + " deg",
           "one of the Micron DST's mechanical steps 0.225, 0.45, 0.9, 1.8, 3.6 deg (in rad)");
  }
  step_ = *match * kDeg;
  left_ = p.number("sector_left", -M_PI, -2.0 * M_PI, 2.0 * M_PI, "rad");
  right_ = p.number("sector_right", M_PI, -2.0 * M_PI, 2.0 * M_PI, "rad");
  continuous_ = p.flag("continuous", true);
  if (!continuous_ && std::abs(right_ - left_) < step_ - 1e-9)
    p.fail("sector_right", formatNumber(right_),
           "at least one step (" + formatNumber(step_) + " rad) away from sector_left for a sector scan");

  const double bw_h = p.number("beam_width_h", 3.0 * kDeg, 0.0, M_PI, "rad");
  const double bw_v = p.number("beam_width_v", 35.0 * kDeg, 0.0, M_PI, "rad");
  const double hpr = p.number("hpr", 5.0, 1.0, 1000.0, "rays");
  const double vpr = p.number("vpr", 70.0, 1.0, 1000.0, "rays");
  if (hpr != std::floor(hpr))
    p.fail("hpr", formatNumber(hpr), "a whole number of rays");
  if (vpr != std::floor(vpr))
    p.fail("vpr", formatNumber(vpr), "a whole number of rays");
  hpr_ = static_cast<int>(hpr);
  vpr_ = static_cast<int>(vpr);
  e.beam_solid_angle = bw_h * 2.0 * std::sin(bw_v / 2.0);  // the azimuth x elevation rectangle on the sphere
  echo_ = EchoModel(e);

  sound_speed_ = SoundSpeed::read(p);
  // One ping at a time: the echo from range_max must be back before the next ping.
  const double max_rate = sound_speed_.configured / (2.0 * e.range_max);
  if (rate() > max_rate * (1.0 + 1e-9)) {
    p.fail("rate", formatNumber(rate()),
           "at most sound_speed / (2 range_max) = " + formatNumber(max_rate) +
               " steps/s (the echo from range_max must return)");
  }

  range_noise_ = p.number("range_noise", 0.0, 0.0, 10.0, "m");
  salt_pepper_ = p.number("salt_pepper", 0.0, 0.0, 1.0, "(probability per bin)");
  salt_level_ = p.number("salt_level", 10.0, 0.0, 100.0, "dB above the noise level");
  speckle_ = p.flag("speckle", false);
  noise_floor_ = p.flag("noise_floor", false);
  noise_power_ = std::pow(10.0, p.number("noise_level", 117.0, 0.0, 300.0, "dB re 1 uPa") / 10.0);
  reflector_ = readSurfaceParams(p, e);
  shadow_ = p.flag("shadow", false);
  shadow_threshold_ = p.number("shadow_threshold", 0.6, 0.0, 1.0, "(intensity)");
  artifacts_ = p.flag("artifacts", false);
  artifacts_gap_ = p.number("artifacts_gap", 0.5, 0.0, 1000.0, "m");
  if (!noise) {
    range_noise_ = salt_pepper_ = 0.0;
    shadow_ = artifacts_ = speckle_ = noise_floor_ = false;
  }
  threshold_low_ = p.number("threshold_low", 0.05, 0.0, 1.0, "(intensity)");
  threshold_medium_ = p.number("threshold_medium", 0.25, 0.0, 1.0, "(intensity)");
  threshold_high_ = p.number("threshold_high", 0.6, 0.0, 1.0, "(intensity)");
  if (!(threshold_low_ <= threshold_medium_ && threshold_medium_ <= threshold_high_))
    p.fail("threshold_medium", formatNumber(threshold_medium_), "threshold_low <= threshold_medium <= threshold_high");

  // The head joint: given, or the joint that carries the sensor link.
  const sim::JointInfo& joint = p.movingJoint(setup.description);
  p.finish();
  joint_ = joint.name;
  axis_ = joint.axis.normalized();

  for (int h = 0; h < hpr_; ++h) {
    const double a = -bw_h / 2.0 + (h + 0.5) * bw_h / hpr_;
    for (int v = 0; v < vpr_; ++v) {
      const double el = -bw_v / 2.0 + (v + 0.5) * bw_v / vpr_;
      dirs_.emplace_back(std::cos(el) * std::cos(a), std::cos(el) * std::sin(a), std::sin(el));
    }
  }
  rays_.resize(dirs_.size());
  surface_.resize(dirs_.size());
  // The shadow's least code; per bin, the exponential draw u below which the noise floor alone stays code 0.
  shadow_code_ = std::max(1, static_cast<int>(std::ceil(shadow_threshold_ * e.levels - 1e-9)));
  noise_visible_.resize(e.nbins);
  for (int b = 0; b < e.nbins; ++b)
    noise_visible_[b] = -std::expm1(-echo_.codePower(1, b) / noise_power_);  // P(noise E >= code-1 power) = 1 - that
  column_.resize(vpr_);
}

Eigen::Isometry3d MsisSensor::headPose(double a) const {
  return spec().pose * Eigen::AngleAxisd(a, axis_);
}

void MsisSensor::onReset() {
  angle_ = left_;
  dir_ = right_ >= left_ ? 1 : -1;
  last_ = MsisLine();
}

void MsisSensor::advance() {
  if (continuous_) {
    angle_ = wrap(angle_ + dir_ * step_);
    return;
  }
  const double limit = dir_ > 0 ? std::max(left_, right_) : std::min(left_, right_);
  double next = angle_ + dir_ * step_;
  if ((next - limit) * dir_ > 1e-12) {
    if (std::abs(angle_ - limit) <= 1e-12) {  // at the limit: turn back
      dir_ = -dir_;
      next = angle_ + dir_ * step_;
    } else {
      next = limit;  // the last step stops at the limit
    }
  }
  angle_ = next;
}

EchoLevel MsisSensor::level(float i) const {
  if (i >= threshold_high_)
    return EchoLevel::high;
  if (i >= threshold_medium_)
    return EchoLevel::medium;
  if (i >= threshold_low_)
    return EchoLevel::low;
  return EchoLevel::none;
}

void MsisSensor::sample(const sensors::SensorContext& ctx) {
  Ping ping;
  aim(ctx, ping);
  castRays(ctx, rays_, hits_);
  castReflections(ctx, ping);
  depositEchoes(ping);
  shadowBins(ping);
  addReceiverNoise();
  writeLine(ctx, ping);
  advance();
}

void MsisSensor::aim(const sensors::SensorContext& ctx, Ping& ping) {
  const Eigen::Isometry3d head = ctx.state.pose * headPose(angle_);
  const Eigen::Matrix3d R = head.linear();
  const EchoParams& e = echo_.params();
  ping.surface_z = ctx.world.water().surface_z;
  ping.origin = head.translation();
  // ranges as the sonar times them: the path times sound_speed / c_water; in faster water it hears range_max from
  // farther away
  ping.scale = sound_speed_.rangeFactor(ctx.world, ping.origin);
  ping.reach = e.range_max / std::min(1.0, ping.scale);
  const bool submerged = ping.origin.z() < ping.surface_z;
  for (std::size_t i = 0; i < dirs_.size(); ++i) {
    const Eigen::Vector3d d = (R * dirs_[i]).normalized();
    rays_[i].origin = ping.origin.cast<float>();
    rays_[i].direction = d.cast<float>();
    rays_[i].max_range = static_cast<float>(ping.reach);
    // A ray that reaches the free surface within range stops there (the surface echo, and its reflection).
    surface_[i] = -1.0;
    if (reflector_.multipath && submerged && d.z() > 1e-9) {
      const double s = (ping.surface_z - ping.origin.z()) / d.z();
      if (s < ping.reach) {
        surface_[i] = s;
        rays_[i].max_range = static_cast<float>(s);
      }
    }
  }
}

void MsisSensor::castReflections(const sensors::SensorContext& ctx, const Ping& ping) {
  // The reflected rays, only for the rays that reached the surface: mirrored about it, for the rest of the range.
  mirrored_.clear();
  mirror_of_.clear();
  for (std::size_t i = 0; i < rays_.size(); ++i) {
    if (surface_[i] < 0.0 || hits_[i].hit())
      continue;
    mirrored_.push_back(reflectedRay(rays_[i], ping.origin, surface_[i], ping.surface_z, ping.reach - surface_[i]));
    mirror_of_.push_back(i);
  }
  if (!mirrored_.empty())
    castRays(ctx, mirrored_, mirror_hits_);
  ghost_.assign(rays_.size(), -1);
  for (std::size_t k = 0; k < mirror_of_.size(); ++k)
    ghost_[mirror_of_[k]] = static_cast<long>(k);
}

void MsisSensor::depositEchoes(const Ping& ping) {
  energy_.assign(echo_.params().nbins, 0.0);
  const std::size_t n = rays_.size();
  const auto noisy = [&](double r) {
    return std::max(0.0, r + (range_noise_ > 0.0 ? range_noise_ * random().gauss() : 0.0));
  };
  for (int h = 0; h < hpr_; ++h) {
    for (int v = 0; v < vpr_; ++v) {
      const std::size_t i = static_cast<std::size_t>(h) * vpr_ + v;
      const raycast::Hit& hit = hits_[i];
      Echo& echo = column_[v];
      echo.range = -1.0;
      if (hit.hit()) {
        echo.range = noisy(hit.range);
        echo.cos_incidence = std::cos(static_cast<double>(hit.incidence));
        if (!artifacts_)
          echo_.deposit(echo, n, energy_, ping.scale);
        continue;
      }
      if (surface_[i] < 0.0)
        continue;
      // The surface's own backscatter at its incidence (the vertical is its normal)...
      echo_.deposit(Echo{noisy(surface_[i]), static_cast<double>(rays_[i].direction.z()), reflector_.surface_extra}, n,
                    energy_, ping.scale);
      // ...and the ghost: the echo of what the reflected ray meets, back the same way (two reflections).
      const long g = ghost_[i];
      if (g >= 0 && mirror_hits_[g].hit()) {
        const double cos_incidence = std::cos(static_cast<double>(mirror_hits_[g].incidence));
        echo_.deposit(Echo{noisy(surface_[i] + mirror_hits_[g].range), cos_incidence, reflector_.ghost_extra}, n,
                      energy_, ping.scale);
      }
    }
    if (artifacts_)
      echo_.spread(column_, n, artifacts_gap_, energy_, ping.scale);
  }
}

void MsisSensor::shadowBins(Ping& ping) {
  const int nbins = echo_.params().nbins;
  ping.shadowed.assign(nbins, 0);
  if (!shadow_)
    return;
  // No echo behind the first strong one (the noise stays).
  int b = 0;
  while (b < nbins && !(energy_[b] > 0.0 && energy_[b] >= echo_.codePower(shadow_code_, b)))
    ++b;
  for (++b; b < nbins; ++b) {
    energy_[b] = 0.0;
    ping.shadowed[b] = 1;
  }
}

void MsisSensor::addReceiverNoise() {
  // Speckle (Rayleigh amplitude: exponential power) on the echoes, the noise floor (Rayleigh), then the occasional
  // spike near the noise level (salt) or dropped bin (pepper). The same draws whatever the geometry; a logarithm
  // only where the draw can change the code (noise_visible_: below it the floor stays 0).
  const int nbins = echo_.params().nbins;
  for (int b = 0; b < nbins; ++b) {
    double& p = energy_[b];
    if (speckle_) {
      const double u = random().uniform();
      if (p > 0.0)
        p *= -std::log1p(-u);
    }
    if (noise_floor_) {
      const double u = random().uniform();
      if (p > 0.0 || u >= noise_visible_[b])
        p += noise_power_ * -std::log1p(-u);
    }
    if (salt_pepper_ > 0.0 && random().uniform() < salt_pepper_)
      p = random().uniform() < 0.5 ? noise_power_ * std::pow(10.0, salt_level_ * random().uniform() / 10.0) : 0.0;
  }
}

void MsisSensor::writeLine(const sensors::SensorContext& ctx, const Ping& ping) {
  const int nbins = echo_.params().nbins;
  MsisLine& out = last_;
  out.time = ctx.world.time();
  out.angle = angle_;
  echo_.finish(energy_, out.intensity);
  out.level.assign(nbins, EchoLevel::none);
  for (int b = 0; b < nbins; ++b) {
    out.level[b] = level(out.intensity[b]);
    if (ping.shadowed[b] && out.level[b] == EchoLevel::none)
      out.level[b] = EchoLevel::shadow;
  }
}

void MsisSensor::describeSample(SampleWriter& out) const {
  out.scalar("angle", "rad", last_.angle);
  out.array("intensity", "-", last_.intensity);
}

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

#include <unexmin/sensors/dvl_sensor.h>

#include <unexmin/sensors/noise_factory.h>
#include <unexmin/sensors/pressure_sensor.h>
#include <unexmin/sensors/sensor_params.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace unexmin {
namespace sensors {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
/// Largest accepted angle between a beam frame's +x and the beam the parameters give [rad] (0.1 deg).
constexpr double kBeamFrameTolerance = 0.1 * M_PI / 180.0;

}  // namespace

double soundSpeedMedwin(double temperature, double salinity, double depth) {
  const double t = temperature;
  return 1449.2 + 4.6 * t - 0.055 * t * t + 0.00029 * t * t * t + (1.34 - 0.010 * t) * (salinity - 35.0) +
         0.016 * depth;
}

DvlSensor::DvlSensor(const sim::SensorSpec& spec, const SensorSetup& setup) : Sensor(spec, setup) {
  SensorParams p(spec, setup.robot);
  const std::string family = p.text("noise", "gaussian", noiseFamilies());
  beam_angle_ = p.number("beam_angle", 25.0 * M_PI / 180.0, 1e-6, M_PI / 2.0, "rad", true);
  beam_azimuth_0_ = p.number("beam_azimuth_0", 0.0, -2.0 * M_PI, 2.0 * M_PI, "rad");
  beam_width_ = p.number("beam_width", 3.0 * M_PI / 180.0, 1e-6, M_PI / 2.0, "rad", true);
  altitude_min_ = p.number("altitude_min", 0.1, 0.0, 1e4, "m");
  altitude_max_ = p.number("altitude_max", 75.0, 0.0, 1e4, "m");
  if (!(altitude_max_ > altitude_min_))
    p.fail("altitude_max", formatNumber(altitude_max_), "more than altitude_min = " + formatNumber(altitude_min_));
  NoiseParams velocity, range, scale, temperature, pressure;
  velocity.white = p.number("beam_velocity_noise", 0.0, 0.0, 10.0, "m/s");
  scale.turn_on_bias = p.number("velocity_scale_error", 0.0, 0.0, 0.5, "(fraction)");
  range.white = p.number("range_noise", 0.0, 0.0, 100.0, "m");
  water_temperature_ = p.number("water_temperature", 20.0, -5.0, 100.0, "degC");
  salinity_ = p.number("salinity", 0.0, 0.0, 45.0, "PSU");
  temperature.white = p.number("temperature_noise", 0.0, 0.0, 100.0, "degC");
  pressure.white = p.number("pressure_noise", 0.0, 0.0, 1e7, "Pa");
  const std::vector<std::string> frames = p.words("beam_frames");
  p.finish();

  for (NoiseParams* n : {&velocity, &range, &scale, &temperature, &pressure})
    n->interval = interval();
  for (std::size_t i = 0; i < 4; ++i) {
    const double c = beamAzimuth(i);
    directions_[i] = Eigen::Vector3d(std::sin(beam_angle_) * std::cos(c), std::sin(beam_angle_) * std::sin(c),
                                     std::cos(beam_angle_));
    velocity_noise_[i] = createNoise(family, velocity);
    range_noise_[i] = createNoise(family, range);
  }
  scale_noise_ = createNoise(family, scale);
  scale_sigma_ = family == "none" ? 0.0 : scale.turn_on_bias;
  temperature_noise_ = createNoise(family, temperature);
  pressure_noise_ = createNoise(family, pressure);

  if (!frames.empty() && frames.size() != 4)
    p.fail("beam_frames", "'" + p.text("beam_frames", "") + "'", "4 link names (beams 0..3)");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    Eigen::Isometry3d pose;
    try {
      pose = setup.description.linkPose(frames[i]);
    } catch (const ConfigError& e) {
      p.fail("beam_frames", "'" + frames[i] + "'", "links of the robot (" + std::string(e.what()) + ")");
    }
    const Eigen::Vector3d x = spec.pose.linear().transpose() * pose.linear().col(0);
    const double angle = std::acos(std::clamp(x.dot(directions_[i]), -1.0, 1.0));
    if (angle > kBeamFrameTolerance) {
      p.fail("beam_frames",
             "'" + frames[i] + "' whose +x is " + formatNumber(angle * 180.0 / M_PI) + " deg away from beam " +
                 formatNumber(static_cast<double>(i)) + " of beam_angle/beam_azimuth_0 (tolerance 0.1 deg)",
             "frames along the beams");
    }
  }
  rays_.resize(4);
}

double DvlSensor::beamAzimuth(std::size_t i) const {
  return beam_azimuth_0_ + static_cast<double>(i) * M_PI / 2.0;
}

void DvlSensor::onReset() {
  for (std::size_t i = 0; i < 4; ++i) {
    velocity_noise_[i]->reset(random());
    range_noise_[i]->reset(random());
  }
  scale_noise_->reset(random());
  temperature_noise_->reset(random());
  pressure_noise_->reset(random());
  last_ = DvlSample();
}

void DvlSensor::sample(const SensorContext& ctx) {
  const sim::RobotState& s = ctx.state;
  const Eigen::Isometry3d dvl = s.pose * spec().pose;  // DVL frame in the world
  const Eigen::Matrix3d R = dvl.linear();
  const Eigen::Vector3d origin = dvl.translation();
  const double cos_a = std::cos(beam_angle_);
  const double surface_z = ctx.world.water().surface_z;
  // The sound speed it assumes (Medwin, from its thermistor's water temperature: the world's water column's there,
  // else its water_temperature; and its configured salinity) against the water's own: ranges and Doppler
  // velocities come out scaled by assumed / actual (sensor.h's apparentRangeFactor)
  const double depth = std::max(0.0, surface_z - origin.z());
  const auto& column = ctx.world.config().water_column;
  const double temperature = column ? column->at(origin, ctx.world.time()).temperature : water_temperature_;
  const double assumed = soundSpeedMedwin(temperature, salinity_, depth);
  const double k = apparentRangeFactor(ctx.world, origin, assumed);
  std::array<double, 4> to_surface;
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3d d = (R * directions_[i]).normalized();
    rays_[i].origin = origin.cast<float>();
    rays_[i].direction = d.cast<float>();
    // Sound stops at the free surface: a beam that reaches it before any bottom hears the surface, not a bottom.
    to_surface[i] = d.z() > 1e-9 ? (surface_z - origin.z()) / d.z() : kInf;
    rays_[i].max_range = static_cast<float>(std::clamp(to_surface[i], 0.0, altitude_max_ / cos_a / std::min(1.0, k)));
  }
  castRays(ctx, rays_, hits_);

  // Velocity of the DVL origin over the bottom, DVL frame.
  const Eigen::Vector3d r = origin - s.pose.translation();
  const Eigen::Vector3d v = R.transpose() * (s.linear_velocity + s.angular_velocity.cross(r));
  const double scale = 1.0 + scale_noise_->bias();

  DvlSample& out = last_;
  out.time = ctx.world.time();
  std::size_t n_valid = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    DvlBeam& b = out.beams[i];
    b.direction = directions_[i];
    b.velocity_std = velocity_noise_[i]->whiteStd();
    // Draw both noises on every beam, valid or not, so the stream does not depend on the geometry.
    const double hit_range = k * hits_[i].range;  // +inf on no hit
    const double range = range_noise_[i]->apply(hit_range, random());
    const double velocity = velocity_noise_[i]->apply(k * scale * directions_[i].dot(v), random());
    const double along_z = hit_range * cos_a;
    b.surface = !hits_[i].hit() && to_surface[i] <= altitude_max_ / cos_a;
    b.valid = hits_[i].hit() && along_z >= altitude_min_ && along_z <= altitude_max_;
    b.range = b.valid ? std::max(0.0, range) : kInf;
    b.velocity = b.valid ? velocity : kNaN;
    if (b.surface)
      b.velocity_std = kInf;  // the figure of merit: no bottom velocity from this beam
    n_valid += b.valid ? 1 : 0;
  }

  out.bottom_lock = n_valid >= 3;
  out.velocity_z1 = out.velocity_z2 = kNaN;
  if (out.bottom_lock) {
    Eigen::MatrixXd B(n_valid, 3);
    Eigen::VectorXd u(n_valid);
    double altitude = 0.0, sigma2 = 0.0;
    for (std::size_t i = 0, k = 0; i < 4; ++i) {
      if (!out.beams[i].valid)
        continue;
      B.row(k) = directions_[i].transpose();
      u[k] = out.beams[i].velocity;
      altitude += out.beams[i].range * cos_a;
      sigma2 = std::max(sigma2, out.beams[i].velocity_std * out.beams[i].velocity_std);
      ++k;
    }
    const Eigen::Matrix3d BtB_inv = (B.transpose() * B).inverse();
    out.velocity = BtB_inv * B.transpose() * u;
    out.covariance = sigma2 * BtB_inv;
    // The turn-on scale error (1 sigma), as a variance proportional to the squared speed.
    for (int j = 0; j < 3; ++j)
      out.covariance(j, j) += std::pow(scale_sigma_ * out.velocity[j], 2);
    out.altitude = altitude / static_cast<double>(n_valid);
    if (out.beams[0].valid && out.beams[2].valid)
      out.velocity_z1 = (out.beams[0].velocity + out.beams[2].velocity) / (2.0 * cos_a);
    if (out.beams[1].valid && out.beams[3].valid)
      out.velocity_z2 = (out.beams[1].velocity + out.beams[3].velocity) / (2.0 * cos_a);
  } else {
    out.velocity.setConstant(kNaN);
    out.covariance.setConstant(-1.0);
    out.altitude = kNaN;
  }

  out.sound_speed = assumed;
  out.temperature = temperature_noise_->apply(temperature, random());
  out.pressure = std::max(0.0, pressure_noise_->apply(hydrostaticPressure(ctx.world, origin), random()));
}

void DvlSensor::describeSample(SampleWriter& out) const {
  out.flag("bottom_lock", last_.bottom_lock);
  out.vector3("velocity", "m/s", last_.velocity);
  out.scalar("altitude", "m", last_.altitude);
  out.scalar("pressure", "Pa", last_.pressure);
  out.scalar("temperature", "degC", last_.temperature);
  out.scalar("sound_speed", "m/s", last_.sound_speed);
  std::vector<double> range, velocity;
  bool valid[4];
  for (std::size_t i = 0; i < last_.beams.size(); ++i) {
    range.push_back(last_.beams[i].range);
    velocity.push_back(last_.beams[i].velocity);
    valid[i] = last_.beams[i].valid;
  }
  out.array("beam_range", "m", range);
  out.array("beam_velocity", "m/s", velocity);
  out.flags("beam_valid", valid, last_.beams.size());
}

}  // namespace sensors
}  // namespace unexmin

#include <unexmin/sensors/imu_sensor.h>

#include <unexmin/geo/magnetics.h>
#include <unexmin/sensors/magnetic_field.h>
#include <unexmin/sensors/noise_factory.h>
#include <unexmin/sensors/pressure_sensor.h>
#include <unexmin/sensors/sensor_params.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace sensors {

ImuSensor::Channel ImuSensor::makeChannel(SensorParams& p, const std::string& family, const std::string& prefix,
                                          const std::string& unit, double rate) {
  NoiseParams n;
  n.white = p.number(prefix + "_noise_density", 0.0, 0.0, 1e6, unit + "/sqrt(Hz)") * std::sqrt(rate);
  n.bias_random_walk = p.number(prefix + "_bias_random_walk", 0.0, 0.0, 1e6, unit + "/sqrt(s)");
  n.turn_on_bias = p.number(prefix + "_turn_on_bias", 0.0, 0.0, 1e6, unit);
  n.interval = 1.0 / rate;
  return {createNoise(family, n), createNoise(family, n), createNoise(family, n)};
}

ImuSensor::ImuSensor(const sim::SensorSpec& spec, const SensorSetup& setup) : Sensor(spec, setup) {
  SensorParams p(spec, setup.robot);
  const std::string family = p.text("noise", "gaussian", noiseFamilies());
  gyro_ = makeChannel(p, family, "gyro", "rad/s", spec.rate);
  accel_ = makeChannel(p, family, "accel", "m/s^2", spec.rate);
  mag_ = makeChannel(p, family, "mag", "mG", spec.rate);
  gyro_range_ = p.number("gyro_range", 1e3, 1e-6, 1e6, "rad/s");
  accel_range_ = p.number("accel_range", 1e4, 1e-6, 1e6, "m/s^2");
  mag_range_ = p.number("mag_range", 1e5, 1e-6, 1e9, "mG");
  temperature_ = p.number("temperature", 20.0, -50.0, 150.0, "degC");
  water_temperature_ = p.number("water_temperature", 20.0, -5.0, 100.0, "degC");
  NoiseParams t;
  t.white = p.number("temperature_noise", 0.0, 0.0, 100.0, "degC");
  t.interval = interval();
  NoiseParams pr;
  pr.white = p.number("pressure_noise", 0.0, 0.0, 1e7, "Pa");
  pr.interval = interval();
  pressure_range_ = p.number("pressure_range", 1e8, 1.0, 1e9, "Pa");
  p.finish();
  temperature_noise_ = createNoise(family, t);
  pressure_temperature_noise_ = createNoise(family, t);
  pressure_noise_ = createNoise(family, pr);
}

void ImuSensor::onReset() {
  for (Channel* c : {&gyro_, &accel_, &mag_})
    for (auto& axis : *c)
      axis->reset(random());
  temperature_noise_->reset(random());
  pressure_noise_->reset(random());
  pressure_temperature_noise_->reset(random());
  have_previous_ = false;
  alpha_.setZero();
  last_ = ImuSample();
}

void ImuSensor::track(const SensorContext& ctx) {
  const Eigen::Vector3d& w = ctx.state.angular_velocity;
  alpha_ = have_previous_ ? Eigen::Vector3d((w - previous_w_) / ctx.world.dt()) : Eigen::Vector3d::Zero();
  previous_w_ = w;
  have_previous_ = true;
}

Eigen::Vector3d ImuSensor::corrupt(Channel& channel, const Eigen::Vector3d& truth, double range) {
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i)
    out[i] = std::clamp(channel[i]->apply(truth[i], random()), -range, range);
  return out;
}

void ImuSensor::sample(const SensorContext& ctx) {
  const sim::RobotState& s = ctx.state;
  const Eigen::Matrix3d R = s.pose.linear();
  const Eigen::Vector3d r = R * spec().pose.translation();  // IMU origin from the base origin, world axes
  const Eigen::Vector3d& w = s.angular_velocity;
  const Eigen::Vector3d a_point = s.linear_acceleration + alpha_.cross(r) + w.cross(w.cross(r));
  const Eigen::Vector3d g(0.0, 0.0, -ctx.world.water().gravity);
  const Eigen::Matrix3d to_imu = (R * spec().pose.linear()).transpose();  // world -> IMU frame

  last_.time = ctx.world.time();
  last_.specific_force = corrupt(accel_, to_imu * (a_point - g), accel_range_);
  last_.angular_velocity = corrupt(gyro_, to_imu * w, gyro_range_);
  // the world's total field and the robot's own at the IMU (sensors/magnetic_field.h), [nT] -> [mG]
  const Eigen::Vector3d field = magnetometerField(ctx, spec().pose) / geo::kNanoteslaPerMilligauss;
  last_.magnetic_field = corrupt(mag_, field, mag_range_);
  last_.temperature = temperature_noise_->apply(temperature_, random());
  const double p = hydrostaticPressure(ctx.world, s.pose.translation() + r);
  last_.pressure = std::clamp(pressure_noise_->apply(p, random()), 0.0, pressure_range_);
  last_.pressure_temperature = pressure_temperature_noise_->apply(water_temperature_, random());
  auto var = [](const std::unique_ptr<NoiseModel>& m) { return m->whiteStd() * m->whiteStd(); };
  last_.accel_variance = var(accel_[0]);
  last_.gyro_variance = var(gyro_[0]);
  last_.mag_variance = var(mag_[0]);
  last_.pressure_variance = var(pressure_noise_);
}

void ImuSensor::describeSample(SampleWriter& out) const {
  out.vector3("specific_force", "m/s^2", last_.specific_force);
  out.vector3("angular_velocity", "rad/s", last_.angular_velocity);
  out.vector3("magnetic_field", "mG", last_.magnetic_field);
  out.scalar("temperature", "degC", last_.temperature);
  out.scalar("pressure", "Pa", last_.pressure);
}

}  // namespace sensors
}  // namespace unexmin

#include <unexmin/sensors/pressure_sensor.h>

#include <unexmin/sensors/noise_factory.h>
#include <unexmin/sensors/sensor_params.h>

#include <algorithm>
#include <stdexcept>

namespace unexmin {
namespace sensors {

double hydrostaticPressure(const sim::World& world, const Eigen::Vector3d& point) {
  const sim::WorldConfig& config = world.config();
  if (config.water_column)
    return config.atmospheric_pressure + config.water_column->hydrostaticPressure(point, world.time());
  const sim::WaterState& w = world.water();
  return config.atmospheric_pressure + w.density * w.gravity * std::max(0.0, w.surface_z - point.z());
}

PressureSensor::PressureSensor(const sim::SensorSpec& spec, const SensorSetup& setup) : Sensor(spec, setup) {
  SensorParams p(spec, setup.robot);
  const std::string family = p.text("noise", "gaussian", noiseFamilies());
  NoiseParams n;
  n.white = p.number("pressure_noise", 0.0, 0.0, 1e7, "Pa");
  n.turn_on_bias = p.number("pressure_bias", 0.0, 0.0, 1e7, "Pa");
  n.interval = interval();
  range_ = p.number("pressure_range", 1e8, 1.0, 1e9, "Pa");
  p.finish();
  noise_ = createNoise(family, n);
}

void PressureSensor::onReset() {
  noise_->reset(random());
  last_ = PressureSample();
}

void PressureSensor::sample(const SensorContext& ctx) {
  const Eigen::Vector3d origin = ctx.state.pose * spec().pose.translation();
  const double truth = hydrostaticPressure(ctx.world, origin);
  last_.time = ctx.world.time();
  last_.pressure = std::clamp(noise_->apply(truth, random()), 0.0, range_);
  last_.variance = noise_->whiteStd() * noise_->whiteStd();
}

void PressureSensor::describeSample(SampleWriter& out) const {
  out.scalar("pressure", "Pa", last_.pressure);
}

}  // namespace sensors
}  // namespace unexmin

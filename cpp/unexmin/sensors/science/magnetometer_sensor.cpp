#include <unexmin/sensors/science/magnetometer_sensor.h>

#include <unexmin/sensors/magnetic_field.h>
#include <unexmin/sensors/noise_factory.h>
#include <unexmin/sensors/sensor_params.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace sensors {
namespace science {

MagnetometerSensor::MagnetometerSensor(const sim::SensorSpec& spec, const SensorSetup& setup) : Sensor(spec, setup) {
  SensorParams p(spec, setup.robot);
  if (!(spec.rate >= 1.0 && spec.rate <= 1000.0))
    p.fail("rate", formatNumber(spec.rate), "[1, 1000] Hz");
  const std::string family = p.text("noise", "gaussian", noiseFamilies());
  NoiseParams n;
  n.white = p.number("field_noise", 0.1, 0.0, 1e4, "nT");
  n.turn_on_bias = p.number("field_bias", 5.0, 0.0, 1e5, "nT");
  n.interval = interval();
  resolution_ = p.number("resolution", 0.01, 0.0, 1e3, "nT");
  range_ = p.number("field_range", 1e5, 1e3, 1e7, "nT");
  p.finish();
  for (auto& axis : noise_)
    axis = createNoise(family, n);
}

void MagnetometerSensor::onReset() {
  for (auto& axis : noise_)
    axis->reset(random());
  last_ = MagnetometerSample();
}

void MagnetometerSensor::sample(const SensorContext& ctx) {
  const Eigen::Vector3d truth = magnetometerField(ctx, spec().pose);
  last_.time = ctx.world.time();
  for (int i = 0; i < 3; ++i) {
    double b = std::clamp(noise_[i]->apply(truth[i], random()), -range_, range_);
    if (resolution_ > 0.0)
      b = resolution_ * std::round(b / resolution_);
    last_.field[i] = b;
  }
  last_.variance = noise_[0]->whiteStd() * noise_[0]->whiteStd() + resolution_ * resolution_ / 12.0;
}

void MagnetometerSensor::describeSample(SampleWriter& out) const {
  out.vector3("magnetic_field", "nT", last_.field);
  out.scalar("total_field", "nT", last_.field.norm());
}

}  // namespace science
}  // namespace sensors
}  // namespace unexmin

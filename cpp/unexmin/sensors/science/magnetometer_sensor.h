// Three-axis fluxgate magnetometer (docs/magnetometer.md). Type name "magnetometer". Reads the world's total field
// at its origin (the Earth's field of the world file and the geology's anomalies, geo/magnetics.h) through the
// robot's own field (<magnetic> of the description: hard and soft iron, the thrusters' currents), in the sensor
// frame (sensors/magnetic_field.h), then per axis: + turn-on bias + white noise, clamped to the full scale and
// rounded to the resolution.
//
// Parameters (<param name=... value=.../>, all optional):
//   noise        gaussian | none                                            (gaussian)
//   field_noise  white noise, 1 sigma per sample and axis [nT] in [0, 1e4]  (0.1, assumed)
//   field_bias   turn-on bias, 1 sigma per axis [nT] in [0, 1e5]            (5, assumed)
//   resolution   quantisation step [nT] in [0, 1e3]; 0: none                (0.01, assumed)
//   field_range  full scale per axis [nT] in [1e3, 1e7]                     (1e5, assumed)
// The rate (the <sensor> rate) must be in [1, 1000] Hz (and, as for every sensor, at most the physics rate).
#pragma once

#include <unexmin/sensors/noise_model.h>
#include <unexmin/sensors/sensor.h>

#include <array>
#include <memory>

namespace unexmin {
namespace sensors {
namespace science {

struct MagnetometerSample {
  double time = 0.0;               ///< [s]
  Eigen::Vector3d field{0, 0, 0};  ///< sensor frame [nT]
  double variance = 0.0;           ///< of the white noise per axis [nT^2]
};

class MagnetometerSensor : public Sensor {
public:
  /// Throws ConfigError naming the robot, the sensor, the parameter, its value and its range.
  MagnetometerSensor(const sim::SensorSpec& spec, const SensorSetup& setup);

  const MagnetometerSample& last() const { return last_; }
  double resolution() const { return resolution_; }  ///< [nT]
  double range() const { return range_; }            ///< [nT]

protected:
  void onReset() override;
  void sample(const SensorContext& ctx) override;
  void describeSample(SampleWriter& out) const override;

private:
  std::array<std::unique_ptr<NoiseModel>, 3> noise_;
  double resolution_ = 0.01, range_ = 1e5;
  MagnetometerSample last_;
};

}  // namespace science
}  // namespace sensors
}  // namespace unexmin

// Absolute pressure at the sensor link's origin: atmospheric + the weight of the water above it (rho g depth below
// the world's free surface in water of one density; the water column's density integrated from the surface down
// in a world with one), atmospheric above the surface, with noise and a full-scale clamp. Type name "pressure".
//
// Parameters (<param name=... value=.../>, all optional; defaults give an ideal sensor):
//   noise           gaussian | none                    (gaussian)
//   pressure_noise  white noise, 1 sigma per sample [Pa] >= 0          (0)
//   pressure_bias   turn-on bias, 1 sigma [Pa] >= 0                    (0)
//   pressure_range  full scale [Pa] > 0; readings are clamped to [0, range]   (1e8)
#pragma once

#include <unexmin/sensors/noise_model.h>
#include <unexmin/sensors/sensor.h>

#include <memory>

namespace unexmin {
namespace sensors {

/// True absolute pressure at `point` (world frame [m]) now [Pa]: p_atm + g times the density integrated along the
/// vertical from the free surface down to the point (water::WaterColumn::hydrostaticPressure, at the point's x, y and
/// the world's time); in a world without a water column p_atm + rho g max(0, surface_z - z) with the world's one
/// density. Every reader of the pressure (pressure, imu, dvl, water_probe) calls this one function.
double hydrostaticPressure(const sim::World& world, const Eigen::Vector3d& point);

struct PressureSample {
  double time = 0.0;      ///< [s]
  double pressure = 0.0;  ///< absolute [Pa]
  double variance = 0.0;  ///< of the white noise [Pa^2]
};

class PressureSensor : public Sensor {
public:
  /// Throws ConfigError naming the sensor and the parameter.
  PressureSensor(const sim::SensorSpec& spec, const SensorSetup& setup);

  const PressureSample& last() const { return last_; }

protected:
  void onReset() override;
  void sample(const SensorContext& ctx) override;
  void describeSample(SampleWriter& out) const override;

private:
  std::unique_ptr<NoiseModel> noise_;
  double range_ = 1e8;  ///< [Pa]
  PressureSample last_;
};

}  // namespace sensors
}  // namespace unexmin

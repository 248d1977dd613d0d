// Absolute pressure at the sensor link's origin: atmospheric + rho g depth below the world's free
// surface (atmospheric above it), with noise and a full-scale clamp. Type name "pressure".
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

/// True absolute pressure at world height z [Pa]: p_atm + rho g max(0, surface_z - z).
double hydrostaticPressure(const sim::World& world, double z);

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

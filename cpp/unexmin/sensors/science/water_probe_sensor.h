// Water-quality probe (a multiparameter sonde of the kind UX-1Neo logged at 1 Hz: temperature, electrical
// conductivity, pH, redox, dissolved oxygen, pressure). Type name "water_probe". docs/water_probe.md.
//
// At its intake, the sensor link's origin, the probe reads the world's water (water::WaterColumn::at at the intake
// and the world's time; a world without a water column: the defaults of water::WaterRow, fresh water of 10 degC,
// salinity and conductivity 0, pH 7, redox 200 mV, oxygen 10 mg/L) and the absolute pressure there
// (sensors::hydrostaticPressure). Each of its six channels (temperature, conductivity, ph, redox, oxygen, pressure)
// is an electrode with a first-order lag y' = (x - y) / tau, integrated every physics step by its exact
// discretisation y += (x - y) (1 - exp(-dt / tau)) and settled to the water at the intake at the first step after a
// reset; each sample adds white noise and an offset random walk and rounds to the channel's resolution. The
// conductivity compensated to 25 degC is computed from the probe's own readings, EC25 = EC / (1 + alpha (T - 25)),
// and rounded to the conductivity's resolution. Noise: 2 draws per channel per sample, 1 per channel at reset.
//
// Parameters (optional; <c> is temperature [degC], conductivity [uS/cm], ph [pH], redox [mV], oxygen [mg/L] or
// pressure [Pa]; defaults in brackets):
//   noise             gaussian | none                                                       (gaussian)
//   <c>_tau           lag time constant [s] in [0, 3600]; 0: no lag    (T 1, EC 1, pH 5, redox 10, DO 8, p 0.05)
//   <c>_noise         white noise, 1 sigma per sample [u] >= 0                              (0)
//   <c>_drift         offset random walk [u/sqrt(s)] >= 0                                   (0)
//   <c>_resolution    quantisation step of the reading [u] >= 0; 0: none                    (0)
//   alpha             EC temperature-compensation coefficient [1/degC] in [0, 0.03]         (0.02)
#pragma once

#include <unexmin/sensors/science/probe_channel.h>
#include <unexmin/sensors/sensor.h>

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace unexmin {
namespace sensors {
namespace science {

/// One sample of the probe: the readings at its intake and the variance of each about the electrode's state
/// (white noise + quantisation, noise^2 + resolution^2 / 12).
struct WaterProbeSample {
  double time = 0.0;             ///< [s]
  double temperature = 0.0;      ///< [degC]
  double conductivity = 0.0;     ///< in situ [uS/cm]
  double conductivity_25 = 0.0;  ///< compensated to 25 degC [uS/cm]
  double ph = 0.0;               ///< [pH]
  double redox = 0.0;            ///< redox potential (ORP) [mV]
  double oxygen = 0.0;           ///< dissolved oxygen [mg/L]
  double pressure = 0.0;         ///< absolute [Pa]
  double temperature_variance = 0.0, conductivity_variance = 0.0, conductivity_25_variance = 0.0, ph_variance = 0.0,
         redox_variance = 0.0, oxygen_variance = 0.0, pressure_variance = 0.0;  ///< [u^2]
};

class WaterProbeSensor : public Sensor {
public:
  /// The lagged channels, in the order of `channels()`.
  enum Channel { kTemperature, kConductivity, kPh, kRedox, kOxygen, kPressure, kChannelCount };

  /// Throws ConfigError naming the robot, the sensor, the parameter, its value and its range.
  WaterProbeSensor(const sim::SensorSpec& spec, const SensorSetup& setup);

  const WaterProbeSample& last() const { return last_; }
  double alpha() const { return alpha_; }  ///< [1/degC]
  const ProbeChannel& channel(Channel c) const { return channels_[c]; }
  /// The channels' parameter prefixes and units, in Channel order ("temperature" "degC", ...).
  static const std::array<std::pair<const char*, const char*>, kChannelCount>& channels();
  /// The conductivity compensated to 25 degC [uS/cm] of a reading `conductivity` [uS/cm] at `temperature` [degC].
  static double compensated(double conductivity, double temperature, double alpha) {
    return conductivity / (1.0 + alpha * (temperature - 25.0));
  }

protected:
  void onReset() override;
  void track(const SensorContext& ctx) override;
  void sample(const SensorContext& ctx) override;
  void describeSample(SampleWriter& out) const override;

private:
  /// The true values of the channels at the intake now, in Channel order.
  std::array<double, kChannelCount> water(const SensorContext& ctx) const;

  std::vector<ProbeChannel> channels_;  ///< in Channel order
  double alpha_ = 0.02;
  double resolution_25_ = 0.0;  ///< [uS/cm] the conductivity's
  bool settled_ = false;
  WaterProbeSample last_;
};

}  // namespace science
}  // namespace sensors
}  // namespace unexmin

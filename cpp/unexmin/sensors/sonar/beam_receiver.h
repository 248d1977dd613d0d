// The receiver of one sonar beam (docs/sonars.md "Receiver"): the echoes of the beam's rays, each spread over the
// ranges of its footprint (beam_fan.h), summed per range bin as echo power by the sonar equation of the echo
// model (echo_model.h), then the receiver noise and the 8-bit output:
//   speckle      each bin's echo power x an exponential draw of mean 1 (Rayleigh amplitude)
//   noise_floor  + 10^(noise_level / 10) uPa^2 x an exponential draw (Rayleigh noise) at the receiver input
//   output       L_i = 10 log10(P_i) + G + TVG(r_i), code q_i = round((L_i - display_min) / display_span 255)
//                clamped to 0 .. 255 (EchoModel::code)
// Randomness from a counter-based stream (counter_random.h), one per beam and ping: draw i belongs to bin i (with an
// echo, its two 24-bit halves are the speckle's and the noise's uniform draws; without, its high 24 bits are the
// noise's), and the noise alone is drawn bin by bin only where it shows often; elsewhere at geometric gaps, from the
// draws after the bins' (receive()). Knows no ROS.
#pragma once

#include <unexmin/sensors/counter_random.h>
#include <unexmin/sensors/sensor.h>
#include <unexmin/sensors/sensor_params.h>
#include <unexmin/sensors/sonar/echo_model.h>
#include <unexmin/sensors/sonar/equation_params.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace unexmin {
namespace sensors {
namespace sonar {

/// The receiver's noise models.
struct ReceiverNoise {
  bool speckle = true;        ///< exponential factor on each bin's echo power
  bool noise_floor = true;    ///< Rayleigh noise at the receiver input
  double noise_level = 85.0;  ///< noise power per bin [dB re 1 uPa]
};

/// The defaults of a sonar family's receiver parameters.
struct ReceiverDefaults {
  double range_max = 30.0;      ///< [m]
  double nbins = 500.0;         ///< [-]
  double source_level = 210.0;  ///< [dB re 1 uPa at 1 m]
  double noise_level = 85.0;    ///< [dB re 1 uPa]
};

/// A whole-number parameter in [lo, hi]; fails naming it otherwise.
int wholeNumber(SensorParams& p, const std::string& key, double fallback, double lo, double hi);

class BeamReceiver {
public:
  /// Reads range_min (0.1 m), range_max, nbins, gain (0.5), the sonar equation's parameters (equation_params.h),
  /// noise (gaussian|none), speckle (true), noise_floor (true), noise_level and sound_speed (1500 m/s, the speed it
  /// turns echo times into ranges with), and checks that a ping at `rate` [Hz] hears range_max (rate <= sound_speed /
  /// (2 range_max)). `beam_solid_angle` [sr]: the
  /// beam's (BeamFan::solidAngle()).
  static BeamReceiver read(SensorParams& p, const ReceiverDefaults& defaults, double rate, double beam_solid_angle);

  /// `params.levels` is set to 255 (8-bit codes). Throws ParameterError for a bad echo parameter.
  BeamReceiver(EchoParams params, const ReceiverNoise& noise);

  const EchoModel& echo() const { return echo_; }
  const ReceiverNoise& noise() const { return noise_; }
  /// The speed it turns echo times into ranges with [m/s] (read(): the parameter sound_speed; else 1500).
  const SoundSpeed& soundSpeed() const { return sound_speed_; }
  /// Adds the power of `e` (one of `rays` rays of the beam; its range r is the path, which sets the power) spread
  /// evenly over the ranges the sonar times, [r - extent/2, r + extent/2] x scale [m] (scale: the configured over the
  /// water's sound speed, sensors::apparentRangeFactor), to `energy` (nbins) [uPa^2]; what falls outside the range
  /// window is lost.
  void add(const Echo& e, double extent, std::size_t rays, double scale, std::vector<double>& energy) const;
  /// Speckle and noise floor on the echo power `energy` (nbins) [uPa^2], drawn from `random` (the beam's stream of
  /// this ping), then the codes: bin i to codes[i * stride]. `energy` is left all zeros, ready for the next beam.
  void receive(std::vector<double>& energy, const CounterRandom& random, std::uint8_t* codes, std::size_t stride) const;

private:
  static constexpr std::size_t kBlock = 32;  ///< bins per block of the noise's candidates
  static constexpr double kDense = 0.25;     ///< above this block probability every bin of the block draws

  /// The 8-bit code of power `power` [uPa^2] > 0 in bin i.
  std::uint8_t code(double power, std::size_t i) const;

  EchoModel echo_;
  ReceiverNoise noise_;
  SoundSpeed sound_speed_;
  double noise_power_ = 0.0;            ///< 10^(noise_level / 10) [uPa^2]
  std::vector<float> visible_;          ///< per bin: the probability that the noise alone makes code >= 1
  std::vector<double> block_visible_;   ///< per block of kBlock bins: the largest visible_
  std::vector<double> block_log_miss_;  ///< per block: ln(1 - block_visible_)
  float codes_per_log2_ = 0.0f;         ///< codes per factor 2 of power: 10 log10(2) / step
  float log2_noise_power_ = 0.0f;       ///< log2 of noise_power_
  std::vector<float> offset_;           ///< per bin: (G + TVG(r_i) - display_min) / step, in codes
};

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

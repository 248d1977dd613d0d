// Side-scan sonar, port and starboard (docs/sonars.md "Side-scan sonar"). Type name "side_scan". Frame: the
// sensor link; +x along-track (forward), +y to port, +z up.
// Each ping (the sensor's rate, at most sound_speed / (2 range_max)):
//   - one beam per side, its axis across-track and `tilt` below the horizontal (port (0, cos t, -sin t), starboard
//     (0, -cos t, -sin t)), `beam_width` wide along-track and `fov_v` across-track: `rays` rays across fov_v
//     (BeamFan), from the steepest at depression tilt + fov_v/2 to the shallowest at tilt - fov_v/2, cast from the
//     link origin up to range_max; they stop at the free surface and at the first surface they meet (shadows);
//   - each side's echoes (sonar equation, spread over their footprints) become one line of nbins 8-bit codes by slant
//     range as the sonar times it, the path x sound_speed / c_water (c_water the world's water column's sound speed
//     at the sonar, docs/worlds.md "Water column"; 1 without a column; the rays cast up to range_max / min(1, that
//     factor)) (BeamReceiver: speckle, noise floor, gain, TVG); bin 0 the nearest. The water column before the first
//     bottom return carries only noise: the nadir gap, at the slant range altitude / sin(tilt + fov_v/2) of the
//     steepest ray over a flat floor (the altitude itself for a fan that reaches the vertical);
//   - the waterfall (waterfall.h) keeps the latest waterfall_lines pings.
// Pings are built only while they are wanted (setDemand); a ping's speckle and noise come from one draw of the
// sensor's seeded stream per ping, built or not, so the lines do not depend on which pings were built.
// Parameters (defaults in brackets): fov_v [rad] (60 deg), beam_width [rad] (0.5 deg), tilt [rad] (30 deg), rays
// (256), range_min [m] (0.1), range_max [m] (50), nbins (1000), gain (0.5), noise gaussian|none (gaussian), speckle
// (true), noise_floor (true), noise_level [dB re 1 uPa] (75), sound_speed [m/s] (1500), waterfall_lines (400), and
// the sonar equation's (equation_params.h) with source_level 215 dB re 1 uPa at 1 m. Knows no ROS.
#pragma once

#include <unexmin/sensors/sensor.h>
#include <unexmin/sensors/sonar/beam_fan.h>
#include <unexmin/sensors/sonar/beam_receiver.h>
#include <unexmin/sensors/sonar/beam_set.h>
#include <unexmin/sensors/sonar/waterfall.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace unexmin {
namespace sensors {
namespace sonar {

/// One ping of both sides.
struct SideScanPing {
  double time = -1.0;                   ///< ping time [s]
  std::vector<std::uint8_t> port;       ///< nbins codes 0 .. 255, bin 0 the nearest
  std::vector<std::uint8_t> starboard;  ///< likewise
  bool built = false;                   ///< false: the ping was not wanted (setDemand), the lines hold an older ping
};

class SideScanSensor : public Sensor {
public:
  /// Throws ConfigError naming the robot, the sensor and the parameter.
  SideScanSensor(const sim::SensorSpec& spec, const SensorSetup& setup);

  const SideScanPing& last() const { return last_; }
  /// The waterfall: a ping not built adds a row of zeros.
  const Waterfall& waterfall() const { return waterfall_; }
  /// Builds a ping (rays, echoes, receiver) only at samples where `wanted()` is true (e.g. one of its topics has a
  /// subscriber); null: always.
  void setDemand(std::function<bool()> wanted) { demand_ = std::move(wanted); }
  std::size_t bins() const { return static_cast<std::size_t>(beams_.receiver().echo().params().nbins); }
  double rangeMin() const { return beams_.receiver().echo().params().range_min; }          ///< [m]
  double rangeMax() const { return beams_.receiver().echo().params().range_max; }          ///< [m]
  double rangeResolution() const { return beams_.receiver().echo().binWidth(); }           ///< bin width [m]
  double binCenter(std::size_t i) const { return beams_.receiver().echo().binCenter(i); }  ///< [m]
  double tilt() const { return tilt_; }                                                    ///< [rad]
  const BeamReceiver& receiver() const { return beams_.receiver(); }
  /// The fans: 0 port, 1 starboard.
  const BeamFan& fan(std::size_t side) const { return beams_.fan(side); }

protected:
  void onReset() override;
  void sample(const SensorContext& ctx) override;
  void describeSample(SampleWriter& out) const override;

private:
  double tilt_ = 0.0;
  SideScanPing last_;
  Waterfall waterfall_{1, 1};
  BeamSet beams_;
  std::vector<raycast::Hit> hits_;
  std::function<bool()> demand_;
};

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

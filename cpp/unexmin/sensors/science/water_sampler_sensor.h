// A water sampler: a rack of bottles that each take `bottle_volume` of water through one intake (the sensor link's
// origin) over `fill_time`, fired by a caller (Sensor::fire: unexmin.core's Robot.fire, the service
// /<robot>/sampler/fire) or by triggers in the description (depths, times, a jump of one water channel). Type name
// "water_sampler"; docs/water_sampler.md.
//
// The lab result of a bottle is the TRUE water of the world's water column at the intake, averaged over the fill
// (every physics step, track()), with the mean intake position and the start and end times: what the bottle holds,
// not what a probe reads. The water taken is carried: carriedMass() grows by rho V linearly over the fill (rho the
// density of the water taken), and the sensor suite adds it to the robot's mass at the sensor's mount. The
// triggers read the same true water at the intake, as the sampler's own in-line cell would, at `rate`.
//
// Parameters (<param name=... value=.../>, all optional):
//   bottles           number of bottles, an integer in [1, 100]                              (4, assumed)
//   bottle_volume     water per bottle [L] in (0, 20]                                         (0.5, assumed)
//   fill_time         time to fill one bottle [s] in [physics step, 600]                      (2, MBARI Gulper)
//   depth_triggers    depths [m below the free surface], each in [0, 11000]: each fires one bottle at the first
//                     check at or below it                                                   (none)
//   time_triggers     sim times [s], each in [0, 1e7]: each fires one bottle at the first check at or after it
//                                                                                            (none)
//   trigger_channel   none | temperature | conductivity | ph | redox | oxygen                 (none)
//   trigger_jump      > 0, in the channel's unit (degC, uS/cm, pH, mV, mg/L): a bottle fires when the channel
//                     differs from its value at the start of the latest fill (at the first check before any) by
//                     more than this; required with a channel, refused without one
#pragma once

#include <unexmin/sensors/sensor.h>

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace unexmin {
namespace sensors {
namespace science {

/// What fired a bottle.
enum class SampleTrigger : std::uint8_t { manual = 0, depth = 1, time = 2, channel = 3 };
/// "manual", "depth", "time", "channel".
const char* triggerName(SampleTrigger t);

/// One filled bottle: the true water at the intake averaged over its fill (each physics step weighted by the
/// fraction of the bottle it filled). Channels are NaN in a world without a water column.
struct BottleResult {
  std::uint32_t bottle = 0;  ///< index of the bottle, 0-based, in the order they fill
  SampleTrigger trigger = SampleTrigger::manual;
  double start_time = 0.0;            ///< [s] sim time at which the fill began
  double end_time = 0.0;              ///< [s] sim time of the step that completed it
  Eigen::Vector3d position{0, 0, 0};  ///< mean intake position over the fill, world frame [m]
  double depth = 0.0;                 ///< mean intake depth below the free surface [m]
  double temperature = 0.0;           ///< [degC]
  double salinity = 0.0;              ///< practical salinity [PSU]
  double conductivity = 0.0;          ///< in situ [uS/cm]
  double ph = 0.0;                    ///< [pH]
  double redox = 0.0;                 ///< [mV]
  double oxygen = 0.0;                ///< [mg/L]
  double turbidity = 0.0;             ///< [NTU]
  double density = 0.0;               ///< [kg/m^3]
  double volume = 0.0;                ///< [L]
  double mass = 0.0;                  ///< of the water taken [kg]
};

class WaterSamplerSensor : public Sensor {
public:
  /// Throws ConfigError naming the robot, the sensor, the parameter, its value and its range.
  WaterSamplerSensor(const sim::SensorSpec& spec, const SensorSetup& setup);

  /// Starts filling the next bottle now (between physics steps): its fill covers the next fill_time of sim time.
  /// Returns "filling bottle <i> of <n>". Throws ParameterError naming the robot and the sensor when every bottle is
  /// full or one is filling.
  std::string fire() override;
  /// The water in the bottles [kg]: every full bottle's and the part of the filling one taken so far.
  double carriedMass() const override { return carried_mass_; }

  int bottles() const { return bottles_; }
  int bottlesLeft() const;  ///< bottles neither full nor filling
  bool filling() const { return filling_; }
  double fillFraction() const { return filled_; }    ///< of the filling bottle, in [0, 1] (0 when none fills)
  double bottleVolume() const { return volume_l_; }  ///< [L]
  double fillTime() const { return fill_time_; }     ///< [s]
  /// Every filled bottle, in the order filled.
  const std::vector<BottleResult>& results() const { return results_; }

protected:
  void onReset() override;
  void track(const SensorContext& ctx) override;
  void sample(const SensorContext& ctx) override;
  void describeSample(SampleWriter& out) const override;

private:
  enum class Channel { none, temperature, conductivity, ph, redox, oxygen };
  struct Water {
    Eigen::Vector3d point{0, 0, 0};
    double depth = 0.0;
    double values[8] = {0, 0, 0, 0, 0, 0, 0, 0};  ///< T, S, C, pH, redox, O2, turbidity, density
  };
  Water waterAt(const SensorContext& ctx) const;
  double channelOf(const Water& w) const;
  void start(SampleTrigger trigger, double time);

  int bottles_ = 4;
  double volume_l_ = 0.5;   ///< [L]
  double fill_time_ = 2.0;  ///< [s]
  double dt_ = 0.002;       ///< physics step [s]
  std::vector<double> depth_triggers_, time_triggers_;
  Channel channel_ = Channel::none;
  double jump_ = 0.0;

  // state since reset
  std::vector<char> depth_fired_, time_fired_;
  double reference_ = 0.0;  ///< channel value at the start of the latest fill (or at the first check)
  bool have_reference_ = false;
  double time_ = 0.0;  ///< sim time of the latest step seen [s]
  bool filling_ = false;
  SampleTrigger trigger_ = SampleTrigger::manual;
  double start_time_ = 0.0;
  std::uint64_t fill_steps_ = 0;
  double filled_ = 0.0;  ///< fraction of the filling bottle
  Water first_;          ///< the water at the fill's first step
  double sums_[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  Eigen::Vector3d position_sum_{0, 0, 0};
  double depth_sum_ = 0.0;
  double full_mass_ = 0.0;      ///< of the full bottles [kg]
  double carried_mass_ = 0.0;   ///< [kg]
  double intake_depth_ = 0.0;   ///< at the latest check [m]
  double channel_value_ = 0.0;  ///< at the latest check
  std::vector<BottleResult> results_;
};

}  // namespace science
}  // namespace sensors
}  // namespace unexmin

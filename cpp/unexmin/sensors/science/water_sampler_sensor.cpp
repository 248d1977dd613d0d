#include <unexmin/sensors/science/water_sampler_sensor.h>

#include <unexmin/core/error.h>
#include <unexmin/sensors/sensor_params.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace unexmin {
namespace sensors {
namespace science {
namespace {

constexpr int kValues = 8;  // temperature, salinity, conductivity, pH, redox, oxygen, turbidity, density

/// Parameter `key` as a list of numbers, each in [lo, hi] [unit], in the order given (empty when absent).
std::vector<double> numberList(SensorParams& p, const sim::SensorSpec& spec, const std::string& key, double lo,
                               double hi, const std::string& unit) {
  const std::string expected =
      "numbers in [" + formatNumber(lo) + ", " + formatNumber(hi) + "] " + unit + ", separated by spaces";
  p.words(key);  // read: finish() accepts it
  if (spec.text.count(key))
    p.fail(key, "'" + spec.text.at(key) + "'", expected);
  const auto it = spec.params.find(key);
  if (it == spec.params.end())
    return {};
  for (const double v : it->second)
    if (!std::isfinite(v) || v < lo || v > hi)
      p.fail(key, formatNumber(v), expected);
  return it->second;
}

}  // namespace

const char* triggerName(SampleTrigger t) {
  switch (t) {
    case SampleTrigger::depth:
      return "depth";
    case SampleTrigger::time:
      return "time";
    case SampleTrigger::channel:
      return "channel";
    case SampleTrigger::manual:
      break;
  }
  return "manual";
}

WaterSamplerSensor::WaterSamplerSensor(const sim::SensorSpec& spec, const SensorSetup& setup)
    : Sensor(spec, setup), dt_(setup.physics_dt) {
  SensorParams p(spec, setup.robot);
  const double bottles = p.number("bottles", 4.0, 1.0, 100.0, "bottles");
  if (bottles != std::floor(bottles))
    p.fail("bottles", formatNumber(bottles), "a whole number of bottles in [1, 100]");
  bottles_ = static_cast<int>(bottles);
  volume_l_ = p.number("bottle_volume", 0.5, 0.0, 20.0, "L");
  if (!(volume_l_ > 0.0))
    p.fail("bottle_volume", formatNumber(volume_l_), "(0, 20] L");
  fill_time_ = p.number("fill_time", 2.0, setup.physics_dt, 600.0, "s");
  depth_triggers_ = numberList(p, spec, "depth_triggers", 0.0, 11000.0, "m");
  time_triggers_ = numberList(p, spec, "time_triggers", 0.0, 1e7, "s");
  const std::string channel =
      p.text("trigger_channel", "none", {"none", "temperature", "conductivity", "ph", "redox", "oxygen"});
  channel_ = channel == "temperature"    ? Channel::temperature
             : channel == "conductivity" ? Channel::conductivity
             : channel == "ph"           ? Channel::ph
             : channel == "redox"        ? Channel::redox
             : channel == "oxygen"       ? Channel::oxygen
                                         : Channel::none;
  const bool has_jump = spec.params.count("trigger_jump") != 0 || spec.text.count("trigger_jump") != 0;
  if (channel_ == Channel::none && has_jump)
    p.fail("trigger_jump", "(set)", "no jump without a trigger_channel (temperature, conductivity, ph, redox, oxygen)");
  if (channel_ != Channel::none) {
    if (!has_jump)
      p.fail("trigger_jump", "(unset)", "a jump > 0 in the unit of trigger_channel '" + channel + "'");
    jump_ = p.number("trigger_jump", 0.0, 0.0, 1e6, "(the channel's unit)");
    if (!(jump_ > 0.0))
      p.fail("trigger_jump", formatNumber(jump_), "(0, 1e6] in the unit of trigger_channel '" + channel + "'");
  }
  p.finish();
}

int WaterSamplerSensor::bottlesLeft() const {
  return bottles_ - static_cast<int>(results_.size()) - (filling_ ? 1 : 0);
}

void WaterSamplerSensor::onReset() {
  depth_fired_.assign(depth_triggers_.size(), 0);
  time_fired_.assign(time_triggers_.size(), 0);
  have_reference_ = false;
  reference_ = 0.0;
  time_ = 0.0;
  filling_ = false;
  filled_ = 0.0;
  fill_steps_ = 0;
  full_mass_ = 0.0;
  carried_mass_ = 0.0;
  intake_depth_ = 0.0;
  channel_value_ = std::numeric_limits<double>::quiet_NaN();
  results_.clear();
}

std::string WaterSamplerSensor::fire() {
  const std::string who = robotName() + "/" + name();
  if (filling_)
    throw ParameterError(who + ": bottle " + std::to_string(results_.size() + 1) + " of " + std::to_string(bottles_) +
                         " is filling until t = " + formatNumber(start_time_ + fill_time_) + " s: fire again after it");
  if (bottlesLeft() <= 0)
    throw ParameterError(who + ": all " + std::to_string(bottles_) + " bottles are full");
  start(SampleTrigger::manual, time_);
  return "filling bottle " + std::to_string(results_.size() + 1) + " of " + std::to_string(bottles_);
}

void WaterSamplerSensor::start(SampleTrigger trigger, double time) {
  filling_ = true;
  trigger_ = trigger;
  start_time_ = time;
  fill_steps_ = 0;
  filled_ = 0.0;
  std::fill(sums_, sums_ + kValues, 0.0);
  position_sum_.setZero();
  depth_sum_ = 0.0;
  if (channel_ != Channel::none && std::isfinite(channel_value_)) {
    reference_ = channel_value_;  // the channel at the start of this fill
    have_reference_ = true;
  }
}

WaterSamplerSensor::Water WaterSamplerSensor::waterAt(const SensorContext& ctx) const {
  Water w;
  w.point = ctx.state.pose * spec().pose.translation();
  const auto& column = ctx.world.config().water_column;
  if (column) {
    const water::WaterSample s = column->at(w.point, ctx.world.time());
    w.depth = s.depth;
    const double v[kValues] = {s.temperature, s.salinity, s.conductivity, s.ph,
                               s.redox,       s.oxygen,   s.turbidity,    s.density};
    std::copy(v, v + kValues, w.values);
  } else {  // uniform water of the world's density; its chemistry unknown
    w.depth = std::max(0.0, ctx.world.config().surface_z - w.point.z());
    std::fill(w.values, w.values + kValues, std::numeric_limits<double>::quiet_NaN());
    w.values[7] = ctx.world.config().water_density;
  }
  return w;
}

double WaterSamplerSensor::channelOf(const Water& w) const {
  switch (channel_) {
    case Channel::temperature:
      return w.values[0];
    case Channel::conductivity:
      return w.values[2];
    case Channel::ph:
      return w.values[3];
    case Channel::redox:
      return w.values[4];
    case Channel::oxygen:
      return w.values[5];
    case Channel::none:
      break;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

void WaterSamplerSensor::track(const SensorContext& ctx) {
  time_ = ctx.world.time();
  if (!filling_)
    return;
  // This step's share of the bottle: dt / fill_time, the last step only what is left.
  ++fill_steps_;
  const double now = std::min(1.0, static_cast<double>(fill_steps_) * dt_ / fill_time_);
  const double share = now - filled_;
  filled_ = now;
  const Water w = waterAt(ctx);
  if (fill_steps_ == 1)
    first_ = w;
  // Sums of share x (value - the fill's first value): the mean of uniform water is that value exactly.
  for (int i = 0; i < kValues; ++i)
    sums_[i] += share * (w.values[i] - first_.values[i]);
  position_sum_ += share * (w.point - first_.point);
  depth_sum_ += share * (w.depth - first_.depth);
  const double volume_m3 = 1e-3 * volume_l_;
  // The water taken so far: volume x sum of share x rho.
  carried_mass_ = full_mass_ + (first_.values[7] * filled_ + sums_[7]) * volume_m3;
  if (filled_ < 1.0 - 1e-12)
    return;
  BottleResult r;
  r.bottle = static_cast<std::uint32_t>(results_.size());
  r.trigger = trigger_;
  r.start_time = start_time_;
  r.end_time = time_;
  r.position = first_.point + position_sum_ / filled_;
  r.depth = first_.depth + depth_sum_ / filled_;
  double* out[kValues] = {&r.temperature, &r.salinity, &r.conductivity, &r.ph,
                          &r.redox,       &r.oxygen,   &r.turbidity,    &r.density};
  for (int i = 0; i < kValues; ++i)
    *out[i] = first_.values[i] + sums_[i] / filled_;
  r.volume = volume_l_;
  r.mass = r.density * volume_m3;
  results_.push_back(r);
  full_mass_ += r.mass;
  carried_mass_ = full_mass_;
  filling_ = false;
  filled_ = 0.0;
}

void WaterSamplerSensor::sample(const SensorContext& ctx) {
  const Water w = waterAt(ctx);
  const double t = ctx.world.time();
  intake_depth_ = w.depth;
  channel_value_ = channelOf(w);
  if (channel_ != Channel::none && !have_reference_ && std::isfinite(channel_value_)) {
    reference_ = channel_value_;  // the channel at the first check
    have_reference_ = true;
  }
  if (filling_ || bottlesLeft() <= 0)
    return;
  for (std::size_t i = 0; i < depth_triggers_.size(); ++i)
    if (!depth_fired_[i] && w.depth >= depth_triggers_[i]) {
      depth_fired_[i] = 1;
      start(SampleTrigger::depth, t);
      return;
    }
  for (std::size_t i = 0; i < time_triggers_.size(); ++i)
    if (!time_fired_[i] && t + 1e-9 >= time_triggers_[i]) {
      time_fired_[i] = 1;
      start(SampleTrigger::time, t);
      return;
    }
  if (channel_ != Channel::none && std::isfinite(channel_value_) && std::abs(channel_value_ - reference_) > jump_)
    start(SampleTrigger::channel, t);
}

void WaterSamplerSensor::describeSample(SampleWriter& out) const {
  out.count("bottles", static_cast<std::uint64_t>(bottles_));
  out.count("bottles_left", static_cast<std::uint64_t>(bottlesLeft()));
  out.flag("filling", filling_);
  out.scalar("fill_fraction", "-", filled_);
  out.scalar("carried_mass", "kg", carried_mass_);
  out.scalar("intake_depth", "m", intake_depth_);
  const std::size_t n = results_.size();
  std::vector<double> position;
  std::vector<std::uint8_t> trigger;
  for (const auto& r : results_) {
    position.insert(position.end(), {r.position.x(), r.position.y(), r.position.z()});
    trigger.push_back(static_cast<std::uint8_t>(r.trigger));
  }
  auto column = [&](double BottleResult::* field) {
    std::vector<double> v;
    for (const auto& r : results_)
      v.push_back(r.*field);
    return v;
  };
  out.array("result_trigger", "-", trigger, {n});
  out.array("result_start_time", "s", column(&BottleResult::start_time), {n});
  out.array("result_end_time", "s", column(&BottleResult::end_time), {n});
  out.array("result_position", "m", position, {n, 3});
  out.array("result_depth", "m", column(&BottleResult::depth), {n});
  out.array("result_temperature", "degC", column(&BottleResult::temperature), {n});
  out.array("result_salinity", "PSU", column(&BottleResult::salinity), {n});
  out.array("result_conductivity", "uS/cm", column(&BottleResult::conductivity), {n});
  out.array("result_ph", "pH", column(&BottleResult::ph), {n});
  out.array("result_redox", "mV", column(&BottleResult::redox), {n});
  out.array("result_oxygen", "mg/L", column(&BottleResult::oxygen), {n});
  out.array("result_turbidity", "NTU", column(&BottleResult::turbidity), {n});
  out.array("result_density", "kg/m^3", column(&BottleResult::density), {n});
  out.array("result_volume", "L", column(&BottleResult::volume), {n});
  out.array("result_mass", "kg", column(&BottleResult::mass), {n});
}

}  // namespace science
}  // namespace sensors
}  // namespace unexmin

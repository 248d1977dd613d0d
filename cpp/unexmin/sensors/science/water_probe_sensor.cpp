#include <unexmin/sensors/science/water_probe_sensor.h>

#include <unexmin/sensors/noise_factory.h>
#include <unexmin/sensors/pressure_sensor.h>
#include <unexmin/sensors/sensor_params.h>
#include <unexmin/water/water_column.h>

#include <cmath>

namespace unexmin {
namespace sensors {
namespace science {
namespace {

/// Per channel: the default time constant [s] (assumed, docs/water_probe.md) and the largest noise figure accepted.
struct ChannelLimits {
  double tau;
  double max_figure;  ///< [u] for noise and resolution, [u/sqrt(s)] for drift
};
constexpr std::array<ChannelLimits, WaterProbeSensor::kChannelCount> kLimits{{
    {1.0, 10.0},     // temperature [degC]
    {1.0, 1e5},      // conductivity [uS/cm]
    {5.0, 14.0},     // ph
    {10.0, 1000.0},  // redox [mV]
    {8.0, 100.0},    // oxygen [mg/L]
    {0.05, 1e7},     // pressure [Pa]
}};

}  // namespace

const std::array<std::pair<const char*, const char*>, WaterProbeSensor::kChannelCount>& WaterProbeSensor::channels() {
  static const std::array<std::pair<const char*, const char*>, kChannelCount> names{{{"temperature", "degC"},
                                                                                     {"conductivity", "uS/cm"},
                                                                                     {"ph", "pH"},
                                                                                     {"redox", "mV"},
                                                                                     {"oxygen", "mg/L"},
                                                                                     {"pressure", "Pa"}}};
  return names;
}

WaterProbeSensor::WaterProbeSensor(const sim::SensorSpec& spec, const SensorSetup& setup) : Sensor(spec, setup) {
  SensorParams p(spec, setup.robot);
  const std::string family = p.text("noise", "gaussian", noiseFamilies());
  std::array<ProbeChannelParams, kChannelCount> figures;
  for (int c = 0; c < kChannelCount; ++c) {
    const std::string name = channels()[c].first, unit = channels()[c].second;
    const double top = kLimits[c].max_figure;
    ProbeChannelParams& f = figures[c];
    f.tau = p.number(name + "_tau", kLimits[c].tau, 0.0, 3600.0, "s");
    f.noise = p.number(name + "_noise", 0.0, 0.0, top, unit);
    f.drift = p.number(name + "_drift", 0.0, 0.0, top, unit + "/sqrt(s)");
    f.resolution = p.number(name + "_resolution", 0.0, 0.0, top, unit);
  }
  alpha_ = p.number("alpha", 0.02, 0.0, 0.03, "1/degC");
  p.finish();
  channels_.reserve(kChannelCount);
  for (int c = 0; c < kChannelCount; ++c)
    channels_.emplace_back(family, figures[c], interval());
  resolution_25_ = figures[kConductivity].resolution;
}

void WaterProbeSensor::onReset() {
  for (ProbeChannel& c : channels_)
    c.reset(random());
  settled_ = false;
  last_ = WaterProbeSample();
}

std::array<double, WaterProbeSensor::kChannelCount> WaterProbeSensor::water(const SensorContext& ctx) const {
  const Eigen::Vector3d intake = ctx.state.pose * spec().pose.translation();
  std::array<double, kChannelCount> x;
  x[kPressure] = hydrostaticPressure(ctx.world, intake);
  if (const auto& column = ctx.world.config().water_column) {
    const water::WaterSample w = column->at(intake, ctx.world.time());
    x[kTemperature] = w.temperature;
    x[kConductivity] = w.conductivity;
    x[kPh] = w.ph;
    x[kRedox] = w.redox;
    x[kOxygen] = w.oxygen;
  } else {  // uniform water: the column's defaults (fresh, 10 degC)
    const water::WaterRow w;
    x[kTemperature] = w.temperature;
    x[kConductivity] = w.conductivity;
    x[kPh] = w.ph;
    x[kRedox] = w.redox;
    x[kOxygen] = w.oxygen;
  }
  return x;
}

void WaterProbeSensor::track(const SensorContext& ctx) {
  const std::array<double, kChannelCount> x = water(ctx);
  for (int c = 0; c < kChannelCount; ++c) {
    if (settled_)
      channels_[c].track(x[c], ctx.world.dt());
    else
      channels_[c].settle(x[c]);
  }
  settled_ = true;
}

void WaterProbeSensor::sample(const SensorContext& ctx) {
  std::array<double, kChannelCount> y;
  for (int c = 0; c < kChannelCount; ++c)
    y[c] = channels_[c].read(random());
  WaterProbeSample& s = last_;
  s.time = ctx.world.time();
  s.temperature = y[kTemperature];
  s.conductivity = y[kConductivity];
  s.ph = y[kPh];
  s.redox = y[kRedox];
  s.oxygen = y[kOxygen];
  s.pressure = y[kPressure];
  const double q = resolution_25_;
  const double ec25 = compensated(s.conductivity, s.temperature, alpha_);
  s.conductivity_25 = q > 0.0 ? q * std::round(ec25 / q) : ec25;
  s.temperature_variance = channels_[kTemperature].variance();
  s.conductivity_variance = channels_[kConductivity].variance();
  s.ph_variance = channels_[kPh].variance();
  s.redox_variance = channels_[kRedox].variance();
  s.oxygen_variance = channels_[kOxygen].variance();
  s.pressure_variance = channels_[kPressure].variance();
  // first order: d EC25 / d EC = 1 / f, d EC25 / d T = -alpha EC25 / f with f = 1 + alpha (T - 25), and EC25's own
  // rounding
  const double f = 1.0 + alpha_ * (s.temperature - 25.0);
  const double by_t = alpha_ * ec25 / f;
  s.conductivity_25_variance = s.conductivity_variance / (f * f) + by_t * by_t * s.temperature_variance + q * q / 12.0;
}

void WaterProbeSensor::describeSample(SampleWriter& out) const {
  out.scalar("temperature", "degC", last_.temperature);
  out.scalar("conductivity", "uS/cm", last_.conductivity);
  out.scalar("conductivity_25", "uS/cm", last_.conductivity_25);
  out.scalar("ph", "pH", last_.ph);
  out.scalar("redox", "mV", last_.redox);
  out.scalar("oxygen", "mg/L", last_.oxygen);
  out.scalar("pressure", "Pa", last_.pressure);
}

}  // namespace science
}  // namespace sensors
}  // namespace unexmin

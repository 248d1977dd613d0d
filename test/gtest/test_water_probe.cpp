// The water-quality probe (cpp/unexmin/sensors/science/water_probe_sensor.h) against closed forms computed here: the
// first-order lag's step response 1 - exp(-t / tau) and its smear v tau across a chemocline, the conductivity
// compensated to 25 degC, the resolution, the white noise and the offset random walk over seeded samples, the water
// of a world without a column, and every parameter error.
#include <unexmin/sensors/pressure_sensor.h>
#include <unexmin/sensors/science/water_probe_sensor.h>
#include <unexmin/water/water_column.h>
#include "expect_error.h"
#include "sensor_fixture.h"

#include <gtest/gtest.h>

#include <cmath>

namespace unexmin {
namespace test {
namespace {

using sensors::science::WaterProbeSensor;

constexpr double kDt = 0.002;                    // [s] physics step
const Eigen::Vector3d kIntake(0.1, 0.0, -0.25);  // [m] probe link in the base frame
constexpr double kStep = 20.0;                   // [m] depth of the chemocline
constexpr double kT1 = 10.0, kT2 = 16.0;         // [degC] above and below it
constexpr double kEc1 = 500.0, kEc2 = 9000.0;    // [uS/cm]
constexpr double kPh1 = 7.2, kPh2 = 4.1, kRedox1 = 250.0, kRedox2 = -60.0, kDo1 = 9.0, kDo2 = 0.5;

/// Two layers of water (interpolation: layers), the step at kStep.
std::shared_ptr<const water::WaterColumn> layered() {
  water::Profile p;
  p.layers = true;
  p.conductivity = true;
  auto add = [&p](double depth, double t, double ec, double ph, double redox, double oxygen) {
    water::WaterRow r;
    r.depth = depth;
    r.temperature = t;
    r.conductivity = ec;
    r.ph = ph;
    r.redox = redox;
    r.oxygen = oxygen;
    p.rows.push_back(r);
  };
  add(0.0, kT1, kEc1, kPh1, kRedox1, kDo1);
  add(kStep, kT2, kEc2, kPh2, kRedox2, kDo2);
  add(200.0, kT2, kEc2, kPh2, kRedox2, kDo2);
  water::checkProfile(p, "water.profile");
  return std::make_shared<const water::WaterColumn>(p, std::vector<water::Region>{}, 0.0, 9.81);
}

/// A world (with the layered column unless `column` is false) with the sphere robot carrying one probe `probe` at
/// kIntake sampling at `rate`.
std::unique_ptr<SensorWorld> probeWorld(const std::map<std::string, std::string>& params, double rate = 500.0,
                                        bool column = true, double depth = 10.0, std::uint64_t seed = 1) {
  const SphereSpec s = undampedSphere();
  sim::WorldConfig config = openWater(s, Eigen::Vector3d(0, 0, -depth));
  if (column)
    config.water_column = layered();
  const std::string urdf = sensorUrdf(s, mountLink("T/probe_link", kIntake, Eigen::Vector3d::Zero()),
                                      sensorXml("probe", "water_probe", "T/probe_link", rate, params));
  return std::make_unique<SensorWorld>(config, urdf, seed, kDt);
}

/// Puts the robot's base at depth `base` [m] with vertical velocity `vz` [m/s], level, then steps once.
void stepAt(SensorWorld& w, double base, double vz = 0.0) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0, 0, -base);
  w.place(pose, Eigen::Vector3d(0, 0, vz));
  w.step();
}

double intakeDepth(SensorWorld& w) {
  return -(w.robot().state().pose * kIntake).z();
}

/// No noise, no lag unless asked.
std::map<std::string, std::string> ideal(std::map<std::string, std::string> extra = {}) {
  std::map<std::string, std::string> p{{"noise", "none"}};
  for (const char* c : {"temperature", "conductivity", "ph", "redox", "oxygen", "pressure"})
    p[std::string(c) + "_tau"] = "0";
  for (const auto& kv : extra)
    p[kv.first] = kv.second;
  return p;
}

TEST(WaterProbe, TemperatureStepFollowsOneMinusExpOfTOverTau) {
  const double tau = 1.3;
  auto w = probeWorld(ideal({{"temperature_tau", num(tau)}}));
  auto& probe = w->sensor<WaterProbeSensor>("probe");
  for (int i = 0; i < 500; ++i)  // 1 s in the upper layer, settled at the first step
    stepAt(*w, 10.0);
  EXPECT_DOUBLE_EQ(probe.last().temperature, kT1);
  const double t0 = w->world->time();
  int n = 0;
  double worst = 0.0;
  while (w->world->time() < t0 + 4.0 * tau) {  // moved into the lower layer at t0
    stepAt(*w, 30.0);
    const double t = probe.sampleTime() - t0;
    const double expected = kT2 + (kT1 - kT2) * std::exp(-t / tau);
    worst = std::max(worst, std::abs(probe.last().temperature - expected));
    ++n;
  }
  EXPECT_EQ(n, static_cast<int>(std::lround(4.0 * tau / kDt)));
  EXPECT_LT(worst, 1e-9 * (kT2 - kT1));  // exact discretisation: the closed form at every step
  // at t = tau the electrode has gone 1 - 1/e of the way; a tau 1 % off would be 2e-3 of the step away
  auto w2 = probeWorld(ideal({{"temperature_tau", num(tau)}}));
  auto& p2 = w2->sensor<WaterProbeSensor>("probe");
  stepAt(*w2, 10.0);
  const double t1 = w2->world->time();
  while (w2->world->time() < t1 + tau - 1e-9)
    stepAt(*w2, 30.0);
  EXPECT_NEAR((p2.last().temperature - kT1) / (kT2 - kT1), 1.0 - std::exp(-1.0), 1e-3);
  EXPECT_GT(std::abs(1.0 - std::exp(-1.0 / 1.01) - (1.0 - std::exp(-1.0))), 2e-3);
}

TEST(WaterProbe, EveryChannelSettlesAtResetAndLagsWithItsOwnTau) {
  auto w = probeWorld({{"noise", "none"}});  // the default time constants
  auto& probe = w->sensor<WaterProbeSensor>("probe");
  stepAt(*w, 10.0);
  const auto& s = probe.last();
  EXPECT_DOUBLE_EQ(s.temperature, kT1);
  EXPECT_DOUBLE_EQ(s.conductivity, kEc1);
  EXPECT_DOUBLE_EQ(s.ph, kPh1);
  EXPECT_DOUBLE_EQ(s.redox, kRedox1);
  EXPECT_DOUBLE_EQ(s.oxygen, kDo1);
  const Eigen::Vector3d intake = w->robot().state().pose * kIntake;
  EXPECT_DOUBLE_EQ(s.pressure, sensors::hydrostaticPressure(*w->world, intake));
  // 2 s below the step: each channel 1 - exp(-2 / tau) of its way (defaults T 1, EC 1, pH 5, redox 10, DO 8 s)
  const double t0 = w->world->time();
  while (w->world->time() < t0 + 2.0 - 1e-9)
    stepAt(*w, 30.0);
  auto part = [](double tau) { return 1.0 - std::exp(-2.0 / tau); };
  EXPECT_NEAR(s.temperature, kT1 + (kT2 - kT1) * part(1.0), 1e-9);
  EXPECT_NEAR(s.conductivity, kEc1 + (kEc2 - kEc1) * part(1.0), 1e-6);
  EXPECT_NEAR(s.ph, kPh1 + (kPh2 - kPh1) * part(5.0), 1e-9);
  EXPECT_NEAR(s.redox, kRedox1 + (kRedox2 - kRedox1) * part(10.0), 1e-7);
  EXPECT_NEAR(s.oxygen, kDo1 + (kDo2 - kDo1) * part(8.0), 1e-9);
  // pressure (tau 0.05 s): settled to the hydrostatic pressure here within exp(-40) of the 20 m jump
  EXPECT_NEAR(s.pressure, sensors::hydrostaticPressure(*w->world, w->robot().state().pose * kIntake), 1e-3);
}

TEST(WaterProbe, ConductivityCompensatedTo25DegreesFollowsTheFormula) {
  const double alpha = 0.0191;  // KCl
  auto w = probeWorld(ideal({{"alpha", num(alpha)}}));
  auto& probe = w->sensor<WaterProbeSensor>("probe");
  stepAt(*w, 10.0);
  EXPECT_NEAR(probe.last().conductivity_25, kEc1 / (1.0 + alpha * (kT1 - 25.0)), 1e-9 * kEc1);
  stepAt(*w, 30.0);
  EXPECT_NEAR(probe.last().conductivity_25, kEc2 / (1.0 + alpha * (kT2 - 25.0)), 1e-9 * kEc2);
  // 10 degC below 25: the compensated value is 1 / (1 - 0.287) = 1.40 times the in-situ one
  EXPECT_GT(probe.last().conductivity_25, 1.1 * kEc2);
  auto d = probeWorld(ideal());
  stepAt(*d, 10.0);
  EXPECT_DOUBLE_EQ(d->sensor<WaterProbeSensor>("probe").alpha(), 0.02);
  EXPECT_NEAR(d->sensor<WaterProbeSensor>("probe").last().conductivity_25, kEc1 / (1.0 + 0.02 * (kT1 - 25.0)),
              1e-9 * kEc1);
}

TEST(WaterProbe, AChemoclineCrossedAtSpeedVIsSmearedOverVTau) {
  const double tau = 2.0, v = 0.25;  // [s], [m/s] down
  auto w = probeWorld(ideal({{"ph_tau", num(tau)}}));
  auto& probe = w->sensor<WaterProbeSensor>("probe");
  const double start = 17.0;  // base depth [m]; the intake is 0.25 m lower
  double base = start;
  stepAt(*w, base);
  const double level = kPh1 + (kPh2 - kPh1) * (1.0 - std::exp(-1.0));  // 1 - 1/e of the way
  double previous_ph = probe.last().ph, previous_depth = intakeDepth(*w), crossed = NAN;
  while (std::isnan(crossed) && base < start + 10.0) {
    base += v * kDt;
    stepAt(*w, base, -v);
    const double ph = probe.last().ph, depth = intakeDepth(*w);
    if (ph <= level)
      crossed = previous_depth + (depth - previous_depth) * (previous_ph - level) / (previous_ph - ph);
    previous_ph = ph;
    previous_depth = depth;
  }
  ASSERT_FALSE(std::isnan(crossed));
  // the step reached the electrode v tau = 0.5 m late; a step's position lag v dt = 0.5 mm
  EXPECT_NEAR(crossed - kStep, v * tau, 2.0 * v * kDt);
  EXPECT_GT(v * tau * 0.01, 2.0 * v * kDt);  // a tau 1 % off would fail
}

TEST(WaterProbe, ReadingsAreRoundedToTheResolution) {
  auto w = probeWorld(ideal({{"temperature_resolution", "0.25"},
                             {"conductivity_resolution", "7"},
                             {"ph_resolution", "0.5"},
                             {"redox_resolution", "100"}}));
  auto& probe = w->sensor<WaterProbeSensor>("probe");
  stepAt(*w, 30.0);
  const auto& s = probe.last();
  EXPECT_DOUBLE_EQ(s.temperature, 16.0);                             // 16 on the grid
  EXPECT_DOUBLE_EQ(s.conductivity, 7.0 * std::round(9000.0 / 7.0));  // 8999
  EXPECT_DOUBLE_EQ(s.ph, 4.0);                                       // 4.1
  EXPECT_DOUBLE_EQ(s.redox, -100.0);                                 // -60
  EXPECT_DOUBLE_EQ(s.oxygen, kDo2);                                  // no resolution
  EXPECT_DOUBLE_EQ(s.conductivity_25, 7.0 * std::round(s.conductivity / (1.0 + 0.02 * (16.0 - 25.0)) / 7.0));
  EXPECT_DOUBLE_EQ(s.ph_variance, 0.25 / 12.0);  // quantisation's q^2 / 12
}

TEST(WaterProbe, WhiteNoiseAndOffsetRandomWalkHaveTheirSigma) {
  const double sigma = 0.05, walk = 0.5;  // temperature [degC]; redox [mV/sqrt(s)]
  const int n = 20000;                    // 40 s at 500 Hz
  auto w = probeWorld(ideal({{"noise", "gaussian"}, {"temperature_noise", num(sigma)}, {"redox_drift", num(walk)}}),
                      500.0, true, 10.0, 42);
  auto& probe = w->sensor<WaterProbeSensor>("probe");
  double sum = 0.0, sum2 = 0.0, step2 = 0.0, previous = NAN;
  for (int i = 0; i < n; ++i) {
    stepAt(*w, 10.0);
    const double e = probe.last().temperature - kT1;
    sum += e;
    sum2 += e * e;
    if (i > 0)
      step2 += (probe.last().redox - previous) * (probe.last().redox - previous);
    previous = probe.last().redox;
  }
  ASSERT_EQ(probe.sampleCount(), static_cast<std::uint64_t>(n));
  const double mean = sum / n;
  EXPECT_NEAR(mean, 0.0, 4.0 * sigma / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(sum2 / n - mean * mean), sigma, 0.03 * sigma);
  EXPECT_NEAR(std::sqrt(step2 / (n - 1)), walk * std::sqrt(kDt), 0.03 * walk * std::sqrt(kDt));
  EXPECT_DOUBLE_EQ(probe.last().temperature_variance, sigma * sigma);
  // a seed repeats: the same noise again from a fresh world of that seed; another seed differs
  auto again = probeWorld(ideal({{"noise", "gaussian"}, {"temperature_noise", num(sigma)}}), 500.0, true, 10.0, 42);
  auto other = probeWorld(ideal({{"noise", "gaussian"}, {"temperature_noise", num(sigma)}}), 500.0, false, 10.0, 42);
  auto& a = again->sensor<WaterProbeSensor>("probe");
  auto& b = other->sensor<WaterProbeSensor>("probe");
  for (int i = 0; i < 50; ++i) {
    stepAt(*again, 10.0);
    stepAt(*other, 10.0);
    // a fixed count of draws per sample: the noise is the same in a world with a column and one without
    EXPECT_NEAR(a.last().temperature - kT1, b.last().temperature - water::WaterRow().temperature, 1e-12);
  }
}

TEST(WaterProbe, AWorldWithoutAColumnIsFreshWaterAtTenDegrees) {
  auto w = probeWorld(ideal(), 500.0, /*column=*/false, 12.0);
  auto& probe = w->sensor<WaterProbeSensor>("probe");
  stepAt(*w, 12.0);
  const auto& s = probe.last();
  const water::WaterRow fresh;
  EXPECT_DOUBLE_EQ(s.temperature, 10.0);
  EXPECT_DOUBLE_EQ(s.temperature, fresh.temperature);
  EXPECT_DOUBLE_EQ(s.conductivity, 0.0);
  EXPECT_DOUBLE_EQ(s.ph, 7.0);
  EXPECT_DOUBLE_EQ(s.redox, 200.0);
  EXPECT_DOUBLE_EQ(s.oxygen, 10.0);
  const double z = (w->robot().state().pose * kIntake).z();
  EXPECT_DOUBLE_EQ(s.pressure, 101325.0 + 1000.0 * 9.81 * (0.0 - z));  // openWater: 1000 kg/m^3, g 9.81
}

TEST(WaterProbe, DescribesItsSampleWithUnits) {
  auto w = probeWorld(ideal());
  stepAt(*w, 10.0);
  struct Names : sensors::SampleWriter {
    std::vector<std::pair<std::string, std::string>> got;
    void field(const sensors::SampleField& f) override { got.emplace_back(f.name, f.unit); }
  } names;
  w->sensor<WaterProbeSensor>("probe").describe(names);
  const auto& got = names.got;
  const std::vector<std::pair<std::string, std::string>> expected{
      {"time", "s"}, {"count", ""},   {"temperature", "degC"}, {"conductivity", "uS/cm"}, {"conductivity_25", "uS/cm"},
      {"ph", "pH"},  {"redox", "mV"}, {"oxygen", "mg/L"},      {"pressure", "Pa"}};
  EXPECT_EQ(got, expected);
}

TEST(WaterProbe, BadParametersStopStartUpNamingSensorParameterAndRange) {
  auto message = [](const std::map<std::string, std::string>& params) {
    return thrownMessage<ConfigError>([&] { probeWorld(params); });
  };
  std::string m = message({{"ph_tau", "-1"}});
  EXPECT_TRUE(contains(m, "sensor 'probe'")) << m;
  EXPECT_TRUE(contains(m, "'ph_tau' = -1")) << m;
  EXPECT_TRUE(contains(m, "[0, 3600] s")) << m;
  m = message({{"alpha", "0.5"}});
  EXPECT_TRUE(contains(m, "'alpha' = 0.5")) << m;
  m = message({{"oxygen_noise", "-0.1"}});
  EXPECT_TRUE(contains(m, "'oxygen_noise'")) << m;
  m = message({{"temperature_resolution", "20"}});  // above 10 degC
  EXPECT_TRUE(contains(m, "'temperature_resolution'")) << m;
  m = message({{"ph_tua", "3"}});  // a misspelt name
  EXPECT_TRUE(contains(m, "ph_tua")) << m;
  m = message({{"noise", "pink"}});
  EXPECT_TRUE(contains(m, "'noise'")) << m;
}

}  // namespace
}  // namespace test
}  // namespace unexmin

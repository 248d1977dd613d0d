// Gamma-ray counter (cpp/unexmin/sensors/science/gamma_counter_sensor.h) against closed forms computed here: the
// emission per gram from half-lives and abundances (and IAEA-TECDOC-1363's conversion factors), the uncollided flux
// of a flat rock wall phi = q / (2 (mu/rho)_rock) E2(mu_w d) at 0.05..0.3 m, its fall with distance, the 4 pi flux
// inside a spherical cavity, background only without rock, Poisson statistics, the non-paralysable dead time and
// start-up errors.
#include <unexmin/geo/geology.h>
#include <unexmin/sensors/science/gamma_counter_sensor.h>
#include "expect_error.h"
#include "sonar_fixture.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace unexmin {
namespace test {
namespace {

using sensors::science::GammaCounterSensor;
using sensors::science::kGammaWindows;

// ---- the physics, written out again here (docs/gamma_counter.md gives the sources)
constexpr double kNA = 6.02214076e23;
constexpr double kYear = 365.25 * 86400.0;
// [Bq per g of the element]
const double kBqPerGramK = 1.17e-4 * kNA / 39.0983 * std::log(2.0) / (1.248e9 * kYear);
const double kBqPerGramU = 0.992742 * kNA / 238.02891 * std::log(2.0) / (4.468e9 * kYear);
const double kBqPerGramTh = 1.0 * kNA / 232.0377 * std::log(2.0) / (1.405e10 * kYear);
// photons of the line per decay of the parent
const double kYield[3] = {0.1066, 0.1531, 0.3594 * 0.99754};
// (mu/rho) of water [cm^2/g] (NIST, log-log between 1.25/1.5, 1.5/2 and 2/3 MeV) and the rock / water ratio
const double kWaterMuRho[3] = {0.05833, 0.05280, 0.04275};
constexpr double kRockRatio = 0.90;

/// The rock of the tests: a granite-like 2.5 % K, 4 ppm U, 15 ppm Th [assumed numbers].
geo::Rock granite() {
  geo::Rock r;
  r.density = 2650.0;
  r.potassium = 2.5;
  r.uranium = 4.0;
  r.thorium = 15.0;
  return r;
}

/// Photons per gram of rock per second of each line.
std::array<double, 3> emission(const geo::Rock& r) {
  return {r.potassium * 1e-2 * kBqPerGramK * kYield[0], r.uranium * 1e-6 * kBqPerGramU * kYield[1],
          r.thorium * 1e-6 * kBqPerGramTh * kYield[2]};
}

/// E2(x) = integral_0^1 exp(-x / t) dt, Simpson's rule on 20 000 intervals (the integrand is smooth for x > 0).
double e2(double x) {
  const int n = 20000;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double t = static_cast<double>(i) / n;
    const double f = t == 0.0 ? 0.0 : std::exp(-x / t);
    sum += f * (i == 0 || i == n ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0));
  }
  return sum / (3.0 * n);
}

/// The sphere robot with the detector `xyz` from its centre (base link frame).
std::string counterUrdf(const Eigen::Vector3d& xyz, double rate, const std::map<std::string, std::string>& params) {
  return sensorUrdf(SphereSpec(), mountLink("T/gamma_link", xyz, Eigen::Vector3d::Zero()),
                    sensorXml("gamma", "gamma_counter", "T/gamma_link", rate, params));
}

/// No background: the rates are the rock's alone.
std::map<std::string, std::string> noBackground(std::map<std::string, std::string> p = {}) {
  p["potassium_background"] = "0";
  p["uranium_background"] = "0";
  p["thorium_background"] = "0";
  return p;
}

const Eigen::Vector3d kRobot(0, 0, -50);   // deep, far from the surface
const Eigen::Vector3d kMount(0.28, 0, 0);  // inside the 0.3 m hull, near its skin
const double kArea = 54.1;                 // [cm^2] defaults
const double kEfficiency[3] = {0.20, 0.18, 0.14};

/// A world with a 6 m x 6 m x 1 m wall of `rock` whose face is `d` [m] in front of the detector (+x).
sim::WorldConfig wallWorld(double d, const geo::Rock& rock) {
  const double x = kRobot.x() + kMount.x() + d;
  sim::WorldConfig config = meshWorld(
      {{"wall", box(Eigen::Vector3d(x, -3, kRobot.z() - 3), Eigen::Vector3d(x + 1, 3, kRobot.z() + 3))}}, kRobot);
  config.geology = std::make_shared<const geo::Geology>(rock, std::vector<geo::Body>{});
  return config;
}

/// The detector's world position now.
Eigen::Vector3d detector(SensorWorld& w, const Eigen::Vector3d& mount) {
  return w.robot().state().pose * mount;
}

TEST(GammaCounter, EmissionPerGramFollowsHalfLivesAbundancesAndYields) {
  // IAEA-TECDOC-1363 (2003) conversion factors: 1 % K = 313 Bq/kg of 40K, 1 ppm U = 12.35 Bq/kg of 238U,
  // 1 ppm Th = 4.06 Bq/kg of 232Th. Ours for 40K (half-life 1.248e9 y) is 1.3 % more than 313, which rests on older
  // constants.
  EXPECT_NEAR(kBqPerGramK * 10.0, 313.0, 0.025 * 313.0);
  EXPECT_NEAR(kBqPerGramU * 1e-3, 12.35, 0.005 * 12.35);
  EXPECT_NEAR(kBqPerGramTh * 1e-3, 4.06, 0.005 * 4.06);
  const geo::Rock r = granite();
  const std::array<double, 3> expected = emission(r);
  const std::array<double, 3> model = sensors::science::gammaEmissionPerGram(r);
  for (int w = 0; w < 3; ++w)
    EXPECT_NEAR(model[w], expected[w], 1e-9 * expected[w]) << "window " << w;
  EXPECT_EQ(sensors::science::gammaEmissionPerGram(geo::Rock())[0], 0.0);
}

TEST(GammaCounter, FibonacciDirectionsAreUnitAndBalanced) {
  const std::vector<Eigen::Vector3d> d = sensors::science::fibonacciSphere(256);
  ASSERT_EQ(d.size(), 256u);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& v : d) {
    EXPECT_NEAR(v.norm(), 1.0, 1e-12);
    sum += v;
  }
  EXPECT_LT(sum.norm() / 256.0, 0.01);  // no net direction
}

TEST(GammaCounter, FlatWallRateIsTheHalfSpaceClosedFormAndFallsWithDistance) {
  const geo::Rock rock = granite();
  const std::array<double, 3> q = emission(rock);
  const std::vector<double> distances = {0.05, 0.1, 0.2, 0.3};
  std::vector<std::array<double, 3>> rates;
  for (double d : distances) {
    SensorWorld w(wallWorld(d, rock), counterUrdf(kMount, 10.0, noBackground()), 3, 0.01);
    auto& g = w.sensor<GammaCounterSensor>("gamma");
    w.samples(g, 1);
    const Eigen::Vector3d at = detector(w, kMount);
    const double dist = kRobot.x() + kMount.x() + d - at.x();  // the robot may have drifted by micrometres
    ASSERT_NEAR(dist, d, 1e-3);
    std::array<double, 3> r{};
    for (int k = 0; k < 3; ++k) {
      const double mu_w = kWaterMuRho[k] * 1.0 * 100.0;  // [1/m] fresh water, 1 g/cm^3
      const double phi = q[k] / (2.0 * kRockRatio * kWaterMuRho[k]) * e2(mu_w * dist);
      const double expected = kArea * kEfficiency[k] * phi;
      r[k] = g.last().true_rate[k];
      EXPECT_NEAR(g.last().flux[k], phi, 0.02 * phi) << "d " << d << " window " << k;
      EXPECT_NEAR(r[k], expected, 0.02 * expected) << "d " << d << " window " << k;
      // A wrong model misses by more than the tolerance: rock mu/rho equal to water's, or no water attenuation.
      const double same_mu = kArea * kEfficiency[k] * q[k] / (2.0 * kWaterMuRho[k]) * e2(mu_w * dist);
      const double no_exp = kArea * kEfficiency[k] * q[k] / (2.0 * kRockRatio * kWaterMuRho[k]);
      EXPECT_GT(std::abs(r[k] - same_mu), 0.05 * same_mu);
      EXPECT_GT(std::abs(r[k] - no_exp), 0.2 * no_exp);
    }
    rates.push_back(r);
  }
  for (int k = 0; k < 3; ++k) {
    const double mu_w = kWaterMuRho[k] * 100.0;
    // The fall between 5 cm and 30 cm is E2's, close to exp(-mu d) and below it.
    const double ratio = rates[3][k] / rates[0][k];
    EXPECT_NEAR(ratio, e2(mu_w * 0.3) / e2(mu_w * 0.05), 0.03 * ratio) << "window " << k;
    EXPECT_LT(ratio, std::exp(-mu_w * 0.25)) << "window " << k;
    // At 0.3 m the counter sees a small fraction of the contact rate q / (2 mu_rock).
    const double contact = kArea * kEfficiency[k] * q[k] / (2.0 * kRockRatio * kWaterMuRho[k]);
    EXPECT_LT(rates[3][k], 0.25 * contact) << "window " << k;
    EXPECT_LT(rates[1][k], rates[0][k]);
    EXPECT_LT(rates[2][k], rates[1][k]);
  }
}

TEST(GammaCounter, DenserWaterAttenuatesMore) {
  // A brine of 1100 kg/m^3 (a robot of that density, so it stays put): mu_w scales with the water's density.
  SphereSpec s;
  s.rho = 1100.0;
  s.mass = s.rho * s.volume();
  const double d = 0.3;
  sim::WorldConfig config = wallWorld(d, granite());
  config.water_density = s.rho;
  SensorWorld w(config,
                sensorUrdf(s, mountLink("T/gamma_link", kMount, Eigen::Vector3d::Zero()),
                           sensorXml("gamma", "gamma_counter", "T/gamma_link", 10.0, noBackground())),
                3, 0.01);
  auto& g = w.sensor<GammaCounterSensor>("gamma");
  w.samples(g, 1);
  const std::array<double, 3> q = emission(granite());
  for (int k = 0; k < 3; ++k) {
    const double phi = q[k] / (2.0 * kRockRatio * kWaterMuRho[k]) * e2(kWaterMuRho[k] * 1.1 * 100.0 * d);
    const double fresh = q[k] / (2.0 * kRockRatio * kWaterMuRho[k]) * e2(kWaterMuRho[k] * 1.0 * 100.0 * d);
    EXPECT_NEAR(g.last().flux[k], phi, 0.02 * phi) << "window " << k;
    EXPECT_GT(std::abs(g.last().flux[k] - fresh), 0.05 * fresh) << "window " << k;
  }
}

TEST(GammaCounter, InsideASphericalCavityEveryDirectionSeesTheWall) {
  // The borehole-like geometry: the detector at the centre of a cavity of radius R sees rock in every direction,
  // phi = q / (mu/rho)_rock exp(-mu_w R): twice the flat wall's contact value, times the water's attenuation.
  const double radius = 0.5;
  sim::WorldConfig config = meshWorld({{"cavity", icosphere(kRobot, radius, 4)}}, kRobot);
  config.geology = std::make_shared<const geo::Geology>(granite(), std::vector<geo::Body>{});
  SensorWorld w(config, counterUrdf(Eigen::Vector3d::Zero(), 10.0, noBackground()), 3, 0.01);
  auto& g = w.sensor<GammaCounterSensor>("gamma");
  w.samples(g, 1);
  ASSERT_NEAR((detector(w, Eigen::Vector3d::Zero()) - kRobot).norm(), 0.0, 1e-3);
  const std::array<double, 3> q = emission(granite());
  for (int k = 0; k < 3; ++k) {
    const double phi = q[k] / (kRockRatio * kWaterMuRho[k]) * std::exp(-kWaterMuRho[k] * 100.0 * radius);
    EXPECT_NEAR(g.last().flux[k], phi, 0.01 * phi) << "window " << k;
    EXPECT_NEAR(g.last().true_rate[k], kArea * kEfficiency[k] * phi, 0.01 * kArea * kEfficiency[k] * phi);
    // not the half-space value (a model integrating over a hemisphere only)
    EXPECT_GT(std::abs(g.last().flux[k] - 0.5 * phi), 0.4 * phi);
  }
}

TEST(GammaCounter, WithoutRockSourcesItCountsTheBackgroundOnly) {
  const std::map<std::string, std::string> params = {{"potassium_background", "3"},
                                                     {"uranium_background", "2"},
                                                     {"thorium_background", "0.5"},
                                                     {"continuum_factor", "2"}};
  // A world without geology, and a wall of a rock with no K, U or Th: only the background.
  sim::WorldConfig no_geology = wallWorld(0.05, granite());
  no_geology.geology.reset();
  sim::WorldConfig barren = wallWorld(0.05, geo::Rock());
  for (const sim::WorldConfig* config : {&no_geology, &barren}) {
    SensorWorld w(*config, counterUrdf(kMount, 10.0, params), 3, 0.01);
    auto& g = w.sensor<GammaCounterSensor>("gamma");
    w.samples(g, 1);
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(g.last().flux[k], 0.0);
    EXPECT_DOUBLE_EQ(g.last().true_rate[0], 3.0);
    EXPECT_DOUBLE_EQ(g.last().true_rate[1], 2.0);
    EXPECT_DOUBLE_EQ(g.last().true_rate[2], 0.5);
    EXPECT_DOUBLE_EQ(g.last().true_rate_total, 2.0 * 5.5);
  }
  // Open water: the same.
  SensorWorld w(openWater(SphereSpec(), kRobot), counterUrdf(kMount, 10.0, params), 3, 0.01);
  auto& g = w.sensor<GammaCounterSensor>("gamma");
  w.samples(g, 1);
  EXPECT_DOUBLE_EQ(g.last().true_rate[0], 3.0);
}

/// Mean and variance of `n` samples of each window's counts and of the total.
struct Moments {
  std::array<double, 4> mean{}, variance{};
};

Moments countMoments(SensorWorld& w, GammaCounterSensor& g, int n) {
  std::array<double, 4> sum{}, sum2{};
  for (int i = 0; i < n; ++i) {
    w.samples(g, 1);
    for (int k = 0; k < 4; ++k) {
      const double c = static_cast<double>(k < 3 ? g.last().counts[k] : g.last().counts_total);
      sum[k] += c;
      sum2[k] += c * c;
    }
  }
  Moments m;
  for (int k = 0; k < 4; ++k) {
    m.mean[k] = sum[k] / n;
    m.variance[k] = (sum2[k] - n * m.mean[k] * m.mean[k]) / (n - 1);
  }
  return m;
}

TEST(GammaCounter, CountsArePoissonOverSeededSamples) {
  // 100 Hz, 10 ms integration, background only: window means 20, 8, 2; total 3 x 30 = 90.
  const double T = 0.01;
  const std::map<std::string, std::string> params = {{"potassium_background", "2000"},
                                                     {"uranium_background", "800"},
                                                     {"thorium_background", "200"},
                                                     {"continuum_factor", "3"},
                                                     {"dead_time", "0"},
                                                     {"integration_time", num(T)}};
  SensorWorld w(openWater(SphereSpec(), kRobot), counterUrdf(kMount, 100.0, params), 11, 0.01);
  auto& g = w.sensor<GammaCounterSensor>("gamma");
  const int n = 4000;
  const Moments m = countMoments(w, g, n);
  const std::array<double, 4> lambda = {20.0, 8.0, 2.0, 90.0};
  for (int k = 0; k < 4; ++k) {
    const double l = lambda[k];
    EXPECT_NEAR(m.mean[k], l, 4.0 * std::sqrt(l / n)) << "channel " << k;
    // var of the sample variance of a Poisson: (2 l^2 + l) / n
    EXPECT_NEAR(m.variance[k], l, 4.0 * std::sqrt((2.0 * l * l + l) / n)) << "channel " << k;
  }
  EXPECT_NEAR(g.last().expected_counts[0], 20.0, 1e-9);
  // Rates without dead time are the counts over T.
  EXPECT_DOUBLE_EQ(g.last().rate[0], static_cast<double>(g.last().counts[0]) / T);
  EXPECT_DOUBLE_EQ(g.last().dead_time_fraction, 0.0);
}

TEST(GammaCounter, ASeedRepeatsTheCountsAndEachChannelDrawsOnce) {
  const auto counts = [](std::uint64_t seed, const std::string& uranium_background) {
    SensorWorld w(openWater(SphereSpec(), kRobot),
                  counterUrdf(kMount, 100.0,
                              {{"potassium_background", "1000"},
                               {"uranium_background", uranium_background},
                               {"dead_time", "0"},  // else the uranium window's rate changes the live time
                               {"integration_time", "0.01"}}),
                  seed, 0.01);
    auto& g = w.sensor<GammaCounterSensor>("gamma");
    std::vector<std::uint64_t> k;
    for (int i = 0; i < 50; ++i) {
      w.samples(g, 1);
      k.push_back(g.last().counts[0]);
    }
    return k;
  };
  EXPECT_EQ(counts(5, "100"), counts(5, "100"));
  EXPECT_NE(counts(5, "100"), counts(6, "100"));
  // Another mean in the uranium window (more or fewer counts) leaves the potassium counts as they were: a fixed
  // number of draws per sample.
  EXPECT_EQ(counts(5, "100"), counts(5, "3000"));
}

TEST(GammaCounter, NonParalysableDeadTimeAndItsCorrection) {
  // n = 1e5 cps in the K window (the total: continuum factor 1), tau = 5 us: n tau = 0.5, m = n / 1.5.
  const double n_true = 1e5, tau = 5e-6, T = 0.01;
  SensorWorld w(openWater(SphereSpec(), kRobot),
                counterUrdf(kMount, 100.0,
                            {{"potassium_background", num(n_true)},
                             {"uranium_background", "0"},
                             {"thorium_background", "0"},
                             {"continuum_factor", "1"},
                             {"dead_time", num(tau)},
                             {"integration_time", num(T)}}),
                7, 0.01);
  auto& g = w.sensor<GammaCounterSensor>("gamma");
  const int n = 2000;
  double sum = 0.0, corrected = 0.0, fraction = 0.0;
  for (int i = 0; i < n; ++i) {
    w.samples(g, 1);
    EXPECT_EQ(g.last().counts_total, g.last().counts[0]);
    sum += static_cast<double>(g.last().counts[0]);
    corrected += g.last().rate[0];
    fraction += g.last().dead_time_fraction;
  }
  const double m = n_true / (1.0 + n_true * tau);
  const double mean_rate = sum / n / T;
  EXPECT_NEAR(mean_rate, m, 4.0 * std::sqrt(m * T / n) / T);
  EXPECT_GT(std::abs(mean_rate - n_true * std::exp(-n_true * tau)), 0.05 * m);  // not the paralysable model
  EXPECT_NEAR(corrected / n, n_true, 0.01 * n_true);                            // n = m / (1 - m tau)
  EXPECT_NEAR(fraction / n, m * tau, 0.01);
}

TEST(GammaCounter, MalformedParametersStopStartUpNamingSensorAndParameter) {
  const auto error = [](double rate, const std::map<std::string, std::string>& params) {
    return thrownMessage<ConfigError>(
        [&] { SensorWorld w(openWater(SphereSpec(), kRobot), counterUrdf(kMount, rate, params)); });
  };
  std::string m = error(1.0, {{"rays", "8"}});
  EXPECT_TRUE(contains(m, "sensor 'gamma'") && contains(m, "'rays' = 8")) << m;
  m = error(1.0, {{"rays", "100.5"}});
  EXPECT_TRUE(contains(m, "'rays' = 100.5")) << m;
  m = error(2.0, {{"integration_time", "1"}});  // longer than 1 / rate
  EXPECT_TRUE(contains(m, "'integration_time' = 1") && contains(m, "0.5")) << m;
  m = error(1.0, {{"uranium_efficiency", "1.5"}});
  EXPECT_TRUE(contains(m, "'uranium_efficiency' = 1.5")) << m;
  m = error(1.0, {{"water_attenuation", "0.058 0.5 0.044"}});
  EXPECT_TRUE(contains(m, "'water_attenuation' = 0.5")) << m;
  m = error(1.0, {{"dead_tme", "1e-6"}});
  EXPECT_TRUE(contains(m, "dead_tme")) << m;
}

}  // namespace
}  // namespace test
}  // namespace unexmin

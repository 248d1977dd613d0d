#include <unexmin/sensors/science/gamma_counter_sensor.h>

#include <unexmin/core/error.h>
#include <unexmin/sensors/sensor_params.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

namespace unexmin {
namespace sensors {
namespace science {
namespace {

constexpr double kAvogadro = 6.02214076e23;  // [1/mol] (SI 2019, exact)
constexpr double kYear = 365.25 * 86400.0;   // [s] Julian year
const double kLn2 = std::log(2.0);

// Activity per gram of the element [Bq/g] = abundance * N_A / M * ln 2 / T_half.
// 40K: isotopic abundance 0.0117 % (IUPAC 2013, Meija et al. 2016), K 39.0983 g/mol, T_half 1.248e9 y (DDEP/LNHB).
const double kPotassiumActivity = 1.17e-4 * kAvogadro / 39.0983 * kLn2 / (1.248e9 * kYear);  // 31.7 Bq/g K
// 238U: 99.2742 % of the atoms of natural uranium (IUPAC), U 238.02891 g/mol, T_half 4.468e9 y (DDEP).
const double kUraniumActivity = 0.992742 * kAvogadro / 238.02891 * kLn2 / (4.468e9 * kYear);  // 12 347 Bq/g U
// 232Th: 100 % of natural thorium, Th 232.0377 g/mol, T_half 1.405e10 y (DDEP).
const double kThoriumActivity = kAvogadro / 232.0377 * kLn2 / (1.405e10 * kYear);  // 4 057 Bq/g Th
// Photons of the line per decay of the parent: 40K 1460.8 keV 10.66 %; 214Bi 1764.5 keV 15.31 % (per 238U decay in
// secular equilibrium); 208Tl 2614.5 keV 99.75 % per 208Tl decay x 35.94 % of 212Bi decays feeding 208Tl (DDEP).
constexpr double kPotassiumYield = 0.1066;
constexpr double kUraniumYield = 0.1531;
constexpr double kThoriumYield = 0.3594 * 0.99754;
// (mu/rho) of liquid water [cm^2/g], log-log interpolated at the three lines in Hubbell & Seltzer's table (NIST SRD
// 126: 1.25 MeV 0.06323, 1.5 MeV 0.05754, 2 MeV 0.04942, 3 MeV 0.03969).
constexpr double kWaterAttenuation[kGammaWindows] = {0.05833, 0.05280, 0.04275};
// How far behind a wall's surface the rock is looked up [m]: the hit point itself lies on the boundary.
constexpr double kRockProbe = 0.005;
// The largest dead-time fraction reported (a Poisson draw may exceed T / tau counts).
constexpr double kMaxDeadFraction = 0.999;
const char* const kWindowNames[kGammaWindows] = {"potassium", "uranium", "thorium"};

}  // namespace

std::array<double, kGammaWindows> gammaEmissionPerGram(const geo::Rock& rock) {
  return {rock.potassium * 1e-2 * kPotassiumActivity * kPotassiumYield,
          rock.uranium * 1e-6 * kUraniumActivity * kUraniumYield,
          rock.thorium * 1e-6 * kThoriumActivity * kThoriumYield};
}

std::vector<Eigen::Vector3d> fibonacciSphere(int n) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(static_cast<std::size_t>(std::max(n, 0)));
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    out.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
  }
  return out;
}

GammaCounterSensor::GammaCounterSensor(const sim::SensorSpec& spec, const SensorSetup& setup) : Sensor(spec, setup) {
  SensorParams p(spec, setup.robot);
  const double rays = p.number("rays", 256, 16, 65536, "");
  if (rays != std::floor(rays))
    p.fail("rays", formatNumber(rays), "a whole number in [16, 65536]");
  max_range_ = p.number("max_range", 2.0, 0.05, 100.0, "m");
  area_ = p.number("area", 54.1, 1.0, 1e4, "cm^2");
  const double default_efficiency[kGammaWindows] = {0.20, 0.18, 0.14};
  const double default_background[kGammaWindows] = {0.5, 1.0, 0.1};
  for (int w = 0; w < kGammaWindows; ++w) {
    const std::string name = kWindowNames[w];
    efficiency_[w] = p.number(name + "_efficiency", default_efficiency[w], 0.0, 1.0, "");
    background_[w] = p.number(name + "_background", default_background[w], 0.0, 1e6, "cps");
  }
  continuum_factor_ = p.number("continuum_factor", 4.0, 1.0, 100.0, "");
  dead_time_ = p.number("dead_time", 5e-6, 0.0, 0.01, "s");
  integration_time_ = p.number("integration_time", std::min(1.0, interval()), 1e-3, interval(), "s (at most 1 / rate)");
  const std::vector<double> water =
      p.numbers("water_attenuation", {kWaterAttenuation[0], kWaterAttenuation[1], kWaterAttenuation[2]});
  for (int w = 0; w < kGammaWindows; ++w) {
    if (water[w] < 0.01 || water[w] > 0.2)
      p.fail("water_attenuation", formatNumber(water[w]), "three numbers (K, U, Th lines) each in [0.01, 0.2] cm^2/g");
    water_attenuation_[w] = water[w];
  }
  rock_ratio_ = p.number("rock_attenuation_ratio", 0.90, 0.5, 2.0, "");
  p.finish();
  directions_ = fibonacciSphere(static_cast<int>(rays));
  rays_.resize(directions_.size());
  last_.integration_time = integration_time_;
}

void GammaCounterSensor::onReset() {
  last_ = GammaSample();
  last_.integration_time = integration_time_;
}

std::uint64_t GammaCounterSensor::poisson(double mean) {
  // One draw of the sensor's stream seeds the generator of this count: the stream advances by one whatever the count.
  std::mt19937_64 engine(random().bits());
  if (!(mean > 0.0))
    return 0;
  std::poisson_distribution<std::uint64_t> d(mean);
  return d(engine);
}

void GammaCounterSensor::sample(const SensorContext& ctx) {
  const Eigen::Isometry3d link = ctx.state.pose * spec().pose;
  const Eigen::Vector3d origin = link.translation();
  const Eigen::Matrix3d rotation = link.linear();
  for (std::size_t i = 0; i < rays_.size(); ++i) {
    rays_[i].origin = origin.cast<float>();
    rays_[i].direction = (rotation * directions_[i]).normalized().cast<float>();
    rays_[i].max_range = static_cast<float>(max_range_);
  }
  castRays(ctx, rays_, hits_, raycast::Incidence::skip);

  const sim::WorldConfig& config = ctx.world.config();
  const double rho_water =
      (config.water_column ? config.water_column->densityAt(origin, ctx.world.time()) : ctx.world.water().density) *
      1e-3;                                      // [g/cm^3]
  std::array<double, kGammaWindows> mu_water{};  // [1/m]
  for (int w = 0; w < kGammaWindows; ++w)
    mu_water[w] = water_attenuation_[w] * rho_water * 100.0;

  std::array<double, kGammaWindows> flux{};
  if (config.geology) {
    const double weight = 1.0 / static_cast<double>(rays_.size());
    for (std::size_t i = 0; i < rays_.size(); ++i) {
      const raycast::Hit& h = hits_[i];
      if (h.kind != raycast::HitKind::mesh)
        continue;  // nothing within max_range, or another robot's hull: no rock seen
      const Eigen::Vector3d d = rays_[i].direction.cast<double>();
      const Eigen::Vector3d inside = origin + (static_cast<double>(h.range) + kRockProbe) * d;
      const std::array<double, kGammaWindows> q = gammaEmissionPerGram(config.geology->rockAt(inside));
      for (int w = 0; w < kGammaWindows; ++w)
        if (q[w] > 0.0)
          flux[w] += weight * q[w] / (rock_ratio_ * water_attenuation_[w]) * std::exp(-mu_water[w] * h.range);
    }
  }

  GammaSample& s = last_;
  s.time = ctx.world.time();
  s.integration_time = integration_time_;
  s.flux = flux;
  double sum = 0.0;
  for (int w = 0; w < kGammaWindows; ++w) {
    s.true_rate[w] = area_ * efficiency_[w] * flux[w] + background_[w];
    sum += s.true_rate[w];
  }
  s.true_rate_total = continuum_factor_ * sum;
  const double live = 1.0 / (1.0 + s.true_rate_total * dead_time_);  // m = n / (1 + n tau)
  double windows_mean = 0.0;
  for (int w = 0; w < kGammaWindows; ++w) {
    s.expected_counts[w] = s.true_rate[w] * live * integration_time_;
    windows_mean += s.expected_counts[w];
  }
  s.expected_counts_total = s.true_rate_total * live * integration_time_;
  std::uint64_t total = 0;
  for (int w = 0; w < kGammaWindows; ++w) {
    s.counts[w] = poisson(s.expected_counts[w]);
    total += s.counts[w];
  }
  s.counts_total = total + poisson(std::max(0.0, s.expected_counts_total - windows_mean));

  const double measured_total = static_cast<double>(s.counts_total) / integration_time_;
  s.dead_time_fraction = std::min(measured_total * dead_time_, kMaxDeadFraction);
  const double correction = 1.0 / (1.0 - s.dead_time_fraction);
  s.rate_total = measured_total * correction;
  for (int w = 0; w < kGammaWindows; ++w)
    s.rate[w] = static_cast<double>(s.counts[w]) / integration_time_ * correction;
}

void GammaCounterSensor::describeSample(SampleWriter& out) const {
  out.scalar("integration_time", "s", last_.integration_time);
  out.count("counts_total", last_.counts_total);
  out.count("counts_potassium", last_.counts[kPotassium]);
  out.count("counts_uranium", last_.counts[kUranium]);
  out.count("counts_thorium", last_.counts[kThorium]);
  out.scalar("rate_total", "cps", last_.rate_total);
  out.scalar("rate_potassium", "cps", last_.rate[kPotassium]);
  out.scalar("rate_uranium", "cps", last_.rate[kUranium]);
  out.scalar("rate_thorium", "cps", last_.rate[kThorium]);
  out.scalar("dead_time_fraction", "-", last_.dead_time_fraction);
}

}  // namespace science
}  // namespace sensors
}  // namespace unexmin

// A natural gamma-ray counter (type "gamma_counter", docs/gamma_counter.md): a scintillator of cross-section A that
// counts, over an integration time T, the photopeaks of the three lines of natural radioactivity (40K 1.461 MeV,
// 214Bi 1.764 MeV of the uranium series, 208Tl 2.614 MeV of the thorium series) and a total channel, from the
// uncollided flux of the world's rock walls through the water. Knows no ROS.
//
// Per sample, N rays (a Fibonacci sphere of directions in the sensor frame) leave the detector through the world's
// caster (own hull excluded); a ray hitting a wall within max_range at distance L sees the half-space of the rock
// there (geology rockAt just behind the hit point) and adds, per line w,
//   phi_w += (1/N) q_w / (mu/rho)_rock,w * exp(-mu_water,w L)            [photons / (cm^2 s)]
// with q_w [photons / (g s)] the rock's emission per gram of line w (from its K %, U ppm and Th ppm),
// (mu/rho)_rock,w = rock_attenuation_ratio * (mu/rho)_water,w and mu_water,w = (mu/rho)_water,w * rho_water at the
// detector. (1/N = the ray's solid angle 4 pi / N times the 1/(4 pi) of isotropic emission: over a flat wall at d it
// sums to phi = q / (2 (mu/rho)_rock) E2(mu_water d); in a spherical cavity of radius R to q / (mu/rho)_rock
// exp(-mu_water R).) Only the uncollided flux is modelled (no Compton continuum from the rock).
//
// Count rates [cps]: n_w = A eff_w phi_w + b_w (b_w: background of window w from the water, radon), the total
// n_t = continuum_factor * (n_K + n_U + n_Th); a non-paralysable dead time tau makes the measured mean rates
// m = n / (1 + n_t tau). Counts: Poisson of mean m_w T per window, the total = the windows' counts + a Poisson
// of (m_t - sum m_w) T; four 64-bit draws of the sensor's random stream per sample, whatever the geometry.
// Reported: the counts, the rates corrected for dead time r = (N / T) / (1 - f) with the dead-time fraction
// f = min(N_t tau / T, 0.999).
//
// Parameters (<param name=... value=.../>, all optional):
//   rays                    directions per sample, 16..65536                                  (256)
//   max_range               [m] farthest wall that counts, 0.05..100                          (2)
//   area                    [cm^2] detector cross-section, 1..1e4                             (54.1: a 0.3 L sphere)
//   potassium_efficiency    photopeak efficiency of the K window, 0..1                        (0.20, assumed)
//   uranium_efficiency      photopeak efficiency of the U window, 0..1                        (0.18, assumed)
//   thorium_efficiency      photopeak efficiency of the Th window, 0..1                       (0.14, assumed)
//   potassium_background    [cps] background of the K window, 0..1e6                          (0.5, assumed)
//   uranium_background      [cps] background of the U window (radon daughters), 0..1e6        (1.0, assumed)
//   thorium_background      [cps] background of the Th window, 0..1e6                         (0.1, assumed)
//   continuum_factor        total / sum of the windows' rates, 1..100                         (4, assumed)
//   dead_time               [s] non-paralysable, 0..0.01                                      (5e-6, assumed)
//   integration_time        [s] counting time per sample, 1e-3..1/rate                        (1)
//   water_attenuation       [cm^2/g] (mu/rho) of water at the K, U, Th lines, each 0.01..0.2  (NIST, log-log)
//   rock_attenuation_ratio  (mu/rho)_rock / (mu/rho)_water, 0.5..2                            (0.90: Z/A)
#pragma once

#include <unexmin/geo/rock.h>
#include <unexmin/sensors/sensor.h>

#include <array>
#include <cstdint>
#include <vector>

namespace unexmin {
namespace sensors {
namespace science {

/// The photopeak windows, in the order of every per-window array.
enum GammaWindow { kPotassium = 0, kUranium = 1, kThorium = 2 };
constexpr int kGammaWindows = 3;

/// Photons of each line emitted per gram of `rock` per second [photons / (g s)], in window order: K % x 0.01 x the
/// 40K activity per gram of natural potassium x its 1.461 MeV yield; U ppm x 1e-6 x the 238U activity per gram of
/// natural uranium x the 214Bi 1.764 MeV yield (secular equilibrium); Th ppm x 1e-6 x the 232Th activity per gram of
/// thorium x the 208Tl 2.614 MeV yield per 232Th decay (constants and sources in docs/gamma_counter.md).
std::array<double, kGammaWindows> gammaEmissionPerGram(const geo::Rock& rock);

/// The directions of a Fibonacci sphere of n points (unit, equal solid angles 4 pi / n): point i at
/// z = 1 - (2 i + 1) / n, azimuth i pi (3 - sqrt 5).
std::vector<Eigen::Vector3d> fibonacciSphere(int n);

struct GammaSample {
  double time = 0.0;              ///< [s] end of the integration
  double integration_time = 1.0;  ///< [s]
  std::uint64_t counts_total = 0;
  std::array<std::uint64_t, kGammaWindows> counts{};  ///< per window
  double rate_total = 0.0;                            ///< [cps] corrected for dead time
  std::array<double, kGammaWindows> rate{};           ///< [cps] corrected for dead time
  double dead_time_fraction = 0.0;                    ///< [-] of the integration time
  // The truth behind the counts (not reported by a real counter; for tests and validation):
  std::array<double, kGammaWindows> flux{};             ///< uncollided line flux at the detector [photons/(cm^2 s)]
  std::array<double, kGammaWindows> true_rate{};        ///< n_w [cps] with background, before dead time
  double true_rate_total = 0.0;                         ///< n_t [cps] before dead time
  std::array<double, kGammaWindows> expected_counts{};  ///< m_w T, the Poisson means
  double expected_counts_total = 0.0;                   ///< m_t T
};

class GammaCounterSensor : public Sensor {
public:
  /// Throws ConfigError naming the robot, the sensor, the parameter, its value and range.
  GammaCounterSensor(const sim::SensorSpec& spec, const SensorSetup& setup);

  const GammaSample& last() const { return last_; }
  double area() const { return area_; }  ///< [cm^2]
  const std::array<double, kGammaWindows>& efficiency() const { return efficiency_; }
  double deadTime() const { return dead_time_; }  ///< [s]

protected:
  void onReset() override;
  void sample(const SensorContext& ctx) override;
  void describeSample(SampleWriter& out) const override;

private:
  /// Draws one Poisson count of `mean` from one 64-bit draw of the sensor's stream.
  std::uint64_t poisson(double mean);

  std::vector<Eigen::Vector3d> directions_;  ///< sensor frame, unit
  double max_range_ = 2.0;                   ///< [m]
  double area_ = 54.1;                       ///< [cm^2]
  std::array<double, kGammaWindows> efficiency_{};
  std::array<double, kGammaWindows> background_{};  ///< [cps]
  double continuum_factor_ = 4.0;
  double dead_time_ = 5e-6;                                ///< [s]
  double integration_time_ = 1.0;                          ///< [s]
  std::array<double, kGammaWindows> water_attenuation_{};  ///< (mu/rho) [cm^2/g]
  double rock_ratio_ = 0.9;
  std::vector<raycast::Ray> rays_;
  std::vector<raycast::Hit> hits_;
  GammaSample last_;
};

}  // namespace science
}  // namespace sensors
}  // namespace unexmin

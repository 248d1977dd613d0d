// Echo model of an imaging sonar ping (the MSIS, docs/sonars.md "Echo model"): turns the returns of the
// rays of one beam fan into one line of range bins by the sonar equation, summed per bin as echo power (the
// thesis's "area density" of hits, section 5.4.1, with the physics in decibels), then receiver gain,
// time-varied gain and 8-bit quantisation like the Micron DST's output. Per ray j (echo level, dB re 1 uPa):
//
//   EL_j = SL - 2 TL(r_j) + BS(theta_j) + 10 log10(A_j) + X_j
//   TL(r) = 20 log10(r / 1 m) + alpha r              one-way spherical spreading and absorption alpha [dB/m]
//   BS(theta) = BS0 + 10 log10(cos(theta)^n)         backscatter strength of the surface at incidence theta
//   A_j = r_j^2 (Omega / N) / cos(theta_j)           footprint of the ray (solid angle Omega / N of the beam's
//                                                    Omega over its N rays) on the surface [m^2]
//   X_j                                              extra level of the echo (a surface-multipath ghost's
//                                                    reflection loss, the water surface's own backscatter)
//
// Bin i sums the echo power P_i = sum 10^(EL_j / 10) [uPa^2] of the rays whose range falls in it, plus the
// noise power the sensor adds; its output level and 8-bit code are
//
//   L_i = 10 log10(P_i) + G + TVG(r_i)      G = gain * gain_span [dB],  TVG(r) = k log10(r / 1 m) + 2 alpha r
//   q_i = clamp(round((L_i - display_min) / display_span * levels), 0, levels),   I_i = q_i / levels in [0, 1]
//
// Bins: nbins equal bins from range_min to range_max, bin i = [range_min + i w, range_min + (i + 1) w),
// w = (range_max - range_min) / nbins; its point (and r_i) is the bin centre. Knows no ROS.
#pragma once

#include <unexmin/core/error.h>

#include <cstddef>
#include <vector>

namespace unexmin {
namespace sensors {
namespace sonar {

struct EchoParams {
  double range_min = 0.3;               ///< start of the first bin [m] >= 0
  double range_max = 3.0;               ///< end of the last bin [m] > range_min
  int nbins = 400;                      ///< bins per line [-] >= 1
  double gain = 0.2;                    ///< receiver gain, 0 (lowest) .. 1 (highest) [-]
  double gain_span = 40.0;              ///< gain_span * gain = G [dB]
  double source_level = 200.0;          ///< SL [dB re 1 uPa at 1 m]
  double backscatter_strength = -20.0;  ///< BS0 at normal incidence [dB]
  double backscatter_exponent = 2.0;    ///< n of cos(theta)^n [-]
  double absorption = 0.1;              ///< alpha, one way [dB/m] >= 0
  double beam_solid_angle = 0.0315;     ///< Omega of the fan [sr] > 0 (3 x 35 deg)
  double tvg_spreading = 20.0;          ///< k of the time-varied gain k log10(r) [dB per decade]
  double display_min = 125.0;           ///< output level of code 0 [dB re 1 uPa]
  double display_span = 80.0;           ///< output levels over the codes 0 .. levels [dB]
  int levels = 255;                     ///< highest code (8 bits: 255) >= 1
};

/// One ray's echo: where it hit and how.
struct Echo {
  double range = 0.0;          ///< [m]
  double cos_incidence = 1.0;  ///< cos(theta), 0 (grazing) .. 1 (head-on) [-]
  double extra = 0.0;          ///< X: added to the echo level [dB]
};

class EchoModel {
public:
  /// Throws ParameterError naming the figure when a parameter is out of its range.
  explicit EchoModel(const EchoParams& params);

  const EchoParams& params() const { return p_; }
  double binWidth() const { return width_; }  ///< [m]
  double binCenter(std::size_t i) const;      ///< [m]
  /// Bin of range r [m]; -1 outside [range_min, range_max).
  int bin(double r) const;
  double gainDb() const { return p_.gain * p_.gain_span; }  ///< G [dB]
  /// One-way transmission loss TL(r) = 20 log10(r) + alpha r [dB] (r >= 1 mm).
  double transmissionLoss(double r) const;
  /// Time-varied gain TVG(r) = k log10(r) + 2 alpha r [dB] (r >= 1 mm).
  double tvg(double r) const;
  /// Echo level EL of one ray of a fan of `rays` [dB re 1 uPa]; -inf for a grazing (cos <= 0) ray.
  double echoLevel(const Echo& e, std::size_t rays) const;
  /// Echo power of one ray, 10^(EL / 10) [uPa^2].
  double strength(const Echo& e, std::size_t rays) const;
  /// Whether strength(e, rays) >= power [uPa^2] (a detection), mostly without the absorption's exponential: the
  /// strength with the absorption over the whole window (range_max) is a lower bound of it.
  bool reaches(const Echo& e, std::size_t rays, double power) const;
  /// Output level L of a bin of power P [uPa^2] at range r [m] [dB re 1 uPa] (-inf for P = 0).
  double outputLevel(double power, double r) const;
  /// Input power [uPa^2] whose output level at range r is L [dB re 1 uPa] (the inverse of outputLevel).
  double inputPower(double level, double r) const;
  /// Code / levels in [0, 1] of an output level L [dB re 1 uPa].
  float quantise(double level) const;
  /// Output level of one quantisation step [dB].
  double step() const { return p_.display_span / p_.levels; }
  /// The code (0 .. levels) of a power P [uPa^2] in bin i: the same as quantise(outputLevel(P, r_i)), by the
  /// bin's precomputed gain and the code thresholds (no logarithm).
  int code(double power, std::size_t i) const;
  /// The code of one echo alone, at its own range (gain and TVG at r, not at a bin centre): the M3's return.
  int echoCode(const Echo& e, std::size_t rays) const;
  /// The least power [uPa^2] in bin i with a code >= q (1 .. levels).
  double codePower(int q, std::size_t i) const { return thresholds_[q - 1] / bin_gain_[i]; }

  /// Adds the power of every echo to the bin of its range (the area density), then gain, TVG and quantisation:
  /// `line` (resized to nbins) is the intensity line in [0, 1]. `rays`: rays in the fan.
  void line(const std::vector<Echo>& echoes, std::size_t rays, std::vector<float>& line) const;

  /// Ground-artifact filling (thesis: "echoes between these artifacts"): the power of a ray is spread
  /// evenly over the bins between its range and each of its neighbours' (half towards each neighbour that
  /// hit within `max_gap` [m]; the half of a missing or farther neighbour stays in the ray's own bin). Total
  /// power is preserved. `column`: the echoes of one column of the fan in elevation order, a negative range
  /// for a ray with no echo. Adds into `energy` (nbins) [uPa^2]. `scale` as deposit()'s.
  void spread(const std::vector<Echo>& column, std::size_t rays, double max_gap, std::vector<double>& energy,
              double scale = 1.0) const;
  /// Adds one echo's power to its bin of `energy` (nbins); nothing outside the window. `scale` [-]: the echo's range
  /// as the sonar times it is its range (the path, which sets its power) x scale, the configured over the water's
  /// sound speed (sensors::apparentRangeFactor); the echo goes to the bin of that range.
  void deposit(const Echo& e, std::size_t rays, std::vector<double>& energy, double scale = 1.0) const;
  /// Gain, TVG and quantisation: power per bin (nbins) [uPa^2] -> intensity line in [0, 1].
  void finish(const std::vector<double>& energy, std::vector<float>& line) const;

private:
  /// cos^n / cos: backscatter times footprint (cos bounded >= 1e-3 below).
  double incidence(double c) const;
  /// strength() before absorption and the extra level X: SL BS0 Omega / N cos^(n - 1) r^-2 (0 at grazing or
  /// behind); r = the echo's range, at least 1 mm.
  double strengthWithoutAbsorption(const Echo& e, std::size_t rays, double& r) const;
  /// Adds `amount` spread evenly over the range interval [a, b] (clipped to the window).
  void spreadOver(double a, double b, double amount, std::vector<double>& energy) const;

  EchoParams p_;
  double width_ = 0.0;
  double ray_factor_ = 0.0;         ///< 10^((SL + BS0) / 10) Omega [uPa^2 m^2 sr]
  double gain_ = 1.0;               ///< 10^(G / 10)
  double least_absorption_ = 1.0;   ///< the two-way absorption factor at range_max
  std::vector<double> bin_gain_;    ///< per bin: 10^((G + TVG(r_i)) / 10)
  std::vector<double> thresholds_;  ///< code k >= 1 from 10^((display_min + (k - 1/2) step) / 10) on
};

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

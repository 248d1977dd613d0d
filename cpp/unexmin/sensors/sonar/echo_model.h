// Echo model of an imaging sonar ping (the MSIS, docs/sonars.md "Echo model"): turns the returns of the
// rays of one beam fan into one line of range bins, the thesis's "area density" method (section 5.4.1)
// with the physics it left out. The intensity of bin i is
//
//   I_i = min(1, A * sum over the rays j whose echo falls in bin i of  w_j * cos(theta_j)^n * L(r_j))
//
//   w_j = 1 / (rays in the fan)        the density of hits per range bin (fraction of the beam returning)
//   cos(theta_j)^n                     backscatter at incidence theta_j (Lambert's law: n = 2)
//   L(r) = (r_ref / r)^s * 10^(-2 alpha r / 10)
//                                      spreading (exponent s, relative to r_ref) and two-way absorption
//                                      alpha [dB/m] over the range r [m]
//   A = 10^(G gain / 10)               receiver gain: gain in [0, 1] over a span of G [dB]
//
// Bins: nbins equal bins from range_min to range_max, bin i = [range_min + i w, range_min + (i + 1) w),
// w = (range_max - range_min) / nbins; its point is at the bin centre. Knows no ROS.
#pragma once

#include <unexmin/core/error.h>

#include <cstddef>
#include <vector>

namespace unexmin {
namespace sonar {

struct EchoParams
{
  double range_min = 0.3;             ///< start of the first bin [m] >= 0
  double range_max = 3.0;             ///< end of the last bin [m] > range_min
  int nbins = 400;                    ///< bins per line [-] >= 1
  double gain = 0.2;                  ///< receiver gain, 0 (lowest) .. 1 (highest) [-]
  double gain_span = 40.0;            ///< G: amplification at gain 1 [dB]
  double backscatter_exponent = 2.0;  ///< n of cos(theta)^n [-]
  double spreading_exponent = 2.0;    ///< s [-]
  double reference_range = 1.0;       ///< r_ref: range of no spreading loss [m] > 0
  double absorption = 0.1;            ///< alpha, one way [dB/m] >= 0
};

/// One ray's echo: where it hit and how.
struct Echo
{
  double range = 0.0;          ///< [m]
  double cos_incidence = 1.0;  ///< cos(theta), 0 (grazing) .. 1 (head-on) [-]
};

class EchoModel
{
public:
  /// Throws ParameterError naming the figure when a parameter is out of its range.
  explicit EchoModel(const EchoParams& params);

  const EchoParams& params() const { return p_; }
  double binWidth() const { return width_; }                        ///< [m]
  double binCenter(std::size_t i) const;                            ///< [m]
  /// Bin of range r [m]; -1 outside [range_min, range_max).
  int bin(double r) const;
  double amplification() const { return amplification_; }          ///< A [-]
  /// Spreading and absorption factor L(r) [-].
  double loss(double r) const;
  /// Echo strength of one ray before the gain: w cos(theta)^n L(r) [-] (w = 1 / rays).
  double strength(const Echo& e, std::size_t rays) const;

  /// Adds the strength of every echo to the bin of its range (the area density), then applies the gain and
  /// saturates: `line` (resized to nbins) is the intensity line in [0, 1]. `rays`: rays in the fan (w).
  void line(const std::vector<Echo>& echoes, std::size_t rays, std::vector<float>& line) const;

  /// Ground-artifact filling (thesis: "echoes between these artifacts"): the strength of a ray is spread
  /// evenly over the bins between its range and each of its neighbours' (half towards each neighbour that
  /// hit within `max_gap` [m]; the half of a missing or farther neighbour stays in the ray's own bin). Total
  /// strength is preserved. `column`: the echoes of one column of the fan in elevation order, a negative range
  /// for a ray with no echo. Adds (before the gain) into `energy` (nbins).
  void spread(const std::vector<Echo>& column, std::size_t rays, double max_gap, std::vector<double>& energy) const;
  /// Adds one echo's strength to its bin of `energy` (nbins); nothing outside the window.
  void deposit(const Echo& e, std::size_t rays, std::vector<double>& energy) const;
  /// Gain and saturation: energy (nbins) -> intensity line in [0, 1].
  void finish(const std::vector<double>& energy, std::vector<float>& line) const;

private:
  /// Adds `amount` spread evenly over the range interval [a, b] (clipped to the window).
  void spreadOver(double a, double b, double amount, std::vector<double>& energy) const;

  EchoParams p_;
  double width_ = 0.0;
  double amplification_ = 1.0;
};

}  // namespace sonar
}  // namespace unexmin

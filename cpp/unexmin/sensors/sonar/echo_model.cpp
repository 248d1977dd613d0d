#include <unexmin/sensors/sonar/echo_model.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace unexmin {
namespace sensors {
namespace sonar {
namespace {

void check(bool ok, const char* name, double value, const char* expected) {
  if (ok)
    return;
  throw ParameterError(std::string("echo model: ") + name + " = " + formatNumber(value) + ": expected " + expected);
}

}  // namespace

EchoModel::EchoModel(const EchoParams& params) : p_(params) {
  check(std::isfinite(p_.range_min) && p_.range_min >= 0.0, "range_min", p_.range_min, ">= 0 m");
  check(std::isfinite(p_.range_max) && p_.range_max > p_.range_min, "range_max", p_.range_max, "> range_min");
  check(p_.nbins >= 1, "nbins", p_.nbins, ">= 1");
  check(p_.gain >= 0.0 && p_.gain <= 1.0, "gain", p_.gain, "in [0, 1]");
  check(p_.gain_span >= 0.0 && p_.gain_span <= 120.0, "gain_span", p_.gain_span, "in [0, 120] dB");
  check(p_.source_level >= 100.0 && p_.source_level <= 260.0, "source_level", p_.source_level,
        "in [100, 260] dB re 1 uPa at 1 m");
  check(p_.backscatter_strength >= -100.0 && p_.backscatter_strength <= 0.0, "backscatter_strength",
        p_.backscatter_strength, "in [-100, 0] dB");
  check(p_.backscatter_exponent >= 0.0 && p_.backscatter_exponent <= 10.0, "backscatter_exponent",
        p_.backscatter_exponent, "in [0, 10]");
  check(p_.absorption >= 0.0 && p_.absorption <= 10.0, "absorption", p_.absorption, "in [0, 10] dB/m");
  check(p_.beam_solid_angle > 0.0 && p_.beam_solid_angle <= 4.0 * M_PI, "beam_solid_angle", p_.beam_solid_angle,
        "in (0, 4 pi] sr");
  check(p_.tvg_spreading >= 0.0 && p_.tvg_spreading <= 60.0, "tvg_spreading", p_.tvg_spreading,
        "in [0, 60] dB per decade");
  check(std::isfinite(p_.display_min), "display_min", p_.display_min, "a finite level in dB re 1 uPa");
  check(p_.display_span > 0.0 && p_.display_span <= 200.0, "display_span", p_.display_span, "in (0, 200] dB");
  check(p_.levels >= 1 && p_.levels <= 65535, "levels", p_.levels, "in [1, 65535]");
  width_ = (p_.range_max - p_.range_min) / p_.nbins;
  ray_factor_ = std::pow(10.0, (p_.source_level + p_.backscatter_strength) / 10.0) * p_.beam_solid_angle;
  gain_ = std::pow(10.0, gainDb() / 10.0);
  least_absorption_ = std::exp(-0.2 * M_LN10 * p_.absorption * std::max(p_.range_max, 1e-3));
  bin_gain_.resize(p_.nbins);
  for (int i = 0; i < p_.nbins; ++i)
    bin_gain_[i] = std::pow(10.0, (gainDb() + tvg(binCenter(i))) / 10.0);
  thresholds_.resize(p_.levels);
  for (int k = 1; k <= p_.levels; ++k)
    thresholds_[k - 1] = std::pow(10.0, (p_.display_min + (k - 0.5) * step()) / 10.0);
}

double EchoModel::binCenter(std::size_t i) const {
  return p_.range_min + (static_cast<double>(i) + 0.5) * width_;
}

int EchoModel::bin(double r) const {
  if (!(r >= p_.range_min) || !(r < p_.range_max))
    return -1;
  return std::min(p_.nbins - 1, static_cast<int>((r - p_.range_min) / width_));
}

double EchoModel::transmissionLoss(double r) const {
  r = std::max(r, 1e-3);
  return 20.0 * std::log10(r) + p_.absorption * r;
}

double EchoModel::tvg(double r) const {
  r = std::max(r, 1e-3);
  return p_.tvg_spreading * std::log10(r) + 2.0 * p_.absorption * r;
}

double EchoModel::echoLevel(const Echo& e, std::size_t rays) const {
  const double c = std::min(1.0, e.cos_incidence);
  if (!(c > 0.0))
    return -std::numeric_limits<double>::infinity();
  const double r = std::max(e.range, 1e-3);
  const double ray_solid_angle = p_.beam_solid_angle / static_cast<double>(std::max<std::size_t>(1, rays));
  const double area = r * r * ray_solid_angle / std::max(c, 1e-3);  // the footprint, bounded at grazing
  return p_.source_level - 2.0 * transmissionLoss(r) + p_.backscatter_strength +
         10.0 * p_.backscatter_exponent * std::log10(c) + 10.0 * std::log10(area) + e.extra;
}

double EchoModel::strengthWithoutAbsorption(const Echo& e, std::size_t rays, double& r) const {
  const double c = std::min(1.0, e.cos_incidence);
  r = std::max(e.range, 1e-3);
  if (!(c > 0.0))
    return 0.0;
  return ray_factor_ / static_cast<double>(std::max<std::size_t>(1, rays)) * incidence(c) / (r * r);
}

double EchoModel::strength(const Echo& e, std::size_t rays) const {
  // echoLevel in linear form: SL BS0 Omega / N  cos^(n - 1)  r^-2  10^(-2 alpha r / 10)  10^(X / 10).
  double r;
  const double s = strengthWithoutAbsorption(e, rays, r);
  if (!(s > 0.0))
    return 0.0;
  const double extra = e.extra == 0.0 ? 1.0 : std::pow(10.0, e.extra / 10.0);
  return s * std::exp(-0.2 * M_LN10 * p_.absorption * r) * extra;
}

bool EchoModel::reaches(const Echo& e, std::size_t rays, double power) const {
  double r;
  const double s = strengthWithoutAbsorption(e, rays, r);
  if (!(s > 0.0))
    return false;
  const double extra = e.extra == 0.0 ? 1.0 : std::pow(10.0, e.extra / 10.0);
  const double lossless = s * extra;
  if (lossless < power)
    return false;  // below it even without absorption
  if (r <= p_.range_max && lossless * least_absorption_ >= power)
    return true;  // above it with the most absorption
  return strength(e, rays) >= power;
}

double EchoModel::incidence(double c) const {
  const double n = p_.backscatter_exponent;
  return (n == 2.0 ? c * c : std::pow(c, n)) / std::max(c, 1e-3);  // Lambert's n = 2 without pow
}

int EchoModel::echoCode(const Echo& e, std::size_t rays) const {
  // strength x 10^((G + TVG(r)) / 10) at the echo's own range: the absorption cancels, the spreading leaves
  // r^(k / 10 - 2) (1 for the default k = 20).
  const double c = std::min(1.0, e.cos_incidence);
  if (!(c > 0.0))
    return 0;
  const double r = std::max(e.range, 1e-3);
  const double spreading = p_.tvg_spreading == 20.0 ? 1.0 : std::pow(r, p_.tvg_spreading / 10.0 - 2.0);
  const double extra = e.extra == 0.0 ? 1.0 : std::pow(10.0, e.extra / 10.0);
  const double out =
      ray_factor_ / static_cast<double>(std::max<std::size_t>(1, rays)) * incidence(c) * spreading * gain_ * extra;
  return static_cast<int>(std::upper_bound(thresholds_.begin(), thresholds_.end(), out) - thresholds_.begin());
}

int EchoModel::code(double power, std::size_t i) const {
  if (!(power > 0.0))
    return 0;
  return static_cast<int>(std::upper_bound(thresholds_.begin(), thresholds_.end(), power * bin_gain_[i]) -
                          thresholds_.begin());
}

double EchoModel::outputLevel(double power, double r) const {
  if (!(power > 0.0))
    return -std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(power) + gainDb() + tvg(r);
}

double EchoModel::inputPower(double level, double r) const {
  return std::pow(10.0, (level - gainDb() - tvg(r)) / 10.0);
}

float EchoModel::quantise(double level) const {
  if (!(level > p_.display_min))
    return 0.0f;
  const double q = std::min<double>(p_.levels, std::round((level - p_.display_min) / p_.display_span * p_.levels));
  return static_cast<float>(q / p_.levels);  // as finish(): code / levels
}

void EchoModel::deposit(const Echo& e, std::size_t rays, std::vector<double>& energy, double scale) const {
  const int b = bin(scale == 1.0 ? e.range : scale * e.range);
  if (b >= 0)
    energy[b] += strength(e, rays);
}

void EchoModel::spreadOver(double a, double b, double amount, std::vector<double>& energy) const {
  if (a > b)
    std::swap(a, b);
  if (b - a < 1e-9 * width_) {  // a point
    const int i = bin(a);
    if (i >= 0)
      energy[i] += amount;
    return;
  }
  // Even spread over [a, b]: each bin gets the share of the interval it covers; outside the window is lost.
  const double density = amount / (b - a);
  const int lo = std::max(0, static_cast<int>(std::floor((a - p_.range_min) / width_)));
  const int hi = std::min(p_.nbins - 1, static_cast<int>(std::floor((b - p_.range_min) / width_)));
  for (int i = lo; i <= hi; ++i) {
    const double b0 = p_.range_min + i * width_, b1 = b0 + width_;
    const double overlap = std::min(b, b1) - std::max(a, b0);
    if (overlap > 0.0)
      energy[i] += density * overlap;
  }
}

void EchoModel::spread(const std::vector<Echo>& column, std::size_t rays, double max_gap, std::vector<double>& energy,
                       double scale) const {
  const auto timed = [scale](double r) { return scale == 1.0 ? r : scale * r; };  // the range the sonar bins
  const std::size_t n = column.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Echo& e = column[k];
    if (e.range < 0.0)
      continue;
    const double s = strength(e, rays);
    for (int side : {-1, 1}) {
      const long j = static_cast<long>(k) + side;
      const bool paired = j >= 0 && j < static_cast<long>(n) && column[j].range >= 0.0 &&
                          std::abs(column[j].range - e.range) <= max_gap;
      // Towards the neighbour: half the way (the neighbour fills the other half).
      if (paired)
        spreadOver(timed(e.range), timed(0.5 * (e.range + column[j].range)), 0.5 * s, energy);
      else {
        const int b = bin(timed(e.range));
        if (b >= 0)
          energy[b] += 0.5 * s;
      }
    }
  }
}

void EchoModel::finish(const std::vector<double>& energy, std::vector<float>& line) const {
  line.resize(p_.nbins);
  for (int i = 0; i < p_.nbins; ++i)
    line[i] = static_cast<float>(static_cast<double>(code(energy[i], i)) / p_.levels);
}

void EchoModel::line(const std::vector<Echo>& echoes, std::size_t rays, std::vector<float>& out) const {
  std::vector<double> energy(p_.nbins, 0.0);
  for (const Echo& e : echoes)
    deposit(e, rays, energy);
  finish(energy, out);
}

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

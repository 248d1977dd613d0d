#include <unexmin/sensors/sonar/beam_receiver.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace sensors {
namespace sonar {
namespace {

EchoParams eightBit(EchoParams p) {
  p.levels = 255;
  return p;
}

}  // namespace

int wholeNumber(SensorParams& p, const std::string& key, double fallback, double lo, double hi) {
  const double v = p.number(key, fallback, lo, hi, "(whole number)");
  if (v != std::floor(v))
    p.fail(key, formatNumber(v), "a whole number");
  return static_cast<int>(v);
}

BeamReceiver BeamReceiver::read(SensorParams& p, const ReceiverDefaults& defaults, double rate,
                                double beam_solid_angle) {
  EchoParams e;
  e.range_min = p.number("range_min", 0.1, 0.0, 1000.0, "m");
  e.range_max = p.number("range_max", defaults.range_max, 0.0, 1000.0, "m");
  if (!(e.range_max > e.range_min))
    p.fail("range_max", formatNumber(e.range_max), "more than range_min");
  e.nbins = wholeNumber(p, "nbins", defaults.nbins, 1.0, 10000.0);
  e.gain = p.number("gain", 0.5, 0.0, 1.0, "(0 low .. 1 high)");
  readEquationParams(p, e, defaults.source_level);
  e.beam_solid_angle = beam_solid_angle;
  ReceiverNoise noise;
  const bool noisy = p.text("noise", "gaussian", {"gaussian", "none"}) == "gaussian";
  noise.speckle = p.flag("speckle", true) && noisy;
  noise.noise_floor = p.flag("noise_floor", true) && noisy;
  noise.noise_level = p.number("noise_level", defaults.noise_level, 0.0, 300.0, "dB re 1 uPa");
  const double sound_speed = p.number("sound_speed", 1500.0, 1300.0, 1700.0, "m/s");
  const double max_rate = sound_speed / (2.0 * e.range_max);  // the echo from range_max is back before the next ping
  if (rate > max_rate * (1.0 + 1e-9))
    p.fail("rate", formatNumber(rate), "at most sound_speed / (2 range_max) = " + formatNumber(max_rate) + " Hz");
  return BeamReceiver(e, noise);
}

BeamReceiver::BeamReceiver(EchoParams params, const ReceiverNoise& noise)
    : echo_(eightBit(params)), noise_(noise), noise_power_(std::pow(10.0, noise.noise_level / 10.0)) {
  const int n = echo_.params().nbins;
  visible_.resize(n);
  // Noise power E x noise_power (E exponential, mean 1) reaches code 1 when E >= codePower(1) / noise_power, that
  // is when the draw u (E = -ln(1 - u)) is at least 1 - exp(-codePower(1) / noise_power).
  for (int i = 0; i < n; ++i)
    visible_[i] = -std::expm1(-echo_.codePower(1, i) / noise_power_);
  offset_.resize(n);
  for (int i = 0; i < n; ++i)
    offset_[i] = static_cast<float>((echo_.gainDb() + echo_.tvg(echo_.binCenter(i)) - echo_.params().display_min) /
                                    echo_.step());
}

void BeamReceiver::add(const Echo& e, double extent, std::size_t rays, std::vector<double>& energy) const {
  const double power = echo_.strength(e, rays);
  if (!(power > 0.0))
    return;
  const EchoParams& p = echo_.params();
  const double w = echo_.binWidth();
  if (!(extent > 1e-9 * w)) {
    const int b = echo_.bin(e.range);
    if (b >= 0)
      energy[b] += power;
    return;
  }
  // In bin units: the footprint covers [x0, x1); bin i covers [i, i + 1).
  const double x0 = (e.range - 0.5 * extent - p.range_min) / w;
  const double x1 = x0 + extent / w;
  const double per_bin = power * w / extent;
  const int first = std::max(0, static_cast<int>(std::floor(x0)));
  const int last = std::min(p.nbins, static_cast<int>(std::ceil(x1)));
  for (int i = first; i < last; ++i) {
    const double covered = std::min(x1, i + 1.0) - std::max(x0, static_cast<double>(i));
    energy[i] += per_bin * covered;
  }
}

void BeamReceiver::receive(std::vector<double>& energy, Random& random, std::uint8_t* codes, std::size_t stride) const {
  // q = round((10 log10(P) + G + TVG(r_i) - display_min) / step), 0 .. 255: the echo model's code, in single precision
  // (an 8-bit output) without its search over the code thresholds.
  const float codes_per_bel = static_cast<float>(10.0 / echo_.step());
  const float unit = 1.0f / 16777216.0f;  // 2^-24
  const std::size_t n = energy.size();
  for (std::size_t i = 0; i < n; ++i) {
    double power = energy[i];
    const std::uint64_t bits = random.bits();
    const float u_speckle = static_cast<float>(bits >> 40) * unit;
    const float u_noise = static_cast<float>((bits >> 16) & 0xffffffu) * unit;
    if (noise_.speckle && power > 0.0)
      power *= -std::log1p(-u_speckle);
    if (noise_.noise_floor && (power > 0.0 || u_noise >= visible_[i]))
      power += noise_power_ * -std::log1p(-u_noise);
    float q = 0.0f;
    if (power > 0.0)
      q = std::min(255.0f, std::max(0.0f, std::floor(codes_per_bel * std::log10(static_cast<float>(power)) +
                                                     offset_[i] + 0.5f)));
    codes[i * stride] = static_cast<std::uint8_t>(q);
  }
}

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

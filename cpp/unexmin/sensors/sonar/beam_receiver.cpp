#include <unexmin/sensors/sonar/beam_receiver.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace unexmin {
namespace sensors {
namespace sonar {
namespace {

EchoParams eightBit(EchoParams p) {
  p.levels = 255;
  return p;
}

/// log2(x) for a float x > 0, within 3e-6 relative: x = 2^e m with m in [sqrt(1/2), sqrt(2)) from the bits, and
/// log2(m) = t p(t), t = m - 1, p a degree-6 polynomial fitted to log2(1 + t) / t on that interval. No branch and no
/// library call (the receiver takes two or three logarithms per bin). Zero or a subnormal gives about -127.
inline float fastLog2(float x) {
  std::uint32_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const std::int32_t e = static_cast<std::int32_t>(bits - 0x3f3504f3u) >> 23;  // 0x3f3504f3: sqrt(1/2)
  bits -= static_cast<std::uint32_t>(e) << 23;
  float m;
  std::memcpy(&m, &bits, sizeof m);
  const float t = m - 1.0f;
  const float p =
      1.44269609f +
      t * (-0.72135812f +
           t * (0.480676174f + t * (-0.359656751f + t * (0.295109302f + t * (-0.26626122f + t * 0.170013204f)))));
  return static_cast<float>(e) + t * p;
}

/// An exponential draw of mean 1, -ln(u), from u in (0, 1).
inline float exponential(float u) {
  return -0.693147181f * fastLog2(u);
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
  const SoundSpeed sound_speed = SoundSpeed::read(p);
  const double max_rate =
      sound_speed.configured / (2.0 * e.range_max);  // the echo from range_max is back before the next ping
  if (rate > max_rate * (1.0 + 1e-9))
    p.fail("rate", formatNumber(rate), "at most sound_speed / (2 range_max) = " + formatNumber(max_rate) + " Hz");
  BeamReceiver receiver(e, noise);
  receiver.sound_speed_ = sound_speed;
  return receiver;
}

BeamReceiver::BeamReceiver(EchoParams params, const ReceiverNoise& noise)
    : echo_(eightBit(params)), noise_(noise), noise_power_(std::pow(10.0, noise.noise_level / 10.0)) {
  const int n = echo_.params().nbins;
  // Noise power E x noise_power (E exponential, mean 1) reaches code 1 when E >= t_i = codePower(1) / noise_power,
  // with probability exp(-t_i).
  visible_.resize(n);
  for (int i = 0; i < n; ++i)
    visible_[i] = static_cast<float>(std::exp(-echo_.codePower(1, i) / noise_power_));
  const int block = static_cast<int>(kBlock);
  for (int b = 0; b < n; b += block) {
    const double p = *std::max_element(visible_.begin() + b, visible_.begin() + std::min(n, b + block));
    block_visible_.push_back(p);
    block_log_miss_.push_back(std::log1p(-p));
  }
  codes_per_log2_ = static_cast<float>(10.0 * std::log10(2.0) / echo_.step());
  log2_noise_power_ = static_cast<float>(std::log2(noise_power_));
  offset_.resize(n);
  for (int i = 0; i < n; ++i)
    offset_[i] = static_cast<float>((echo_.gainDb() + echo_.tvg(echo_.binCenter(i)) - echo_.params().display_min) /
                                    echo_.step());
}

void BeamReceiver::add(const Echo& e, double extent, std::size_t rays, double scale,
                       std::vector<double>& energy) const {
  const double power = echo_.strength(e, rays);  // at the path
  if (!(power > 0.0))
    return;
  const EchoParams& p = echo_.params();
  const double w = echo_.binWidth();
  // the ranges the sonar times (no arithmetic at scale 1: without a water column the bins are the paths')
  const double range = scale == 1.0 ? e.range : scale * e.range;
  const double span = scale == 1.0 ? extent : scale * extent;
  if (!(span > 1e-9 * w)) {
    const int b = echo_.bin(range);
    if (b >= 0)
      energy[b] += power;
    return;
  }
  // In bin units: the footprint covers [x0, x1); bin i covers [i, i + 1).
  const double x0 = (range - 0.5 * span - p.range_min) / w;
  const double x1 = x0 + span / w;
  const double per_bin = power * w / span;
  const int first = std::max(0, static_cast<int>(std::floor(x0)));
  const int last = std::min(p.nbins, static_cast<int>(std::ceil(x1)));
  for (int i = first; i < last; ++i) {
    const double covered = std::min(x1, i + 1.0) - std::max(x0, static_cast<double>(i));
    energy[i] += per_bin * covered;
  }
}

inline std::uint8_t BeamReceiver::code(double power, std::size_t i) const {
  // q = round((10 log10(P) + G + TVG(r_i) - display_min) / step), 0 .. 255: the echo model's code, in single precision
  // (an 8-bit output) without its search over the code thresholds.
  const float q = codes_per_log2_ * fastLog2(static_cast<float>(power)) + offset_[i] + 0.5f;
  return static_cast<std::uint8_t>(std::min(255.0f, std::max(0.0f, q)));  // truncation: floor of q >= 0
}

void BeamReceiver::receive(std::vector<double>& energy, const CounterRandom& random, std::uint8_t* codes,
                           std::size_t stride) const {
  const float unit = 1.0f / 16777216.0f;           // 2^-24
  const double unit53 = 1.0 / 9007199254740992.0;  // 2^-53
  const std::size_t n = energy.size();
  // Draws 0 .. n - 1: bin i's with an echo; n .. n + ceil(n / 2) - 1: two bins' noise alone each (bins 2h and 2h + 1
  // from draw n + h, its upper and lower 32-bit halves); after them, the sparse noise's.
  std::uint64_t next = n + (n + 1) / 2;
  for (std::size_t b = 0, i0 = 0; i0 < n; ++b, i0 += kBlock) {
    const std::size_t m = std::min(kBlock, n - i0);
    std::uint8_t q[kBlock];
    // The noise alone in every bin of the block (the echo bins' codes replace theirs below). It shows (code >= 1) with
    // probability visible_[i]: a uniform draw w is kept when w < visible_[i], and then -ln(w) is an exponential draw
    // given that it exceeds -ln(visible_[i]), the noise's power in units of noise_power. With p the block's largest
    // visible_: where p is small, only candidates at geometric gaps of parameter p (two draws each), each with w
    // uniform in [0, p) (kept with probability visible_[i] / p); elsewhere every bin draws w in [0, 1) from its own
    // draw.
    const double p = noise_.noise_floor ? block_visible_[b] : 0.0;
    if (p > kDense) {
      // The draws, then every bin's code without a branch (vectorisable). i0 is even (kBlock is).
      float w[kBlock];
      for (std::size_t j = 0; j < m; j += 2) {
        const std::uint64_t bits = random.bits(n + (i0 + j) / 2);
        w[j] = (static_cast<float>(bits >> 40) + 0.5f) * unit;
        w[j + 1] = (static_cast<float>((bits >> 8) & 0xffffffu) + 0.5f) * unit;  // past m when m is odd: not read
      }
      for (std::size_t j = 0; j < m; ++j) {
        const float level =
            codes_per_log2_ * (log2_noise_power_ + fastLog2(exponential(w[j]))) + offset_[i0 + j] + 0.5f;
        const auto c = static_cast<std::uint8_t>(std::min(255.0f, std::max(0.0f, level)));
        q[j] = w[j] < visible_[i0 + j] ? c : 0;
      }
    } else {
      std::fill(q, q + m, std::uint8_t{0});
      for (std::size_t j = 0; p > 0.0; ++j) {
        const double u = static_cast<double>((random.bits(next++) >> 11) + 1) * unit53;  // (0, 1]
        const double gap = std::floor(std::log(u) / block_log_miss_[b]);
        if (!(gap < static_cast<double>(m - j)))
          break;
        j += static_cast<std::size_t>(gap);
        const double w = (static_cast<double>(random.bits(next++) >> 11) + 0.5) * unit53 * p;
        if (w < visible_[i0 + j])
          q[j] = code(noise_power_ * exponential(static_cast<float>(w)), i0 + j);
      }
    }
    // The bins with an echo: speckle and noise from the bin's own draw.
    for (std::size_t j = 0; j < m; ++j) {
      double power = energy[i0 + j];
      energy[i0 + j] = 0.0;  // zero again for the next beam
      if (!(power > 0.0))
        continue;
      const std::uint64_t bits = random.bits(i0 + j);
      if (noise_.speckle)
        power *= exponential((static_cast<float>(bits >> 40) + 0.5f) * unit);
      if (noise_.noise_floor)
        power += noise_power_ * exponential((static_cast<float>((bits >> 16) & 0xffffffu) + 0.5f) * unit);
      q[j] = code(power, i0 + j);
    }
    for (std::size_t j = 0; j < m; ++j)
      codes[(i0 + j) * stride] = q[j];
  }
}

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

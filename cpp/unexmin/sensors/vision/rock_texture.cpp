#include <unexmin/sensors/vision/rock_texture.h>

#include <unexmin/sensors/vision/image_formation.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace sensors {
namespace vision {
namespace {

constexpr float kTwoPi = 6.28318530718f;
constexpr float kCrackWidth = 0.12f;  ///< |n| below which a crack darkens (fraction of the noise's range)
/// shadeMany takes a slow noise (regions, stains) as linear about the centre of a batch's bounding box when the box
/// is within this fraction of its scale on every axis: the error is second order in it (in the distance from the
/// centre, at most half the box's diagonal).
constexpr float kLinearSpan = 0.04f;

/// A lattice value in [-1, 1) from the integer cell corner (x, y, z) and a seed: per-axis multiplicative hashes,
/// combined and finished by one xor-shift and one multiply (whose top bits, the value's, mix every bit: enough for
/// noise, cheap in lanes).
inline float lattice(std::uint32_t hx, std::uint32_t hy, std::uint32_t hz, std::uint32_t seed) {
  std::uint32_t h = seed ^ hx ^ hy ^ hz;
  h ^= h >> 15;
  h *= 0x2c1b3c6du;
  return static_cast<float>(h >> 1) * (1.0f / 1073741824.0f) - 1.0f;
}

/// Value noise at q (lattice units): trilinear in smoothstep weights of seeded corner values in [-1, 1]; its
/// gradient (lattice units) into `g`.
/// floor(x) as an integer, without libm's floor (a call on x86-64 without SSE4.1); |x| < 2^31.
inline std::int32_t floorInt(float x) {
  const auto i = static_cast<std::int32_t>(x);
  return x < static_cast<float>(i) ? i - 1 : i;
}

inline float noise(const Eigen::Vector3f& q, std::uint32_t seed, Eigen::Vector3f& g) {
  const std::int32_t fx = floorInt(q.x()), fy = floorInt(q.y()), fz = floorInt(q.z());
  const float tx = q.x() - static_cast<float>(fx), ty = q.y() - static_cast<float>(fy);
  const float tz = q.z() - static_cast<float>(fz);
  const auto ix = static_cast<std::uint32_t>(fx);
  const auto iy = static_cast<std::uint32_t>(fy);
  const auto iz = static_cast<std::uint32_t>(fz);
  const std::uint32_t x0 = ix * 0x8da6b343u, x1 = x0 + 0x8da6b343u;
  const std::uint32_t y0 = iy * 0xd8163841u, y1 = y0 + 0xd8163841u;
  const std::uint32_t z0 = iz * 0xcb1ab31fu, z1 = z0 + 0xcb1ab31fu;
  const float a = lattice(x0, y0, z0, seed), b = lattice(x1, y0, z0, seed);
  const float c = lattice(x0, y1, z0, seed), d = lattice(x1, y1, z0, seed);
  const float e = lattice(x0, y0, z1, seed), f = lattice(x1, y0, z1, seed);
  const float gg = lattice(x0, y1, z1, seed), h = lattice(x1, y1, z1, seed);
  const float ux = tx * tx * (3.0f - 2.0f * tx), uy = ty * ty * (3.0f - 2.0f * ty), uz = tz * tz * (3.0f - 2.0f * tz);
  const float dx = 6.0f * tx * (1.0f - tx), dy = 6.0f * ty * (1.0f - ty), dz = 6.0f * tz * (1.0f - tz);
  const float k1 = b - a, k2 = c - a, k3 = e - a, k4 = a - b - c + d, k5 = a - c - e + gg, k6 = a - b - e + f;
  const float k7 = -a + b + c - d + e - f - gg + h;
  g.x() = dx * (k1 + k4 * uy + k6 * uz + k7 * uy * uz);
  g.y() = dy * (k2 + k5 * uz + k4 * ux + k7 * uz * ux);
  g.z() = dz * (k3 + k6 * ux + k5 * uy + k7 * ux * uy);
  return a + k1 * ux + k2 * uy + k3 * uz + k4 * ux * uy + k5 * uy * uz + k6 * uz * ux + k7 * ux * uy * uz;
}

inline float crackOf(float n, float& slope)  // -max(0, 1 - |n| / w)^2 and its derivative in n
{
  const float a = 1.0f - std::abs(n) / kCrackWidth;
  if (a <= 0.0f) {
    slope = 0.0f;
    return 0.0f;
  }
  slope = (n > 0.0f ? 2.0f : -2.0f) * a / kCrackWidth;
  return -a * a;
}

/// Mean and standard deviation of the components over the noise (independent of the seed and the scale), from a
/// fixed sample of 2^17 points (once per process).
struct Moments {
  float value_sd, grain_mean, grain_sd, crack_mean, crack_sd;
  /// Root mean square of |grad| of the stains', grains' and cracks' centred, unit components, per unit of their
  /// scale [-] (lattice units).
  float value_slope, grain_slope, crack_slope;
};

const Moments& moments() {
  static const Moments m = [] {
    constexpr int kN = 1 << 17;
    const std::uint32_t seeds[2] = {0x1234567u, 0x89abcdefu};
    double s[3] = {0, 0, 0}, s2[3] = {0, 0, 0}, g2[3] = {0, 0, 0};
    std::uint64_t z = 0x5eed;
    auto uniform = [&z] {  // splitmix64 -> [0, 1)
      z += 0x9e3779b97f4a7c15ull;
      std::uint64_t x = z;
      x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
      x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
      return static_cast<double>((x ^ (x >> 31)) >> 11) / 9007199254740992.0;
    };
    for (int i = 0; i < kN; ++i) {
      const Eigen::Vector3f q(static_cast<float>(1000.0 * uniform()), static_cast<float>(1000.0 * uniform()),
                              static_cast<float>(1000.0 * uniform()));
      Eigen::Vector3f g[3];
      float slope;
      const double v[3] = {noise(q, seeds[0], g[0]), noise(q, seeds[0], g[1]),
                           crackOf(noise(q, seeds[1], g[2]), slope)};
      g[2] *= slope;
      for (int k = 0; k < 3; ++k) {
        s[k] += v[k];
        s2[k] += v[k] * v[k];
        g2[k] += g[k].squaredNorm();
      }
    }
    auto sd = [&](int k) { return static_cast<float>(std::sqrt(s2[k] / kN - (s[k] / kN) * (s[k] / kN))); };
    const float value_sd = static_cast<float>(std::sqrt(s2[0] / kN));
    auto rms = [&](int k, float sigma) { return static_cast<float>(std::sqrt(g2[k] / kN)) / sigma; };
    return Moments{value_sd,      static_cast<float>(s[1] / kN),
                   sd(1),         static_cast<float>(s[2] / kN),
                   sd(2),         rms(0, value_sd),
                   rms(1, sd(1)), rms(2, sd(2))};
  }();
  return m;
}

std::uint32_t seedOf(std::uint64_t seed, std::uint64_t salt) {
  std::uint64_t z = seed * 0x9e3779b97f4a7c15ull + salt * 0xd1b54a32d192ed03ull + 0x632be59bd9b4e019ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return static_cast<std::uint32_t>((z ^ (z >> 31)) >> 16);
}

}  // namespace

RockTexture::RockTexture(const sim::Material& m, const std::string& prefix) : m_(m) {
  sim::checkMaterial(m, prefix);
  for (int i = 0; i < 6; ++i)
    seed_[i] = seedOf(m.seed, static_cast<std::uint64_t>(i));
  const double scales[5] = {m.grain, m.cracks, m.strata, m.stains, m.region};
  for (int i = 0; i < 5; ++i)
    inv_scale_[i] = scales[i] > 0.0 ? static_cast<float>(1.0 / scales[i]) : 0.0f;
  double sum2 = 0.0, relief2 = 0.0;  // the relief: grain, cracks and strata (stains are colour, not shape)
  for (int i = 0; i < 4; ++i)
    if (inv_scale_[i] > 0.0f) {
      sum2 += m.weights[i] * m.weights[i];
      relief2 += i < 3 ? m.weights[i] * m.weights[i] : 0.0;
    }
  const double norm = sum2 > 0.0 ? 1.0 / std::sqrt(sum2) : 0.0;
  const double relief_norm = relief2 > 0.0 ? 1.0 / std::sqrt(relief2) : 0.0;
  // Each component's height is its value times its scale over its RMS slope per unit scale, so that each has an
  // RMS slope of 1 (the strata: 2 pi, their warp neglected); the stains have none.
  const Moments& mo = moments();
  const float slope[4] = {mo.grain_slope, mo.crack_slope, kTwoPi, mo.value_slope};
  for (int i = 0; i < 4; ++i) {
    weight_[static_cast<std::size_t>(i)] = inv_scale_[i] > 0.0f ? static_cast<float>(m.weights[i] * norm) : 0.0f;
    height_[static_cast<std::size_t>(i)] =
        i < 3 && inv_scale_[i] > 0.0f ? static_cast<float>(m.weights[i] * relief_norm * scales[i] / slope[i]) : 0.0f;
  }
  albedo_ = m.albedo.cast<float>().array();
  contrast_ = m.textured() ? static_cast<float>(m.contrast) : 0.0f;
  relief_ = m.textured() ? static_cast<float>(m.relief) : 0.0f;
  // The regions' colour direction: three seeded numbers in [-1, 1], scaled so that the largest is +-1.
  Eigen::Array3f d;
  for (int k = 0; k < 3; ++k)
    d[k] = static_cast<float>(seedOf(m.seed, 16u + static_cast<std::uint64_t>(k))) / 4294967296.0f * 2.0f - 1.0f;
  d /= std::max(1e-6f, d.abs().maxCoeff());
  tint_ = Eigen::Array3f::Zero();
  if (m.textured() && m.region > 0.0)
    tint_ = static_cast<float>(m.tint) * d;

  RockLanes& k = lanes_;
  for (int i = 0; i < 5; ++i) {
    k.seed[i] = seed_[i];
    k.inv_scale[i] = inv_scale_[i];
  }
  for (std::size_t i = 0; i < 4; ++i) {
    k.weight[i] = weight_[i];
    k.height[i] = height_[i];
  }
  for (int c = 0; c < 3; ++c) {
    k.albedo[c] = albedo_[c];
    k.tint[c] = tint_[c];
  }
  k.contrast = contrast_;
  k.relief = relief_;
  k.crack_width = kCrackWidth;
  k.value_sd = mo.value_sd;
  k.grain_mean = mo.grain_mean;
  k.grain_sd = mo.grain_sd;
  k.crack_mean = mo.crack_mean;
  k.crack_sd = mo.crack_sd;
  k.tinted = tint_.matrix().squaredNorm() > 0.0f;
  k.region_linear = k.stain_linear = false;
}

float RockTexture::evaluate(const Eigen::Vector3f& p, Eigen::Vector3f& gf, float& h, Eigen::Vector3f& gh, float& region,
                            const RockLanes* linear) const {
  const Moments& mo = moments();
  float f = 0.0f;
  h = 0.0f;
  gf.setZero();
  gh.setZero();
  region = 0.0f;
  Eigen::Vector3f g;
  auto add = [&](int i, float c, const Eigen::Vector3f& grad) {
    f += weight_[static_cast<std::size_t>(i)] * c;
    gf += weight_[static_cast<std::size_t>(i)] * grad;
    h += height_[static_cast<std::size_t>(i)] * c;
    gh += height_[static_cast<std::size_t>(i)] * grad;
  };
  if (weight_[0] != 0.0f) {
    const float n = noise(p * inv_scale_[0], seed_[0], g);
    add(0, (n - mo.grain_mean) / mo.grain_sd, g * (inv_scale_[0] / mo.grain_sd));
  }
  if (weight_[1] != 0.0f) {
    float slope;
    const float c = crackOf(noise(p * inv_scale_[1], seed_[2], g), slope);
    add(1, (c - mo.crack_mean) / mo.crack_sd, g * (slope * inv_scale_[1] / mo.crack_sd));
  }
  float stain = 0.0f;
  Eigen::Vector3f stain_g = Eigen::Vector3f::Zero();
  if (linear && linear->stain_linear) {
    stain_g = Eigen::Vector3f(linear->stain_grad[0], linear->stain_grad[1], linear->stain_grad[2]);
    stain = linear->stain0 + stain_g.dot(p - Eigen::Vector3f(linear->origin[0], linear->origin[1], linear->origin[2]));
  } else if (inv_scale_[3] > 0.0f) {
    stain = noise(p * inv_scale_[3], seed_[3], stain_g) / mo.value_sd;
    stain_g *= inv_scale_[3] / mo.value_sd;
  }
  if (weight_[2] != 0.0f) {  // bands along z, warped by the stains' noise (half a band per unit of it)
    const float phase = kTwoPi * (p.z() * inv_scale_[2] + 0.5f * mo.value_sd * stain);
    Eigen::Vector3f dphase = (kTwoPi * 0.5f * mo.value_sd) * stain_g;
    dphase.z() += kTwoPi * inv_scale_[2];
    constexpr float kRoot2 = 1.41421356237f;  // sin of a uniform phase has standard deviation 1 / sqrt(2)
    add(2, kRoot2 * std::sin(phase), (kRoot2 * std::cos(phase)) * dphase);
  }
  if (weight_[3] != 0.0f)
    add(3, stain, stain_g);
  if (linear && linear->region_linear)
    region = linear->region0 + linear->region_grad[0] * (p.x() - linear->origin[0]) +
             linear->region_grad[1] * (p.y() - linear->origin[1]) +
             linear->region_grad[2] * (p.z() - linear->origin[2]);
  else if (tint_.matrix().squaredNorm() > 0.0f)
    region = noise(p * inv_scale_[4], seed_[4], g) / mo.value_sd;
  return f;
}

void RockTexture::albedoOf(float f, float region, float* out) const {
  const float m = 1.0f + contrast_ * f;
  for (int k = 0; k < 3; ++k)
    out[k] = std::min(1.0f, std::max(0.0f, albedo_[k] * m * (1.0f + tint_[k] * region)));
}

float RockTexture::field(const Eigen::Vector3f& p, Eigen::Vector3f* gradient) const {
  Eigen::Vector3f gf, gh;
  float h, region;
  const float f = evaluate(p, gf, h, gh, region);
  if (gradient)
    *gradient = gf;
  return f;
}

float RockTexture::height(const Eigen::Vector3f& p, Eigen::Vector3f* gradient) const {
  Eigen::Vector3f gf, gh;
  float h, region;
  evaluate(p, gf, h, gh, region);
  if (gradient)
    *gradient = gh;
  return h;
}

Eigen::Array3f RockTexture::albedo(const Eigen::Vector3f& p) const {
  Eigen::Vector3f gf, gh;
  float h, region;
  const float f = evaluate(p, gf, h, gh, region);
  Eigen::Array3f out;
  albedoOf(f, region, out.data());
  return out;
}

Eigen::Vector3f RockTexture::normal(const Eigen::Vector3f& p, const Eigen::Vector3f& n) const {
  float albedo[3];
  Eigen::Vector3f out;
  shade(p, n, albedo, out);
  return out;
}

void RockTexture::shade(const Eigen::Vector3f& p, const Eigen::Vector3f& n, float* albedo, Eigen::Vector3f& shading,
                        const RockLanes* linear) const {
  Eigen::Vector3f gf, gh;
  float h, region;
  const float f = evaluate(p, gf, h, gh, region, linear);
  albedoOf(f, region, albedo);
  if (relief_ > 0.0f)
    shading = (n - relief_ * (gh - gh.dot(n) * n)).normalized();
  else
    shading = n;
}

void RockTexture::shadeMany(int n, const float* px, const float* py, const float* pz, float* nx, float* ny, float* nz,
                            float* const albedo[3], bool simd) const {
  if (n <= 0)
    return;
  // The slow noises, linear over a batch small against their scales.
  RockLanes k = lanes_;
  // The batch's extent: its bounding box's largest side (six independent running bounds, no chain between axes).
  const bool lanes = simd && rockAvx2Built() && ImageFormation::simdAvailable();
  float lo[3] = {px[0], py[0], pz[0]}, hi[3] = {px[0], py[0], pz[0]};
  int from = 1;
  if (lanes && n >= 8) {
    from = n / 8 * 8;
    rockBoundsAvx2(from, px, py, pz, lo, hi);
  }
  for (int i = from; i < n; ++i) {
    lo[0] = std::min(lo[0], px[i]), hi[0] = std::max(hi[0], px[i]);
    lo[1] = std::min(lo[1], py[i]), hi[1] = std::max(hi[1], py[i]);
    lo[2] = std::min(lo[2], pz[i]), hi[2] = std::max(hi[2], pz[i]);
  }
  const float span = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const Eigen::Vector3f p0(0.5f * (lo[0] + hi[0]), 0.5f * (lo[1] + hi[1]), 0.5f * (lo[2] + hi[2]));
  const float inv_sd = 1.0f / moments().value_sd;
  auto linearise = [&](int scale, std::uint32_t seed, float& value, float* grad) {
    Eigen::Vector3f g;
    value = noise(p0 * inv_scale_[scale], seed, g) * inv_sd;
    for (int a = 0; a < 3; ++a)
      grad[a] = g[a] * inv_scale_[scale] * inv_sd;
    return true;
  };
  for (int a = 0; a < 3; ++a)
    k.origin[a] = p0[a];
  if (n > 1 && k.tinted && span * inv_scale_[4] <= kLinearSpan)
    k.region_linear = linearise(4, seed_[4], k.region0, k.region_grad);
  if (n > 1 && inv_scale_[3] > 0.0f && span * inv_scale_[3] <= kLinearSpan)
    k.stain_linear = linearise(3, seed_[3], k.stain0, k.stain_grad);
  int i = 0;
  if (lanes) {
    i = n / 8 * 8;
    rockShadeAvx2(k, i, px, py, pz, nx, ny, nz, albedo);
  }
  for (; i < n; ++i) {
    float a[3];
    Eigen::Vector3f s;
    shade(Eigen::Vector3f(px[i], py[i], pz[i]), Eigen::Vector3f(nx[i], ny[i], nz[i]), a, s, &k);
    for (int c = 0; c < 3; ++c)
      albedo[c][i] = a[c];
    nx[i] = s.x();
    ny[i] = s.y();
    nz[i] = s.z();
  }
}

void RockTexture::shadeManyFrom(const Eigen::Matrix3f& rotation, const Eigen::Vector3f& translation, int n,
                                const float* px, const float* py, const float* pz, float* nx, float* ny, float* nz,
                                float* const albedo[3], bool simd) const {
  const bool lanes = simd && rockAvx2Built() && ImageFormation::simdAvailable();
  // (x, y, z)[i] = m (x, y, z)[i] + t, eight at a time where the CPU can.
  auto transform = [lanes](int count, const Eigen::Matrix3f& m, const float* t, const float* x, const float* y,
                           const float* z, float* ox, float* oy, float* oz) {
    int i = 0;
    if (lanes) {
      const Eigen::Matrix<float, 3, 3, Eigen::RowMajor> rows = m;
      i = count / 8 * 8;
      rockTransformAvx2(i, rows.data(), t, x, y, z, ox, oy, oz);
    }
    for (; i < count; ++i) {
      const Eigen::Vector3f v = m * Eigen::Vector3f(x[i], y[i], z[i]) + Eigen::Vector3f(t[0], t[1], t[2]);
      ox[i] = v.x(), oy[i] = v.y(), oz[i] = v.z();
    }
  };
  constexpr int kChunk = 64;
  const float none[3] = {0.0f, 0.0f, 0.0f};
  const Eigen::Matrix3f back = rotation.transpose();
  for (int first = 0; first < n; first += kChunk) {
    const int count = std::min(kChunk, n - first);
    alignas(32) float x[3][kChunk], d[3][kChunk];
    transform(count, rotation, translation.data(), px + first, py + first, pz + first, x[0], x[1], x[2]);
    transform(count, rotation, none, nx + first, ny + first, nz + first, d[0], d[1], d[2]);
    float* const out[3] = {albedo[0] + first, albedo[1] + first, albedo[2] + first};
    shadeMany(count, x[0], x[1], x[2], d[0], d[1], d[2], out, simd);
    transform(count, back, none, d[0], d[1], d[2], nx + first, ny + first, nz + first);
  }
}

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin

// The eight-lane (AVX2 + FMA) build of RockTexture::shade (compiled with -mavx2 -mfma, see CMakeLists.txt; called
// only on CPUs that have both, see RockTexture::shadeMany). The same formulas as rock_texture.cpp, eight points at a
// time; results equal up to rounding (FMA, and the sine's polynomial: below 1e-6). Also the batch's bounding box and
// the move of its points into the mesh frame, in lanes.
#include <unexmin/sensors/vision/rock_texture.h>

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#endif

namespace unexmin {
namespace sensors {
namespace vision {

#if defined(__AVX2__) && defined(__FMA__)
namespace {

using F = __m256;
using I = __m256i;

struct V {
  F x, y, z;
};

inline F set(float a) {
  return _mm256_set1_ps(a);
}
inline F add(F a, F b) {
  return _mm256_add_ps(a, b);
}
inline F sub(F a, F b) {
  return _mm256_sub_ps(a, b);
}
inline F mul(F a, F b) {
  return _mm256_mul_ps(a, b);
}
inline F fma(F a, F b, F c) {
  return _mm256_fmadd_ps(a, b, c);
}
inline V scale(const V& v, F s) {
  return {mul(v.x, s), mul(v.y, s), mul(v.z, s)};
}
inline V madd(const V& acc, F s, const V& v) {
  return {fma(s, v.x, acc.x), fma(s, v.y, acc.y), fma(s, v.z, acc.z)};
}

inline I hashAxis(I i, std::uint32_t k) {
  return _mm256_mullo_epi32(i, _mm256_set1_epi32(static_cast<int>(k)));
}

/// lattice() of rock_texture.cpp in lanes, from the corner's x ^ y hash and its z ^ seed.
inline F lattice(I hxy, I hzs) {
  I h = _mm256_xor_si256(hxy, hzs);
  h = _mm256_xor_si256(h, _mm256_srli_epi32(h, 15));
  h = _mm256_mullo_epi32(h, _mm256_set1_epi32(0x2c1b3c6d));
  // h as an unsigned number / 2^31 - 1: its top 31 bits as a signed integer / 2^30.
  return fma(_mm256_cvtepi32_ps(_mm256_srli_epi32(h, 1)), set(1.0f / 1073741824.0f), set(-1.0f));
}

/// The eight corner values of a lattice cell as noise() combines them: a, then k1..k7.
struct Corners {
  F k[8];
};

/// Corners of the cells (ix, iy, iz) of each lane.
inline Corners corners(I ix, I iy, I iz, std::uint32_t seed_value) {
  const I x0 = hashAxis(ix, 0x8da6b343u), x1 = _mm256_add_epi32(x0, _mm256_set1_epi32(static_cast<int>(0x8da6b343u)));
  const I y0 = hashAxis(iy, 0xd8163841u), y1 = _mm256_add_epi32(y0, _mm256_set1_epi32(static_cast<int>(0xd8163841u)));
  const I z0 = hashAxis(iz, 0xcb1ab31fu), z1 = _mm256_add_epi32(z0, _mm256_set1_epi32(static_cast<int>(0xcb1ab31fu)));
  const I seed = _mm256_set1_epi32(static_cast<int>(seed_value));
  const I x0y0 = _mm256_xor_si256(x0, y0), x1y0 = _mm256_xor_si256(x1, y0);
  const I x0y1 = _mm256_xor_si256(x0, y1), x1y1 = _mm256_xor_si256(x1, y1);
  const I z0s = _mm256_xor_si256(z0, seed), z1s = _mm256_xor_si256(z1, seed);
  const F a = lattice(x0y0, z0s), b = lattice(x1y0, z0s);
  const F c = lattice(x0y1, z0s), d = lattice(x1y1, z0s);
  const F e = lattice(x0y0, z1s), f = lattice(x1y0, z1s);
  const F gg = lattice(x0y1, z1s), h = lattice(x1y1, z1s);
  // k7 = -a + b + c - d + e - f - g + h
  return {{a, sub(b, a), sub(c, a), sub(e, a), add(sub(sub(a, b), c), d), add(sub(sub(a, c), e), gg),
           add(sub(sub(a, b), e), f), add(sub(sub(add(sub(add(sub(b, a), c), d), e), f), gg), h)}};
}

/// The noise at the fractions (tx, ty, tz) of the cells of `k`, its gradient (lattice units) into g.
inline F interpolate(const Corners& k, F tx, F ty, F tz, V& g) {
  const F three = set(3.0f), two = set(2.0f), six = set(6.0f), one_f = set(1.0f);
  const F ux = mul(mul(tx, tx), sub(three, mul(two, tx))), uy = mul(mul(ty, ty), sub(three, mul(two, ty)));
  const F uz = mul(mul(tz, tz), sub(three, mul(two, tz)));
  const F dx = mul(mul(six, tx), sub(one_f, tx)), dy = mul(mul(six, ty), sub(one_f, ty));
  const F dz = mul(mul(six, tz), sub(one_f, tz));
  const F a = k.k[0], k1 = k.k[1], k2 = k.k[2], k3 = k.k[3], k4 = k.k[4], k5 = k.k[5], k6 = k.k[6], k7s = k.k[7];
  g.x = mul(dx, fma(k7s, mul(uy, uz), fma(k6, uz, fma(k4, uy, k1))));
  g.y = mul(dy, fma(k7s, mul(uz, ux), fma(k4, ux, fma(k5, uz, k2))));
  g.z = mul(dz, fma(k7s, mul(ux, uy), fma(k5, uy, fma(k6, ux, k3))));
  F v = fma(k1, ux, a);
  v = fma(k2, uy, v);
  v = fma(k3, uz, v);
  v = fma(k4, mul(ux, uy), v);
  v = fma(k5, mul(uy, uz), v);
  v = fma(k6, mul(uz, ux), v);
  return fma(k7s, mul(mul(ux, uy), uz), v);
}

/// noise() of rock_texture.cpp in lanes.
inline F noise(const V& q, std::uint32_t seed, V& g) {
  const F fx = _mm256_floor_ps(q.x), fy = _mm256_floor_ps(q.y), fz = _mm256_floor_ps(q.z);
  const Corners k = corners(_mm256_cvttps_epi32(fx), _mm256_cvttps_epi32(fy), _mm256_cvttps_epi32(fz), seed);
  return interpolate(k, sub(q.x, fx), sub(q.y, fy), sub(q.z, fz), g);
}

/// The corners of the last cell that all eight lanes of a group fell in: a noise much coarser than a batch (the
/// cracks) takes them from here for most groups instead of hashing again (the same numbers).
struct CellCache {
  bool valid = false;
  I cell[3];
  Corners k;
};

/// noise() in lanes through `cache`.
inline F noise(const V& q, std::uint32_t seed, V& g, CellCache& cache) {
  const F fx = _mm256_floor_ps(q.x), fy = _mm256_floor_ps(q.y), fz = _mm256_floor_ps(q.z);
  const I ix = _mm256_cvttps_epi32(fx), iy = _mm256_cvttps_epi32(fy), iz = _mm256_cvttps_epi32(fz);
  const F tx = sub(q.x, fx), ty = sub(q.y, fy), tz = sub(q.z, fz);
  auto same = [&](const I* c) {
    const I eq = _mm256_and_si256(_mm256_and_si256(_mm256_cmpeq_epi32(ix, c[0]), _mm256_cmpeq_epi32(iy, c[1])),
                                  _mm256_cmpeq_epi32(iz, c[2]));
    return _mm256_movemask_epi8(eq) == -1;
  };
  if (cache.valid && same(cache.cell))
    return interpolate(cache.k, tx, ty, tz, g);
  const Corners k = corners(ix, iy, iz, seed);
  const I zero = _mm256_setzero_si256();
  const I first[3] = {_mm256_permutevar8x32_epi32(ix, zero), _mm256_permutevar8x32_epi32(iy, zero),
                      _mm256_permutevar8x32_epi32(iz, zero)};
  cache.valid = same(first);
  if (cache.valid) {  // one cell: its corners in every lane
    for (int a = 0; a < 3; ++a)
      cache.cell[a] = first[a];
    cache.k = k;
  }
  return interpolate(k, tx, ty, tz, g);
}

/// sin and cos of x [rad] (any x of a float's exact range): reduced to [-pi, pi], then odd and even polynomials
/// (Taylor to x^11 and x^12 on [-pi/2, pi/2] after the reflection x -> pi - x; error below 1e-6).
inline void sinCos(F x, F& s, F& c) {
  const F inv_two_pi = set(0.15915494309f), two_pi = set(6.28318530718f), pi = set(3.14159265359f);
  x = sub(x, mul(two_pi, _mm256_round_ps(mul(x, inv_two_pi), _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC)));
  // Reflect into [-pi/2, pi/2]: sin(pi - x) = sin x, cos(pi - x) = -cos x.
  const F half_pi = set(1.57079632679f), sign = set(-0.0f);
  const F big = _mm256_cmp_ps(_mm256_andnot_ps(sign, x), half_pi, _CMP_GT_OQ);
  const F reflected = sub(_mm256_or_ps(pi, _mm256_and_ps(sign, x)), x);
  x = _mm256_blendv_ps(x, reflected, big);
  const F x2 = mul(x, x);
  F ps = set(-2.5052108e-8f);
  ps = fma(ps, x2, set(2.7557319e-6f));
  ps = fma(ps, x2, set(-1.9841270e-4f));
  ps = fma(ps, x2, set(8.3333333e-3f));
  ps = fma(ps, x2, set(-1.6666667e-1f));
  s = fma(mul(ps, x2), x, x);
  F pc = set(2.0876757e-9f);
  pc = fma(pc, x2, set(-2.7557319e-7f));
  pc = fma(pc, x2, set(2.4801587e-5f));
  pc = fma(pc, x2, set(-1.3888889e-3f));
  pc = fma(pc, x2, set(4.1666667e-2f));
  pc = fma(pc, x2, set(-0.5f));
  c = fma(pc, x2, set(1.0f));
  c = _mm256_blendv_ps(c, _mm256_xor_ps(c, sign), big);
}

}  // namespace

bool rockAvx2Built() {
  return true;
}

void rockTransformAvx2(int n, const float* m, const float* t, const float* x, const float* y, const float* z, float* ox,
                       float* oy, float* oz) {
  const F m00 = set(m[0]), m01 = set(m[1]), m02 = set(m[2]), m10 = set(m[3]), m11 = set(m[4]), m12 = set(m[5]);
  const F m20 = set(m[6]), m21 = set(m[7]), m22 = set(m[8]), t0 = set(t[0]), t1 = set(t[1]), t2 = set(t[2]);
  for (int i = 0; i + 8 <= n; i += 8) {
    const F a = _mm256_loadu_ps(x + i), b = _mm256_loadu_ps(y + i), c = _mm256_loadu_ps(z + i);
    _mm256_storeu_ps(ox + i, fma(m00, a, fma(m01, b, fma(m02, c, t0))));
    _mm256_storeu_ps(oy + i, fma(m10, a, fma(m11, b, fma(m12, c, t1))));
    _mm256_storeu_ps(oz + i, fma(m20, a, fma(m21, b, fma(m22, c, t2))));
  }
}

void rockBoundsAvx2(int n, const float* px, const float* py, const float* pz, float* lo, float* hi) {
  const float* p[3] = {px, py, pz};
  for (int a = 0; a < 3; ++a) {
    F l = _mm256_loadu_ps(p[a]), h = l;
    for (int i = 8; i + 8 <= n; i += 8) {
      const F v = _mm256_loadu_ps(p[a] + i);
      l = _mm256_min_ps(l, v);
      h = _mm256_max_ps(h, v);
    }
    alignas(32) float ls[8], hs[8];
    _mm256_store_ps(ls, l);
    _mm256_store_ps(hs, h);
    lo[a] = ls[0], hi[a] = hs[0];
    for (int k = 1; k < 8; ++k) {  // no std::min here: an inline function compiled for AVX2 must not be shared
      lo[a] = ls[k] < lo[a] ? ls[k] : lo[a];
      hi[a] = hs[k] > hi[a] ? hs[k] : hi[a];
    }
  }
}

void rockShadeAvx2(const RockLanes& lanes, int n, const float* px, const float* py, const float* pz, float* nx,
                   float* ny, float* nz, float* const albedo[3]) {
  // A copy the outputs cannot alias: its constants (and their quotients) stay out of the loop.
  const RockLanes k = lanes;
  const F zero = set(0.0f), one = set(1.0f);
  CellCache cracks, stains, regions;  // the coarse lattices' last cells
  for (int i = 0; i + 8 <= n; i += 8) {
    const V p{_mm256_loadu_ps(px + i), _mm256_loadu_ps(py + i), _mm256_loadu_ps(pz + i)};
    F f = zero;
    V gh{zero, zero, zero};
    V g;
    if (k.weight[0] != 0.0f) {  // grain
      const F n1 = noise(scale(p, set(k.inv_scale[0])), k.seed[0], g);
      const F c = mul(sub(n1, set(k.grain_mean)), set(1.0f / k.grain_sd));
      f = fma(set(k.weight[0]), c, f);
      gh = madd(gh, set(k.height[0] * k.inv_scale[0] / k.grain_sd), g);
    }
    if (k.weight[1] != 0.0f) {  // cracks
      const F nk = noise(scale(p, set(k.inv_scale[1])), k.seed[2], g, cracks);
      const F sign = _mm256_and_ps(nk, set(-0.0f));
      const F a = _mm256_max_ps(zero, sub(one, mul(_mm256_andnot_ps(set(-0.0f), nk), set(1.0f / k.crack_width))));
      // slope = sign(n) 2 a / w (0 where a = 0), c = -a^2
      const F slope = _mm256_xor_ps(mul(a, set(2.0f / k.crack_width)), sign);
      const F c = mul(sub(sub(zero, mul(a, a)), set(k.crack_mean)), set(1.0f / k.crack_sd));
      f = fma(set(k.weight[1]), c, f);
      gh = madd(gh, mul(slope, set(k.height[1] * k.inv_scale[1] / k.crack_sd)), g);
    }
    F stain = zero;
    V sg{zero, zero, zero};
    const V o{set(k.origin[0]), set(k.origin[1]), set(k.origin[2])};
    const V d{sub(p.x, o.x), sub(p.y, o.y), sub(p.z, o.z)};
    if (k.stain_linear) {  // stain0 + stain_grad . (p - origin)
      sg = {set(k.stain_grad[0]), set(k.stain_grad[1]), set(k.stain_grad[2])};
      stain = fma(sg.x, d.x, fma(sg.y, d.y, fma(sg.z, d.z, set(k.stain0))));
    } else if (k.inv_scale[3] > 0.0f) {
      stain = mul(noise(scale(p, set(k.inv_scale[3])), k.seed[3], sg, stains), set(1.0f / k.value_sd));
      sg = scale(sg, set(k.inv_scale[3] / k.value_sd));
    }
    if (k.weight[2] != 0.0f) {  // strata
      constexpr float kTwoPi = 6.28318530718f, kRoot2 = 1.41421356237f;
      const F phase = mul(set(kTwoPi), fma(p.z, set(k.inv_scale[2]), mul(set(0.5f * k.value_sd), stain)));
      F s, c;
      sinCos(phase, s, c);
      V dphase = scale(sg, set(kTwoPi * 0.5f * k.value_sd));
      dphase.z = add(dphase.z, set(kTwoPi * k.inv_scale[2]));
      f = fma(set(k.weight[2]), mul(set(kRoot2), s), f);
      gh = madd(gh, mul(set(k.height[2] * kRoot2), c), dphase);
    }
    if (k.weight[3] != 0.0f)  // stains: colour, no relief (height[3] = 0)
      f = fma(set(k.weight[3]), stain, f);
    F region = zero;
    if (k.region_linear)  // region0 + region_grad . (p - origin)
      region = fma(set(k.region_grad[0]), d.x,
                   fma(set(k.region_grad[1]), d.y, fma(set(k.region_grad[2]), d.z, set(k.region0))));
    else if (k.tinted)
      region = mul(noise(scale(p, set(k.inv_scale[4])), k.seed[4], g, regions), set(1.0f / k.value_sd));
    const F m = fma(set(k.contrast), f, one);
    for (int c = 0; c < 3; ++c) {
      const F a = mul(mul(set(k.albedo[c]), m), fma(set(k.tint[c]), region, one));
      _mm256_storeu_ps(albedo[c] + i, _mm256_min_ps(one, _mm256_max_ps(zero, a)));
    }
    if (k.relief > 0.0f) {
      const V nn{_mm256_loadu_ps(nx + i), _mm256_loadu_ps(ny + i), _mm256_loadu_ps(nz + i)};
      const F dot = fma(gh.x, nn.x, fma(gh.y, nn.y, mul(gh.z, nn.z)));
      const F r = set(k.relief);
      // n - relief (gh - (gh . n) n)
      const V t{fma(r, fma(dot, nn.x, sub(zero, gh.x)), nn.x), fma(r, fma(dot, nn.y, sub(zero, gh.y)), nn.y),
                fma(r, fma(dot, nn.z, sub(zero, gh.z)), nn.z)};
      // 1 / |t|: the approximate reciprocal square root and one Newton step (relative error ~1e-7).
      const F len2 = fma(t.x, t.x, fma(t.y, t.y, mul(t.z, t.z)));
      const F r0 = _mm256_rsqrt_ps(len2);
      const F inv = mul(r0, fma(mul(set(-0.5f), len2), mul(r0, r0), set(1.5f)));
      _mm256_storeu_ps(nx + i, mul(t.x, inv));
      _mm256_storeu_ps(ny + i, mul(t.y, inv));
      _mm256_storeu_ps(nz + i, mul(t.z, inv));
    }
  }
}

#else

bool rockAvx2Built() {
  return false;
}
void rockBoundsAvx2(int, const float*, const float*, const float*, float*, float*) {}
void rockTransformAvx2(int, const float*, const float*, const float*, const float*, const float*, float*, float*,
                       float*) {}
void rockShadeAvx2(const RockLanes&, int, const float*, const float*, const float*, float*, float*, float*,
                   float* const[3]) {}

#endif

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin

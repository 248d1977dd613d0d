// SIMD lanes for the camera's shading kernels (shading_kernels.h): the same kernel source runs one pixel at a time
// (F1, I1, M1: plain float, int, bool) or eight side by side (F8, I8, M8: AVX2, only where the translation unit is
// compiled with -mavx2 -mfma, see shading_avx2.cpp). Each type offers just what the kernels use: arithmetic,
// comparisons giving masks, select, truncation, and gathers from a table. No Eigen, nothing shared with other
// translation units but these types (a function compiled for AVX2 must never be picked for a CPU without it).
#pragma once

#include <cmath>
#include <cstdint>

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#endif

namespace unexmin {
namespace sensors {
namespace vision {
namespace lanes {
// Everything here gets a namespace of its own in the AVX2 translation unit, so that no inline function compiled
// there can be chosen by the linker for the others (which may run on CPUs without AVX2).
#if defined(__AVX2__) && defined(__FMA__)
inline namespace avx2 {
#else
inline namespace baseline {
#endif

// ---------------------------------------------------------------- one lane

struct M1 {
  bool v;
};
struct I1 {
  std::int32_t v;
};
struct F1 {
  static constexpr int kWidth = 1;
  using Mask = M1;
  using Int = I1;
  float v;
  F1() = default;
  explicit F1(float x) : v(x) {}
};

inline F1 load(const float* p, F1) {
  return F1(*p);
}
inline I1 loadInt(const std::uint32_t* p, F1) {
  return I1{static_cast<std::int32_t>(*p)};
}
inline I1 loadInt(const std::int32_t* p, F1) {
  return I1{*p};
}
inline void store(float* p, F1 a) {
  *p = a.v;
}
inline void storeInt(std::int32_t* p, I1 a) {
  *p = a.v;
}
inline F1 operator+(F1 a, F1 b) {
  return F1(a.v + b.v);
}
inline F1 operator-(F1 a, F1 b) {
  return F1(a.v - b.v);
}
inline F1 operator*(F1 a, F1 b) {
  return F1(a.v * b.v);
}
inline F1 operator/(F1 a, F1 b) {
  return F1(a.v / b.v);
}
inline F1 sqrt(F1 a) {
  return F1(std::sqrt(a.v));
}
inline F1 min(F1 a, F1 b) {
  return F1(b.v < a.v ? b.v : a.v);
}
inline F1 max(F1 a, F1 b) {
  return F1(a.v < b.v ? b.v : a.v);
}
inline M1 operator<(F1 a, F1 b) {
  return M1{a.v < b.v};
}
inline M1 operator>(F1 a, F1 b) {
  return M1{a.v > b.v};
}
inline M1 operator&(M1 a, M1 b) {
  return M1{a.v && b.v};
}
inline bool none(M1 m) {
  return !m.v;
}
inline F1 select(M1 m, F1 a, F1 b) {
  return m.v ? a : b;
}
inline I1 select(M1 m, I1 a, I1 b) {
  return m.v ? a : b;
}
inline I1 truncate(F1 a) {
  return I1{static_cast<std::int32_t>(a.v)};
}
inline F1 toFloat(I1 a) {
  return F1(static_cast<float>(a.v));
}
inline F1 gather(const float* base, I1 i) {
  return F1(base[i.v]);
}
inline I1 gatherInt(const std::int32_t* base, I1 i) {
  return I1{base[i.v]};
}
inline I1 operator+(I1 a, I1 b) {
  return I1{a.v + b.v};
}
inline I1 operator*(I1 a, I1 b) {
  return I1{a.v * b.v};
}
inline I1 min(I1 a, I1 b) {
  return I1{b.v < a.v ? b.v : a.v};
}
inline I1 splatInt(std::int32_t x, F1) {
  return I1{x};
}
inline M1 operator<(I1 a, I1 b) {
  return M1{a.v < b.v};
}
inline M1 anyBit(I1 a, std::uint32_t bit) {
  return M1{(static_cast<std::uint32_t>(a.v) & bit) != 0u};
}
/// out[0..8) = wa a[0..8) + wb b[0..8) + wc c[0..8) + wd d[0..8) (any alignment).
inline void weigh8(const float* a, float wa, const float* b, float wb, const float* c, float wc, const float* d,
                   float wd, float* out, F1) {
  for (int m = 0; m < 8; ++m)
    out[m] = wa * a[m] + wb * b[m] + wc * c[m] + wd * d[m];
}

// ---------------------------------------------------------------- eight lanes (AVX2 + FMA)

#if defined(__AVX2__) && defined(__FMA__)
struct M8 {
  __m256 v;
};
struct I8 {
  __m256i v;
};
struct F8 {
  static constexpr int kWidth = 8;
  using Mask = M8;
  using Int = I8;
  __m256 v;
  F8() = default;
  explicit F8(__m256 x) : v(x) {}
  explicit F8(float x) : v(_mm256_set1_ps(x)) {}
};

inline F8 load(const float* p, F8) {
  return F8(_mm256_loadu_ps(p));
}
inline I8 loadInt(const std::uint32_t* p, F8) {
  return I8{_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p))};
}
inline I8 loadInt(const std::int32_t* p, F8) {
  return I8{_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p))};
}
inline void store(float* p, F8 a) {
  _mm256_storeu_ps(p, a.v);
}
inline void storeInt(std::int32_t* p, I8 a) {
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), a.v);
}
inline F8 operator+(F8 a, F8 b) {
  return F8(_mm256_add_ps(a.v, b.v));
}
inline F8 operator-(F8 a, F8 b) {
  return F8(_mm256_sub_ps(a.v, b.v));
}
inline F8 operator*(F8 a, F8 b) {
  return F8(_mm256_mul_ps(a.v, b.v));
}
inline F8 operator/(F8 a, F8 b) {
  return F8(_mm256_div_ps(a.v, b.v));
}
inline F8 sqrt(F8 a) {
  return F8(_mm256_sqrt_ps(a.v));
}
// min/max as F1's, NaN included: minps/maxps return their second operand when either is NaN.
inline F8 min(F8 a, F8 b) {
  return F8(_mm256_min_ps(b.v, a.v));
}
inline F8 max(F8 a, F8 b) {
  return F8(_mm256_max_ps(b.v, a.v));
}
inline M8 operator<(F8 a, F8 b) {
  return M8{_mm256_cmp_ps(a.v, b.v, _CMP_LT_OQ)};
}
inline M8 operator>(F8 a, F8 b) {
  return M8{_mm256_cmp_ps(a.v, b.v, _CMP_GT_OQ)};
}
inline M8 operator&(M8 a, M8 b) {
  return M8{_mm256_and_ps(a.v, b.v)};
}
inline bool none(M8 m) {
  return _mm256_movemask_ps(m.v) == 0;
}
inline F8 select(M8 m, F8 a, F8 b) {
  return F8(_mm256_blendv_ps(b.v, a.v, m.v));
}
inline I8 select(M8 m, I8 a, I8 b) {
  return I8{_mm256_castps_si256(_mm256_blendv_ps(_mm256_castsi256_ps(b.v), _mm256_castsi256_ps(a.v), m.v))};
}
inline I8 truncate(F8 a) {
  return I8{_mm256_cvttps_epi32(a.v)};
}
inline F8 toFloat(I8 a) {
  return F8(_mm256_cvtepi32_ps(a.v));
}
inline F8 gather(const float* base, I8 i) {
  return F8(_mm256_i32gather_ps(base, i.v, 4));
}
inline I8 gatherInt(const std::int32_t* base, I8 i) {
  return I8{_mm256_i32gather_epi32(base, i.v, 4)};
}
inline I8 operator+(I8 a, I8 b) {
  return I8{_mm256_add_epi32(a.v, b.v)};
}
inline I8 operator*(I8 a, I8 b) {
  return I8{_mm256_mullo_epi32(a.v, b.v)};
}
inline I8 min(I8 a, I8 b) {
  return I8{_mm256_min_epi32(a.v, b.v)};
}
inline I8 splatInt(std::int32_t x, F8) {
  return I8{_mm256_set1_epi32(x)};
}
inline M8 operator<(I8 a, I8 b) {
  return M8{_mm256_castsi256_ps(_mm256_cmpgt_epi32(b.v, a.v))};
}
inline M8 anyBit(I8 a, std::uint32_t bit) {
  const __m256i zero = _mm256_setzero_si256();
  const __m256i none =
      _mm256_cmpeq_epi32(_mm256_and_si256(a.v, _mm256_set1_epi32(static_cast<std::int32_t>(bit))), zero);
  return M8{_mm256_castsi256_ps(_mm256_xor_si256(none, _mm256_cmpeq_epi32(zero, zero)))};  // not none
}
inline void weigh8(const float* a, float wa, const float* b, float wb, const float* c, float wc, const float* d,
                   float wd, float* out, F8) {
  __m256 r = _mm256_mul_ps(_mm256_set1_ps(wa), _mm256_loadu_ps(a));
  r = _mm256_fmadd_ps(_mm256_set1_ps(wb), _mm256_loadu_ps(b), r);
  r = _mm256_fmadd_ps(_mm256_set1_ps(wc), _mm256_loadu_ps(c), r);
  _mm256_storeu_ps(out, _mm256_fmadd_ps(_mm256_set1_ps(wd), _mm256_loadu_ps(d), r));
}
#endif

/// max(lo, min(x, hi)) in either lane type: NaN gives lo (the second operand wins in both F1's and F8's min/max).
template <class F>
inline F clamp(F x, F lo, F hi) {
  return max(lo, min(x, hi));
}

}  // inline namespace avx2 / baseline
}  // namespace lanes
}  // namespace vision
}  // namespace sensors
}  // namespace unexmin

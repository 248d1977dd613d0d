// The per-pixel shading of ImageFormation (image_formation.h has the model), written once over SIMD lanes
// (lanes.h): F1 runs one pixel at a time, F8 eight side by side (shading_avx2.cpp). No branch per pixel: a light
// that does not reach a pixel gives a selected 0, and every table index is clamped so that each load is in bounds,
// NaN included (clamp() maps it to the low end: a NaN input gives a wrong pixel, never a read out of bounds).
// Plain arrays only (no Eigen): this header is compiled with and without AVX2.
#pragma once

#include <unexmin/raycast/block.h>
#include <unexmin/sensors/vision/lanes.h>

#include <cstdint>

namespace unexmin {
namespace sensors {
namespace vision {
namespace shading {

/// One light of the direct term, camera frame, in the form the kernel reads.
struct Light {
  float position[3];      ///< [m]
  float axis[3];          ///< unit
  float intensity[3];     ///< I0 / pi per channel [W/sr]
  float cos_half = 0.0f;  ///< cos(cone / 2) >= 0
  float cos_half2 = 0.0f;
  float pow_scale = 0.0f;        ///< table index per unit of cos(theta)
  const float* pow_m = nullptr;  ///< profile over cos in [cos_half, 1], pow_last + 2 entries
  std::uint32_t bit = 0;         ///< this light's bit in the pixels' lit masks
};

/// Up to raycast::kBlock pixels (a camera tile) as a structure of arrays (one array per quantity, so that lanes
/// load side by side).
struct Pixels {
  int n = 0;                                                                        ///< pixels in use
  alignas(32) float u[raycast::kBlock], v[raycast::kBlock];                         ///< pixel coordinates [px]
  alignas(32) float range[raycast::kBlock];                                         ///< lens to the surface [m]
  alignas(32) float px[raycast::kBlock], py[raycast::kBlock], pz[raycast::kBlock];  ///< surface point, camera frame [m]
  alignas(32) float nx[raycast::kBlock], ny[raycast::kBlock], nz[raycast::kBlock];  ///< unit normal towards the lens
  alignas(32) float albedo[3][raycast::kBlock];    ///< Lambertian albedo per channel (R, G, B) [-]
  alignas(32) std::uint32_t lit[raycast::kBlock];  ///< bit k: light k reaches the point (no shadow)
  alignas(32) float out[3][raycast::kBlock];       ///< radiance per channel [W m^-2 sr^-1]
};

/// exp(-c x) per channel, 4 floats an entry (R, G, B, 0) over x in [0, last / scale]; pow tables' last index.
struct Tables {
  const float* exp = nullptr;
  float exp_scale = 0.0f;  ///< entries per metre
  float exp_last = 0.0f;   ///< entries - 2 (the interpolation reads index + 1)
  float pow_last = 0.0f;   ///< entries of a light's pow_m - 2
};

/// For the first n pixels of p (n a multiple of the lane width): out = albedo * sum over lights of
/// (I0/pi) cos^m(theta) cos(phi) exp(-c (R_L + R_C)) / R_L^2 (see ImageFormation): the direct term, written (not
/// added) to out.
template <class F>
void direct(Pixels& p, int n, const Light* lights, int count, const Tables& t) {
  using I = typename F::Int;
  const F zero(0.0f), one(1.0f), tiny(1e-12f), exp_scale(t.exp_scale), exp_last(t.exp_last), pow_last(t.pow_last);
  for (int i = 0; i < n; i += F::kWidth) {
    const F px = load(p.px + i, zero), py = load(p.py + i, zero), pz = load(p.pz + i, zero);
    const F nx = load(p.nx + i, zero), ny = load(p.ny + i, zero), nz = load(p.nz + i, zero);
    const F range = load(p.range + i, zero);
    const I lit = loadInt(p.lit + i, zero);
    F s0 = zero, s1 = zero, s2 = zero;
    for (int k = 0; k < count; ++k) {
      const Light& l = lights[k];
      const F vx = px - F(l.position[0]), vy = py - F(l.position[1]), vz = pz - F(l.position[2]);  // light -> surface
      const F ca = F(l.axis[0]) * vx + F(l.axis[1]) * vy + F(l.axis[2]) * vz;                      // r cos(theta)
      const F r2 = max(vx * vx + vy * vy + vz * vz, tiny);
      const F cos_phi = zero - (nx * vx + ny * vy + nz * vz);  // r cos(incidence)
      // Inside the cone (ca > cos_half r with cos_half >= 0, tested without the square root), lit from the front.
      const auto on = (ca > zero) & (ca * ca > F(l.cos_half2) * r2) & (cos_phi > zero) & anyBit(lit, l.bit);
      if (none(on))
        continue;  // a light that reaches none of these pixels (most lights, in most tiles)
      const F inv_r = one / sqrt(r2);
      const F r = r2 * inv_r;
      const F fi = clamp((ca * inv_r - F(l.cos_half)) * F(l.pow_scale), zero, pow_last);
      const I ip = truncate(fi);
      const F p0 = gather(l.pow_m, ip), p1 = gather(l.pow_m + 1, ip);
      const F pw = p0 + (fi - toFloat(ip)) * (p1 - p0);
      // exp(-c x) at x = R_C + R_L; 0 beyond the table.
      const F fe = clamp((range + r) * exp_scale, zero, exp_last);
      const I ie = truncate(fe);
      const F we = fe - toFloat(ie);
      const I e4 = ie * splatInt(4, zero);
      const F g = select(on & (fe < exp_last), pw * cos_phi * inv_r * inv_r * inv_r, zero);
      const F e0 = gather(t.exp, e4), e1 = gather(t.exp + 1, e4), e2 = gather(t.exp + 2, e4);
      s0 = s0 + F(l.intensity[0]) * g * (e0 + we * (gather(t.exp + 4, e4) - e0));
      s1 = s1 + F(l.intensity[1]) * g * (e1 + we * (gather(t.exp + 5, e4) - e1));
      s2 = s2 + F(l.intensity[2]) * g * (e2 + we * (gather(t.exp + 6, e4) - e2));
    }
    store(p.out[0] + i, s0 * load(p.albedo[0] + i, zero));
    store(p.out[1] + i, s1 * load(p.albedo[1] + i, zero));
    store(p.out[2] + i, s2 * load(p.albedo[2] + i, zero));
  }
}

/// The backscatter table: nu x nv pixel nodes, bins + 1 range edges s (bin j spans [s_j, s_j+1]), 4 floats per
/// (node, edge) (R, G, B, 0).
struct Backscatter {
  const float* table = nullptr;
  const float* edge = nullptr;     ///< s_j [m], bins + 1
  const float* inv_bin = nullptr;  ///< 1 / (s_j+1 - s_j), bins
  int nu = 2, nv = 2, bins = 1;
  float inv_step_u = 1.0f, inv_step_v = 1.0f, inv_range = 1.0f;  ///< nodes per px, 1 / s_bins
};

/// For the first n pixels of p (n a multiple of the lane width): out += the backscatter along each pixel's ray to
/// its range (clamped to [0, s_bins]): bilinear in the pixel, linear in range. First, in lanes, each pixel's cell
/// (first node and bin) and its weights; then per pixel the 8 floats a node holds for the two bin edges around the
/// range (both edges, all channels: one load in AVX), weighted over the cell's four nodes, and the range's weight
/// between the two edges.
template <class F>
void backscatter(Pixels& p, int n, const Backscatter& b) {
  using I = typename F::Int;
  alignas(32) std::int32_t cell[raycast::kBlock];
  alignas(32) float weight[5][raycast::kBlock];  // the four nodes' (00, 10, 01, 11), then range's
  const F zero(0.0f), one_f(1.0f), max_u(static_cast<float>(b.nu - 1)), max_v(static_cast<float>(b.nv - 1));
  const F s_max(b.edge[b.bins]), inv_range(b.inv_range), bins_f(static_cast<float>(b.bins));
  const I last_node_u = splatInt(b.nu - 2, zero), last_node_v = splatInt(b.nv - 2, zero);
  const I last_bin = splatInt(b.bins - 1, zero), bins = splatInt(b.bins, zero), one = splatInt(1, zero);
  const I minus_one = splatInt(-1, zero), nu = splatInt(b.nu, zero), four = splatInt(4, zero);
  const int stride = (b.bins + 1) * 4;  // floats per node
  const I node_stride = splatInt(stride, zero);
  for (int i = 0; i < n; i += F::kWidth) {
    const F fu = clamp(load(p.u + i, zero) * F(b.inv_step_u), zero, max_u);
    const F fv = clamp(load(p.v + i, zero) * F(b.inv_step_v), zero, max_v);
    const I iu = min(truncate(fu), last_node_u), iv = min(truncate(fv), last_node_v);
    const F wu = fu - toFloat(iu), wv = fv - toFloat(iv);
    const F rr = clamp(load(p.range + i, zero), zero, s_max);
    I j = min(truncate(sqrt(rr * inv_range) * bins_f), last_bin);
    // Rounding in the square root may land one bin off: step to the bin that holds rr.
    j = select(rr < gather(b.edge, j), j + minus_one, j);
    const I next = j + one;
    j = select((next < bins) & (rr > gather(b.edge, min(next, bins))), next, j);
    storeInt(cell + i, (iv * nu + iu) * node_stride + j * four);
    store(weight[0] + i, (one_f - wu) * (one_f - wv));
    store(weight[1] + i, wu * (one_f - wv));
    store(weight[2] + i, (one_f - wu) * wv);
    store(weight[3] + i, wu * wv);
    store(weight[4] + i, (rr - gather(b.edge, j)) * gather(b.inv_bin, j));
  }
  const int down = b.nu * stride;
  for (int i = 0; i < n; ++i) {
    const float* n00 = b.table + cell[i];
    const float* n10 = n00 + stride;
    const float* n01 = n00 + down;
    const float* n11 = n01 + stride;
    const float w00 = weight[0][i], w10 = weight[1][i], w01 = weight[2][i], w11 = weight[3][i], wr = weight[4][i];
    float at[8];  // bin edge j (R, G, B, 0), then j + 1
    weigh8(n00, w00, n10, w10, n01, w01, n11, w11, at, zero);
    for (int c = 0; c < 3; ++c)
      p.out[c][i] += at[c] + wr * (at[c + 4] - at[c]);
  }
}

/// The response of the camera's image sensor (CameraSensor has the model): radiance -> 8-bit code per channel.
struct SensorResponse {
  float exposure = 0.0f;  ///< fraction of full well per unit radiance
  float gain = 1.0f;
  float shot = 0.0f;                     ///< 1 / full_well
  float read2 = 0.0f;                    ///< (read_noise / full_well)^2
  const float* normal = nullptr;         ///< standard normal quantiles, indexed by Pixels' noise indices
  const std::int32_t* encode = nullptr;  ///< gamma table: code of signal i / encode_last, encode_last + 1 entries
  float encode_last = 0.0f;
};

/// code[c][i] = encode[round(encode_last * clamp(gain * (s + sqrt(s shot + read2) N), 0, 1))] with
/// s = min(1, exposure radiance[c][i]) and N = normal[noise[c][i]] (noise null: no noise), for i in [0, n).
template <class F>
void sensorResponse(const SensorResponse& s, int n, float* const radiance[3], const std::int32_t* const noise[3],
                    std::int32_t* const code[3]) {
  const F zero(0.0f), one(1.0f), half(0.5f), exposure(s.exposure), gain(s.gain), shot(s.shot), read2(s.read2);
  const F last(s.encode_last);
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < n; i += F::kWidth) {
      F signal = min(exposure * load(radiance[c] + i, zero), one);
      if (noise[c])
        signal = signal + sqrt(signal * shot + read2) * gather(s.normal, loadInt(noise[c] + i, zero));
      const F level = clamp(gain * signal, zero, one) * last + half;
      storeInt(code[c] + i, gatherInt(s.encode, truncate(level)));
    }
}

/// The AVX2 + FMA builds of the three (shading_avx2.cpp); call only where avx2Built() and the CPU has both.
void directAvx2(Pixels& p, int n, const Light* lights, int count, const Tables& t);
void backscatterAvx2(Pixels& p, int n, const Backscatter& b);
void sensorResponseAvx2(const SensorResponse& s, int n, float* const radiance[3], const std::int32_t* const noise[3],
                        std::int32_t* const code[3]);
/// Whether the two above were built for AVX2 + FMA (x86-64 with GCC or Clang).
bool avx2Built();

}  // namespace shading
}  // namespace vision
}  // namespace sensors
}  // namespace unexmin

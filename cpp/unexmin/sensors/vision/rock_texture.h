// A procedural solid texture (no texture coordinates): the albedo and the shading normal of a surface at a point of
// the mesh's own frame, from a field of value noise (a hashed lattice of the material's seed, smoothstep
// interpolation, analytic gradient) at the material's scales (sim::Material, docs/vision.md "Materials"):
//
//   grain   g(p) = n(p / s_g)                                        (one octave)
//   cracks  k(p) = -max(0, 1 - |n(p / s_k)| / 0.12)^2               (thin dark lines where the noise crosses 0)
//   strata  t(p) = sin(2 pi (z / s_t + n(p / s_s) / 2))            (bands along the mesh frame's z, warped)
//   stains  s(p) = n(p / s_s)                                       (blotches)
//
// Each component is centred and scaled to unit standard deviation (its mean and standard deviation over the
// noise, computed once), and they are summed with the kind's weights w_i: f = sum w_i c_i / sqrt(sum w_i^2) (zero
// mean, standard deviation 1 when the components are independent). Then
//
//   albedo_k(p) = clip(A_k (1 + contrast f(p)) (1 + tint d_k r(p)), 0, 1)
//
// with A the material's albedo, r a unit-variance noise at the `region` scale and d a seeded direction in colour
// space (|d_k| <= 1): the texture modulates around A (mean A, relative standard deviation `contrast` before the
// clipping, for tint 0). Relief: the height field h(p) = sum w_i s_i c_i / (G_i sqrt(sum w_i^2)) [m] over grain,
// cracks and strata (the stains are colour, not shape), with G_i the RMS of |grad c_i| per unit of its scale (so each
// component has an RMS slope of 1 and h one of about 1; for the strata G = 2 pi, their warp neglected), tilts the
// shading normal n:
//
//   n' = normalize(n - relief (grad h - (grad h . n) n))      so tan(tilt) = relief |grad_t h|
//
// Knows no ROS; one evaluation per pixel hit (two to four lattice octaves, no allocation).
#pragma once

#include <unexmin/sim/material.h>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>

namespace unexmin {
namespace sensors {
namespace vision {

/// A texture's constants as the eight-lane kernel (rock_texture_avx2.cpp) reads them.
struct RockLanes {
  std::uint32_t seed[5];
  float inv_scale[5], weight[4], height[4], albedo[3], tint[3];
  float contrast, relief, crack_width;
  float value_sd, grain_mean, grain_sd, crack_mean, crack_sd;
  bool tinted;
  /// The slow noises as linear over one batch (shadeMany), about its bounding box's centre `origin` [m]: the region
  /// noise r = region0 + region_grad . (p - origin), the stains' unit noise s = stain0 + stain_grad . (p - origin).
  bool region_linear, stain_linear;
  float origin[3], region0, region_grad[3], stain0, stain_grad[3];
};
/// Whether this build has the eight-lane kernel (x86-64 built with AVX2 and FMA).
bool rockAvx2Built();
/// RockTexture::shade of the first n points (n a multiple of 8), eight at a time: the CPU must have AVX2 and FMA.
void rockShadeAvx2(const RockLanes& k, int n, const float* px, const float* py, const float* pz, float* nx, float* ny,
                   float* nz, float* const albedo[3]);
/// The bounding box (lo[0..2], hi[0..2]) of the first n points (n a positive multiple of 8), eight at a time: the CPU
/// must have AVX2.
void rockBoundsAvx2(int n, const float* px, const float* py, const float* pz, float* lo, float* hi);
/// (ox, oy, oz)[i] = m (x, y, z)[i] + t for the first n points (n a multiple of 8; m row-major 3 x 3, t 3 numbers;
/// the outputs may be the inputs), eight at a time: the CPU must have AVX2 and FMA.
void rockTransformAvx2(int n, const float* m, const float* t, const float* x, const float* y, const float* z, float* ox,
                       float* oy, float* oz);

class RockTexture {
public:
  /// Throws ParameterError naming the key of the first bad value of `m` (sim::checkMaterial); `prefix` is put
  /// before the key in the message.
  explicit RockTexture(const sim::Material& m, const std::string& prefix = "");

  const sim::Material& material() const { return m_; }

  /// The texture field f at point `p` of the mesh frame [m]: zero mean, unit standard deviation [-]; `gradient`
  /// (if not null): grad f [1/m].
  float field(const Eigen::Vector3f& p, Eigen::Vector3f* gradient = nullptr) const;
  /// The relief's height field h at `p` [m] and, if not null, its gradient [-].
  float height(const Eigen::Vector3f& p, Eigen::Vector3f* gradient = nullptr) const;
  /// Albedo (R, G, B) at `p` [-].
  Eigen::Array3f albedo(const Eigen::Vector3f& p) const;
  /// Shading normal at `p` of a surface of unit normal `n` (both in the mesh frame): unit, tilted by the relief.
  Eigen::Vector3f normal(const Eigen::Vector3f& p, const Eigen::Vector3f& n) const;
  /// Both at once (one evaluation of the field): albedo into `albedo[0..2]`, the tilted unit normal into `shading`.
  /// `linear` (shadeMany's): where its region_linear or stain_linear is set, that noise is the linear function.
  void shade(const Eigen::Vector3f& p, const Eigen::Vector3f& n, float* albedo, Eigen::Vector3f& shading,
             const RockLanes* linear = nullptr) const;
  /// shade() of n points at once (mesh frame; coordinates px, py, pz [m]); the unit normals nx, ny, nz are tilted in
  /// place, the albedo goes to albedo[c][0..n). `simd` (and a CPU with AVX2 and FMA): eight at a time, the same
  /// values up to rounding (FMA, the sine's polynomial). The slow noises (regions, stains) are evaluated once, at the
  /// centre of the batch's bounding box, with their gradients, and each taken as linear over the batch when the box
  /// is within 0.04 of its scale on every axis (the tiles of a frame): the albedo then differs from shade()'s by
  /// second-order terms (below 0.5 % of it at the defaults, tested).
  void shadeMany(int n, const float* px, const float* py, const float* pz, float* nx, float* ny, float* nz,
                 float* const albedo[3], bool simd) const;

  /// shadeMany() of n points given in another frame A: the mesh frame's p = rotation p_A + translation. Points
  /// px, py, pz (frame A [m], left as they are) and unit normals nx, ny, nz (frame A, tilted in place, still in frame
  /// A); albedo into albedo[c][0..n). The transforms run in lanes too with `simd`.
  void shadeManyFrom(const Eigen::Matrix3f& rotation, const Eigen::Vector3f& translation, int n, const float* px,
                     const float* py, const float* pz, float* nx, float* ny, float* nz, float* const albedo[3],
                     bool simd) const;

private:
  /// f at p; grad f into `gf`, h into `h`, grad h into `gh` and the region noise r into `region`.
  float evaluate(const Eigen::Vector3f& p, Eigen::Vector3f& gf, float& h, Eigen::Vector3f& gh, float& region,
                 const RockLanes* linear = nullptr) const;
  void albedoOf(float f, float region, float* out) const;

  sim::Material m_;
  RockLanes lanes_;              ///< the same constants for the eight-lane kernel
  std::uint32_t seed_[6];        ///< per lattice: grain, spare, cracks, stains, region, spare
  float inv_scale_[5];           ///< 1 / scale of grain, cracks, strata, stains, region [1/m] (0: off)
  std::array<float, 4> weight_;  ///< w_i / sqrt(sum w^2) of the components that are on
  std::array<float, 4> height_;  ///< weight_ x scale [m]
  Eigen::Array3f albedo_;
  Eigen::Array3f tint_;  ///< tint d_k
  float contrast_, relief_;
};

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin

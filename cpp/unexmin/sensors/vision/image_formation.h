// Underwater image formation for a camera lit only by lights that travel with it (Jaffe-McGlamery; no ambient
// light: the mine is dark). Per RGB channel, the radiance reaching the lens [W m^-2 sr^-1] along a pixel ray that
// meets a Lambertian surface at range R_C is
//
//   direct       E_d = sum_L (rho / pi) I_L(theta) cos(phi) exp(-c (R_L + R_C)) / R_L^2
//   backscatter  E_b = sum_L int_0^R_C b p(psi) I_L(theta_s) exp(-c (s + r_L)) / r_L^2 ds
//
// with, for light L: R_L its distance to the surface point, theta the angle of that point off the light's axis,
// I_L(theta) = I0 cos^m(theta) inside the light's cone (0 outside), phi the angle of incidence of the light on the
// surface (no light from behind it); along the pixel ray at distance s, r_L the distance from the light, theta_s
// the angle off its axis and psi the scattering angle between the light's direction of travel and the direction
// back to the lens; c = a + b and b from WaterOptics, p the Henyey-Greenstein phase function.
//
// Since the lights are fixed to the camera's robot, E_b depends only on the pixel and the range: it is integrated
// once (Simpson, in the camera frame) on a grid of pixel rays (at most 65 x 49 nodes spanning the image) and range
// bins (64 bins, s_j = max_range (j / 64)^2, finer near the lens) and interpolated (bilinear in the pixel,
// linear in range). The direct term is evaluated per pixel with tabulated exp(-c x) and cos^m (relative error
// below 1e-3). Lights that cannot reach anything the camera sees within max_range are skipped.
// Everything here is in the camera's optical frame (z forward). Knows no ROS.
#pragma once

#include <unexmin/sensors/vision/camera_model.h>
#include <unexmin/sensors/vision/water_optics.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <vector>

namespace unexmin {
namespace sensors {
namespace vision {

/// An LED lamp: a cone of light of radiant intensity I0 cos^m(theta), its edge softened over the outer kEdge of the
/// half angle (a smoothstep down to 0 at cone / 2, as a reflector's beam ends) [assumed].
struct LedLight
{
  static constexpr double kEdge = 0.2;  ///< fraction of the half angle over which the beam fades out
  Eigen::Vector3d position{0, 0, 0};   ///< camera optical frame [m]
  Eigen::Vector3d axis{0, 0, 1};       ///< unit, camera optical frame (the light link's +x)
  Eigen::Vector3d intensity{1, 1, 1};  ///< I0: on-axis radiant intensity per channel (R, G, B) [W/sr]
  double cone = M_PI / 2.0;            ///< full cone angle [rad]: no light beyond cone / 2 off the axis
  double exponent = 1.0;               ///< m of I0 cos^m(theta) [-]

  /// Radiant intensity per channel toward a direction with cos(theta) = cos_theta off the axis [W/sr].
  Eigen::Vector3d at(double cos_theta) const;
  /// I(theta) / I0 [-]: cos^m(theta) times the edge's fade, 0 beyond cone / 2.
  double profile(double cos_theta) const;
};

class ImageFormation
{
public:
  static constexpr int kPowEntries = 1024;  ///< cos^m table over [cos_half, 1]
  static constexpr int kExpEntries = 8192;  ///< exp(-c x) table over [0, x_max]

  /// `camera`: the image the pixels refer to; `lights` in its optical frame; `max_range` [m] > 0: the farthest
  /// surface (beyond it a ray sees open water up to max_range). `threads` builds the table (0 = all).
  ImageFormation(const CameraModel& camera, std::vector<LedLight> lights, const WaterOptics& water, double max_range,
                 int threads = 0);

  const WaterOptics& water() const { return water_; }
  const std::vector<LedLight>& lights() const { return lights_; }
  double maxRange() const { return max_range_; }
  /// Indices of the lights that reach some point the camera sees within max_range (the others are skipped).
  const std::vector<int>& activeLights() const { return active_; }

  /// Direct radiance at the lens [W m^-2 sr^-1] per channel from a surface point `p` [m] (camera frame, at range
  /// |p| from the lens) of unit normal `n` (towards the lens) and albedo `albedo`, lit by the lights whose bit is
  /// set in `lit` (bit k: light k reaches p; all by default). Per-pixel fast path (tabulated exp and cos^m).
  Eigen::Array3f direct(const Eigen::Vector3f& p, float range, const Eigen::Vector3f& n, const Eigen::Array3f& albedo,
                        unsigned lit = ~0u) const
  {
    return direct4(p, range, n, Eigen::Array4f(albedo[0], albedo[1], albedo[2], 0.0f), lit).head<3>();
  }
  /// Backscatter radiance [W m^-2 sr^-1] per channel along the ray of pixel (u, v) [px] from the lens to range `r`
  /// [m] (clamped to [0, max_range]), interpolated from the table.
  Eigen::Array3f backscatter(float u, float v, float r) const { return backscatter4(u, v, r).head<3>(); }
  /// The same two with the channels in the first 3 of 4 lanes (SIMD-friendly; the 4th lane is 0).
  Eigen::Array4f direct4(const Eigen::Vector3f& p, float range, const Eigen::Vector3f& n, const Eigen::Array4f& albedo,
                         unsigned lit = ~0u) const;
  Eigen::Array4f backscatter4(float u, float v, float r) const;
  /// Whether light `k` can light point `p` (camera frame) from the front of a surface of normal `n`: inside its
  /// cone and not behind the surface. Decides which shadow rays are cast.
  bool lights(int k, const Eigen::Vector3f& p, const Eigen::Vector3f& n) const;

  /// exp(-c_k x) per channel from the table, x >= 0 [m].
  Eigen::Array3f transmission(float x) const { return transmission4(x).head<3>(); }

private:
  Eigen::Array4f transmission4(float x) const;
  /// Sum over active lights of b p(psi) I(theta) exp(-c (s + r)) / r^2 at distance s along unit ray d.
  Eigen::Array3d integrand(const Eigen::Vector3d& d, double s, std::vector<char>* reached) const;
  void buildTable(const CameraModel& camera, int threads);

  WaterOptics water_;
  std::vector<LedLight> lights_;
  double max_range_;
  std::vector<int> active_;

  // Per-light constants of the fast path (float, camera frame).
  struct Fast
  {
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
    Eigen::Vector3f position, axis;
    Eigen::Array4f intensity;   ///< I0 / pi [W/sr] (4th lane 0)
    float cos_half = 0.0f;      ///< cos(cone / 2), >= 0 (a cone is at most a half space)
    float cos_half2 = 0.0f;     ///< cos_half^2
    std::vector<float> pow_m;   ///< cos^m over cos in [cos_half, 1]
    float pow_scale = 0.0f;     ///< table index per unit of cos
  };
  std::vector<Fast> fast_;
  std::vector<double> reach_cos_;  ///< cos(cone / 2 + margin): a grid ray this close keeps the light active
  // exp(-c x): 4 floats per entry (R, G, B, 0) over [0, x_max].
  std::vector<float> exp_;
  float exp_scale_ = 0.0f;  ///< entries per metre

  // Backscatter table: nodes nu_ x nv_ (pixel (i step_u_, j step_v_)), bins_ + 1 ranges, 3 channels.
  int nu_ = 2, nv_ = 2, bins_ = 64;
  float step_u_ = 1.0f, step_v_ = 1.0f;
  float inv_step_u_ = 1.0f, inv_step_v_ = 1.0f, inv_range_ = 1.0f;
  std::vector<float> s_;      ///< range of each bin edge [m]
  std::vector<float> inv_bin_;  ///< 1 / bin width [1/m]
  std::vector<float> table_;  ///< [(node * (bins + 1) + j) * 4 + channel] (4th lane 0)
};

// ---------------------------------------------------------------- the per-pixel fast path, inline

inline Eigen::Array4f ImageFormation::transmission4(float x) const
{
  const float f = std::max(0.0f, x) * exp_scale_;
  const int i = static_cast<int>(f);
  if (i >= kExpEntries) return Eigen::Array4f::Zero();
  const Eigen::Map<const Eigen::Array4f> e0(&exp_[4 * i]), e1(&exp_[4 * i + 4]);
  return e0 + (f - static_cast<float>(i)) * (e1 - e0);
}

inline Eigen::Array4f ImageFormation::direct4(const Eigen::Vector3f& p, float range, const Eigen::Vector3f& n,
                                       const Eigen::Array4f& albedo, unsigned lit) const
{
  Eigen::Array4f sum = Eigen::Array4f::Zero();
  for (int k : active_) {
    if (!(lit & (1u << k))) continue;
    const Fast& l = fast_[static_cast<std::size_t>(k)];
    const Eigen::Vector3f v = p - l.position;  // light -> surface
    const float ca = l.axis.dot(v);            // r cos(theta)
    const float r2 = v.squaredNorm();
    // Outside the cone (ca <= cos_half r, with cos_half >= 0), tested without the square root.
    if (!(ca > 0.0f) || !(ca * ca > l.cos_half2 * r2)) continue;
    const float cos_phi = -n.dot(v);  // r cos(incidence)
    if (!(cos_phi > 0.0f)) continue;  // lit from behind
    const float inv_r = 1.0f / std::sqrt(r2);
    const float r = r2 * inv_r;
    const float fi = (ca * inv_r - l.cos_half) * l.pow_scale;
    const int i = std::min(static_cast<int>(fi), kPowEntries);
    const float pw = l.pow_m[i] + (fi - static_cast<float>(i)) * (l.pow_m[i + 1] - l.pow_m[i]);
    sum += l.intensity * (pw * cos_phi * inv_r * inv_r * inv_r) * transmission4(range + r);
  }
  return albedo * sum;
}

inline Eigen::Array4f ImageFormation::backscatter4(float u, float v, float r) const
{
  const float fu = std::min(std::max(u * inv_step_u_, 0.0f), static_cast<float>(nu_ - 1));
  const float fv = std::min(std::max(v * inv_step_v_, 0.0f), static_cast<float>(nv_ - 1));
  const int iu = std::min(static_cast<int>(fu), nu_ - 2), iv = std::min(static_cast<int>(fv), nv_ - 2);
  const float wu = fu - static_cast<float>(iu), wv = fv - static_cast<float>(iv);
  const float rr = std::min(std::max(r, 0.0f), s_.back());
  int j = std::min(static_cast<int>(std::sqrt(rr * inv_range_) * static_cast<float>(bins_)), bins_ - 1);
  // Rounding in the square root may land one bin off: step to the bin that holds rr.
  if (rr < s_[j]) --j;
  else if (j + 1 < bins_ && rr > s_[j + 1]) ++j;
  const float wr = (rr - s_[j]) * inv_bin_[j];
  const std::size_t stride = static_cast<std::size_t>((bins_ + 1) * 4);
  const float* n00 = &table_[static_cast<std::size_t>(iv * nu_ + iu) * stride + j * 4];
  using Map = Eigen::Map<const Eigen::Array4f>;
  const auto at = [&](const float* node) { return Map(node) + wr * (Map(node + 4) - Map(node)); };
  const Eigen::Array4f top = at(n00) + wu * (at(n00 + stride) - at(n00));
  const float* n01 = n00 + nu_ * stride;
  const Eigen::Array4f bottom = at(n01) + wu * (at(n01 + stride) - at(n01));
  return top + wv * (bottom - top);
}

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin

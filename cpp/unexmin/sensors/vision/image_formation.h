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
// below 1e-3). Lights that cannot reach anything the camera sees within max_range are skipped. Both terms run in
// the kernels of shading_kernels.h, on a PixelBatch of up to raycast::kBlock = 64 pixels, eight at a time where the
// CPU has AVX2.
// Everything here is in the camera's optical frame (z forward). Knows no ROS.
#pragma once

#include <unexmin/sensors/vision/camera_model.h>
#include <unexmin/sensors/vision/shading_kernels.h>
#include <unexmin/sensors/vision/water_optics.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace unexmin {
namespace sensors {
namespace vision {

/// An LED lamp: a cone of light of radiant intensity I0 cos^m(theta), its edge softened over the outer kEdge of the
/// half angle (a smoothstep down to 0 at cone / 2, as a reflector's beam ends) [assumed].
struct LedLight {
  static constexpr double kEdge = 0.2;  ///< fraction of the half angle over which the beam fades out
  Eigen::Vector3d position{0, 0, 0};    ///< camera optical frame [m]
  Eigen::Vector3d axis{0, 0, 1};        ///< unit, camera optical frame (the light link's +x)
  Eigen::Vector3d intensity{1, 1, 1};   ///< I0: on-axis radiant intensity per channel (R, G, B) [W/sr]
  double cone = M_PI / 2.0;             ///< full cone angle [rad]: no light beyond cone / 2 off the axis
  double exponent = 1.0;                ///< m of I0 cos^m(theta) [-]

  /// Radiant intensity per channel toward a direction with cos(theta) = cos_theta off the axis [W/sr].
  Eigen::Vector3d at(double cos_theta) const;
  /// I(theta) / I0 [-]: cos^m(theta) times the edge's fade, 0 beyond cone / 2.
  double profile(double cos_theta) const;
};

/// Up to raycast::kBlock pixels of one tile (shading::Pixels) as the camera fills them. A pixel that sees no surface
/// has range = max_range, albedo 0 and normal 0 (backscatter only).
struct PixelBatch : shading::Pixels {
  /// Sets pixel i: (u, v), the surface at `range` (point p, normal n, albedo a), lit by the bits of `lit_mask`.
  void set(int i, float pu, float pv, float r, const Eigen::Vector3f& p, const Eigen::Vector3f& normal, const float* a,
           std::uint32_t lit_mask) {
    u[i] = pu;
    v[i] = pv;
    range[i] = r;
    px[i] = p.x();
    py[i] = p.y();
    pz[i] = p.z();
    nx[i] = normal.x();
    ny[i] = normal.y();
    nz[i] = normal.z();
    albedo[0][i] = a[0];
    albedo[1][i] = a[1];
    albedo[2][i] = a[2];
    lit[i] = lit_mask;
  }
  /// Sets pixel i as open water up to `max_range` (no surface).
  void setWater(int i, float pu, float pv, float max_range) {
    static const float zero[3] = {0.0f, 0.0f, 0.0f};
    set(i, pu, pv, max_range, Eigen::Vector3f::Zero(), Eigen::Vector3f::Zero(), zero, 0u);
  }

  /// radiance() also writes the direct term alone into `direct` (forward scattering and silt read it)
  bool keep_direct = false;
  alignas(32) float direct[3][raycast::kBlock];  ///< the direct term per channel [W m^-2 sr^-1] (if keep_direct)
};

class ImageFormation {
public:
  static constexpr int kPowEntries = 1024;  ///< cos^m table over [cos_half, 1]
  static constexpr int kExpEntries = 8192;  ///< exp(-c x) table over [0, x_max]

  /// `camera`: the image the pixels refer to; `lights` in its optical frame; `max_range` [m] > 0: the farthest
  /// surface (beyond it a ray sees open water up to max_range). `threads` builds the table (0 = all).
  ImageFormation(const CameraModel& camera, std::vector<LedLight> lights, const WaterOptics& water, double max_range,
                 int threads = 0);
  ImageFormation(const ImageFormation&) = delete;  // the kernels' views point into its tables
  ImageFormation& operator=(const ImageFormation&) = delete;

  const WaterOptics& water() const { return water_; }
  const std::vector<LedLight>& lights() const { return lights_; }
  double maxRange() const { return max_range_; }
  /// Indices of the lights that reach some point the camera sees within max_range (the others are skipped).
  const std::vector<int>& activeLights() const { return active_; }

  /// Direct radiance at the lens [W m^-2 sr^-1] per channel from a surface point `p` [m] (camera frame, at range
  /// |p| from the lens) of unit normal `n` (towards the lens) and albedo `albedo`, lit by the lights whose bit is
  /// set in `lit` (bit k: light k reaches p; all by default): one pixel of radiance() (tabulated exp and cos^m).
  Eigen::Array3f direct(const Eigen::Vector3f& p, float range, const Eigen::Vector3f& n, const Eigen::Array3f& albedo,
                        unsigned lit = ~0u) const;
  /// Backscatter radiance [W m^-2 sr^-1] per channel along the ray of pixel (u, v) [px] from the lens to range `r`
  /// [m] (clamped to [0, max_range]), interpolated from the table: one pixel of radiance().
  Eigen::Array3f backscatter(float u, float v, float r) const;
  /// Radiance at the lens of every pixel of `batch` (direct + backscatter, into batch.out; the direct term alone
  /// also into batch.direct when batch.keep_direct). `simd` (and
  /// simdAvailable()): eight pixels side by side in AVX2 lanes; else one at a time. Same kernels either way
  /// (shading_kernels.h); the results differ only by rounding (FMA), about 1e-7 relative.
  /// The silt the thrusters raised is the camera's to add afterwards (SiltView::apply, with keep_direct set).
  void radiance(PixelBatch& batch, bool simd = true) const;
  /// Whether this build and this CPU run the eight-lane kernels (x86-64 with AVX2 and FMA).
  static bool simdAvailable();
  /// Whether light `k` can light point `p` (camera frame) from the front of a surface of normal `n`: inside its
  /// cone and not behind the surface. Decides which shadow rays are cast.
  bool canLight(int k, const Eigen::Vector3f& p, const Eigen::Vector3f& n) const;

private:
  /// Sum over active lights of b p(psi) I(theta) exp(-c (s + r)) / r^2 at distance s along unit ray d.
  Eigen::Array3d integrand(const Eigen::Vector3d& d, double s, std::vector<char>* reached) const;
  void buildTable(const CameraModel& camera, int threads);

  WaterOptics water_;
  std::vector<LedLight> lights_;
  double max_range_;
  std::vector<int> active_;

  // Per light, as the shading kernels read them (float, camera frame), and its cos^m table over [cos_half, 1].
  std::vector<shading::Light> light_f_;
  std::vector<std::vector<float>> pow_m_;
  std::vector<double> reach_cos_;  ///< cos(cone / 2 + margin): a grid ray this close keeps the light active
  // exp(-c x): 4 floats per entry (R, G, B, 0) over [0, x_max].
  std::vector<float> exp_;
  // Backscatter table (its shape in backscatter_): nu x nv pixel nodes, bins + 1 range edges, 4 floats each.
  std::vector<float> s_;        ///< range of each bin edge [m]
  std::vector<float> inv_bin_;  ///< 1 / bin width [1/m]
  std::vector<float> table_;    ///< [(node * (bins + 1) + j) * 4 + channel] (4th lane 0)

  // The active lights and the tables as the shading kernels read them (pointers into the vectors above, and the
  // tables' scales and shape).
  std::vector<shading::Light> kernel_lights_;
  shading::Tables tables_;
  shading::Backscatter backscatter_;
};

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin

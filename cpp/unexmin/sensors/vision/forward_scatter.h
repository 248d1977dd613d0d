// Forward scattering of the image (the third term of Jaffe's model, after the direct and backscatter terms of
// ImageFormation): light from the surface that the water scatters by a small angle on its way to the lens is not lost
// (as exp(-c R) in the direct term counts it) but arrives a little off its true direction, so the direct image is
// blurred and brightened by an amount that grows with range R and turbidity.
//
// Model (small-angle multiple forward scattering; the image-spread argument of Wells 1973, written out here):
// scattering by angles below kLobe (the forward lobe of the water's Henyey-Greenstein phase function; eta = its share
// of the scattering coefficient b, <theta^2> its mean square angle) keeps light in the image. Along the camera leg of
// length R a ray undergoes a Poisson number of such scatterings, of mean lambda = eta b R. One scattering at
// distance z from the lens by angle theta moves the apparent direction of a point by theta (R - z) / R: uniform in z,
// that is a mean square <theta^2> / 3 per scattering, so the image of a point is
//   PSF = exp(-lambda) delta + (1 - exp(-lambda)) G(sigma_h)
// of total power exp(-(a + (1 - eta) b) R), with G a two-dimensional Gaussian whose standard deviation per image
// axis is sigma_h^2 = (<theta^2> / 6) lambda / (1 - exp(-lambda)) (the mean number of scatterings of the light
// scattered at least once) and the whole PSF's mean square width per axis sigma^2 = lambda <theta^2> / 6: it vanishes
// as b -> 0. Relative to the direct term (already attenuated by exp(-c R)) the halo's weight is exp(lambda) - 1.
// Only the camera leg blurs the image (scattering on the lights' leg spreads the illumination, not the picture).
//
// Per frame: each tile of the image (cell x cell pixels) sums its pixels' halo light, direct x (exp(lambda) - 1), in
// one of kBands range bands (edges max_range (k / kBands)^2); each band's grid is blurred by a Gaussian of the band's
// halo width (sigma_h at the band's middle range, in pixels through the focal length, normalised at the image's
// edges: what lies beyond the frame is taken as what lies at its edge) and the sum is interpolated back to every
// pixel (bilinear between tile centres). Widths below about half a cell come out as about half a cell.
// Clear water is left alone: below kMinScattering (the `none` level) the pass does not run, unless the camera sees
// silt (sim::SedimentField): the silt's own scattering on the camera leg, of optical depth tau, is taken to have the
// water's phase function [assumed], so it adds eta tau forward scatterings to the pixel's lambda (its halo weight
// exp(lambda + eta tau) - 1), spread with the water's band widths [assumed: the silt's scatterings would widen it].
// Knows no ROS.
#pragma once

#include <unexmin/raycast/ray_caster.h>
#include <unexmin/sensors/vision/water_optics.h>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace unexmin {
namespace sensors {
namespace vision {

class ForwardScatter {
public:
  static constexpr int kBands = 8;  ///< range bands of the halo's width
  static constexpr double kLobe =
      10.0 * M_PI / 180;  ///< [rad] scattering below this keeps light in the image [assumed]
  /// [1/m] the pass runs only where some channel's b reaches this (not in the `none` water, b = 0.037): there the
  /// halo holds at most eta b R = 4.5 % of the direct light at 2 m [assumed threshold].
  static constexpr double kMinScattering = 0.1;

  /// Whether `water` scatters enough for the pass (b >= kMinScattering in some channel).
  static bool needed(const WaterOptics& water);
  /// The share eta of Henyey-Greenstein scattering of asymmetry g within `lobe` [rad] of the forward direction, and
  /// the mean square angle <theta^2> [rad^2] of that share (numerical integration).
  static void lobe(double g, double lobe, double& eta, double& mean_square);

  /// `water`; `max_range` [m] > 0 (the camera's clip_far); `focal` [px] the image's focal length; the image's
  /// `width` x `height` [px] in cells of `cell` px.
  ForwardScatter(const WaterOptics& water, double max_range, double focal, int width, int height, int cell);

  double eta() const { return eta_; }                 ///< [-] share of b in the forward lobe
  double meanSquareAngle() const { return theta2_; }  ///< <theta^2> of the lobe [rad^2]
  /// lambda = eta b R per channel: mean number of forward scatterings over range R [m].
  Eigen::Array3d scatterings(double range) const;
  /// Halo weight relative to the direct term per channel: exp(lambda) - 1 [-].
  Eigen::Array3d haloWeight(double range) const;
  /// Halo width per image axis [rad]: sqrt((<theta^2> / 6) lambda / (1 - exp(-lambda))), green channel.
  double haloSigma(double range) const;
  /// The whole PSF's RMS width per image axis [rad]: sqrt(lambda <theta^2> / 6), green channel (0 at b = 0).
  double psfSigma(double range) const;
  /// Halo width of band k [px] (haloSigma at the band's middle range times the focal length).
  double bandSigmaPixels(int k) const { return band_sigma_px_[static_cast<std::size_t>(k)]; }

  /// Starts a frame: every cell's sums to zero.
  void clear();
  /// Adds the halo of `n` pixels of the tile (cell column cu, row cv): their direct radiance per channel
  /// (direct[c][i]) at range[i] [m] (max_range and beyond: open water, nothing). `extra` (null: none): per pixel, more
  /// forward scatterings on its camera leg than the water's (the silt's eta tau), so that its halo weight is
  /// exp(lambda + extra[i]) - 1; spread with the water's band widths. One thread per cell at a time.
  void accumulate(int cu, int cv, int n, const float* const direct[3], const float* range,
                  const float* extra = nullptr);
  /// Blurs the frame's halo and adds it to `radiance` (3 floats per pixel, row-major [W m^-2 sr^-1]). The
  /// interpolation to the pixels runs in strips of kStripRows rows on `pool`'s threads (the camera's ray caster; null:
  /// on the calling thread alone); every pixel is computed alone, so the image does not depend on it.
  void apply(std::vector<float>& radiance, const raycast::RayCaster* pool = nullptr) const;

  static constexpr int kStripRows = 16;  ///< rows per job of the interpolation pass

private:
  /// Separable Gaussian blur of one band's grid (3 channels interleaved), normalised at the edges.
  void blur(const float* in, float* out, double sigma_cells, std::vector<float>& tmp) const;

  WaterOptics water_;
  double max_range_, focal_;
  int width_, height_, cell_, cols_, rows_;
  double eta_ = 0.0, theta2_ = 0.0;
  std::array<double, kBands> band_sigma_px_{};
  std::vector<float> weight_;       ///< per range step of the table: halo weight per channel (4 floats)
  double weight_scale_ = 0.0;       ///< table steps per metre
  std::vector<std::uint8_t> band_;  ///< per range step of the table: its band
  std::vector<float> sums_;         ///< [band][cell][channel]: mean halo radiance of the cell's pixels
};

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin

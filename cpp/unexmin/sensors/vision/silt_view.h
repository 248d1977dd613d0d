// The silt raised by the thrusters (sim::SedimentField) as one camera sees it in a frame: along each pixel ray the
// silt's optical depth tau(s) attenuates the direct light, and the silt scatters the lights' light back towards the
// lens on top of the water's own backscatter.
//
// For a pixel whose surface is at range R:
//   direct      E_d exp(-2 tau(R))   (the camera leg and, the lights being beside the lens, the lights' leg alike)
//   backscatter E_b + sum_j dB_j ((b + db_j) exp(-2 tau_j) - b) / b
// with E_b the water's backscatter (ImageFormation), dB_j its increment over range bin j of the grid below, db_j the
// silt's mean extra scattering over that bin (its optical depth over the bin / the bin's length) and tau_j the silt's
// optical depth to the bin's middle: the bin scatters back in proportion to its scattering coefficient, attenuated
// by the silt in front of it.
// Computed per frame on a grid of pixel rays (every kStep pixels, and the last row and column) and kBins range bins
// (edges max_range (j / kBins)^2), then interpolated (bilinear in the pixel, linear in range). Only frames whose
// camera is within max_range (plus 4 sigma) of some silt use it: elsewhere the image is left as it was. Knows no ROS.
#pragma once

#include <unexmin/sensors/vision/camera_model.h>
#include <unexmin/sensors/vision/image_formation.h>
#include <unexmin/sim/sediment.h>

#include <Eigen/Geometry>

#include <vector>

namespace unexmin {
namespace sensors {
namespace vision {

class SiltView {
public:
  static constexpr int kStep = 8;   ///< [px] between the grid's pixel rays
  static constexpr int kBins = 32;  ///< range bins of the grid

  /// The grid of `camera`'s pixel rays, with the water's backscatter per unit b along each (from `formation`, which
  /// must outlive the view).
  SiltView(const CameraModel& camera, const ImageFormation& formation);

  /// This frame's optical depths and extra backscatter of the camera at `pose` (optical frame in the world) in
  /// `field`. Returns whether any silt is near enough to be seen (false: apply() must not be called).
  bool update(const sim::SedimentField& field, const Eigen::Isometry3d& pose);
  /// The silt's optical depth along pixel (u, v) [px] to range r [m] (interpolated).
  double opticalDepth(float u, float v, float r) const;
  /// Applies the silt to the first batch.n pixels: batch.out holds direct + backscatter and `direct` [c][i] the direct
  /// term alone; both are updated (the direct term attenuated).
  void apply(PixelBatch& batch, float (*direct)[raycast::kBlock]) const;

private:
  /// Grid node (column iu, row iv) and bin edge j: 4 floats (tau, extra backscatter R, G, B).
  float* node(int iu, int iv, int j) {
    return &table_[((static_cast<std::size_t>(iv) * nu_ + iu) * (kBins + 1) + j) * 4];
  }
  /// Interpolated (tau, extra R, G, B) at pixel (u, v) and range r.
  void lookup(float u, float v, float r, float out[4]) const;

  const ImageFormation& formation_;
  int width_, height_, nu_, nv_;
  double max_range_;
  std::vector<float> edge_;           ///< range of each bin edge [m]
  std::vector<Eigen::Vector3d> ray_;  ///< per node: unit ray, optical frame
  std::vector<float> unit_b_;         ///< per node and edge: the water's backscatter to that range / b, 3 floats
  std::vector<float> table_;          ///< this frame's, per node and edge (node())
};

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin

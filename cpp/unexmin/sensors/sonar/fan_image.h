// The Cartesian fan image of an imaging sonar's polar image (docs/sonars.md "Imaging sonar"): a top view of the
// fan in the sensor's x-y plane, the sonar at the middle of the bottom edge, its +x up and +y (port) to the left.
// Square pixels of range_max / height metres; pixel (row, col) has its centre at
//   x = (height - row - 1/2) s,   y = (width / 2 - col - 1/2) s,   s = range_max / height,
// and shows the polar image's bin of range hypot(x, y) and beam of azimuth atan2(y, x) (beam k covers the
// azimuths fov_h/2 - (k + 1) fov_h / beams .. fov_h/2 - k fov_h / beams); 0 outside the fan or the range window.
// Width: 2 ceil(range_max sin(fov_h / 2) / s) (fov_h <= pi). Built once (a lookup per pixel); rendering is a
// gather over the runs of pixels inside the fan. Knows no ROS.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace unexmin {
namespace sensors {
namespace sonar {

class FanImage {
public:
  /// A polar image of `beams` beams over fov_h [rad] in (0, pi] and `bins` equal bins from range_min to range_max
  /// [m]; `height` >= 1 rows. Throws ParameterError for a bad figure.
  FanImage(std::size_t beams, double fov_h, std::size_t bins, double range_min, double range_max, int height);

  int width() const { return width_; }         ///< [px]
  int height() const { return height_; }       ///< [px]
  double pixelSize() const { return pixel_; }  ///< [m]
  /// Index bin * beams + beam of the polar image shown at pixel (row, col); -1: none.
  long source(int row, int col) const;
  /// `polar` (bins x beams, row-major) -> `out` (height x width, row-major; resized).
  void render(const std::vector<std::uint8_t>& polar, std::vector<std::uint8_t>& out) const;

private:
  int width_ = 0, height_ = 0;
  double pixel_ = 0.0;
  /// A run of consecutive pixels of one row inside the fan: its first pixel (row-major) and its length, and where
  /// its polar indices start in index_.
  struct Run {
    std::uint32_t pixel = 0, length = 0, first = 0;
  };
  std::vector<Run> runs_;               // in pixel order
  std::vector<std::uint32_t> row_run_;  // per row: its first run; height + 1 entries
  std::vector<std::uint32_t> index_;    // per pixel of the runs, in order: bin * beams + beam
};

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

// Points from a finished polar image of a forward-looking imaging sonar (docs/sonars.md "Point cloud"), as sonar
// mapping pipelines make them: per beam, the first range bin whose code stands `threshold` above the noise floor,
// placed at the beam's azimuth and the middle of the vertical aperture (elevation 0).
//   noise floor  per range bin (row) i: the median code of that row over all beams (its ceil(beams/2)-th smallest). The
//   receiver's noise, raised by
//                the time-varied gain, grows with range, so the floor is taken per range; in a ping most beams at a
//                given range see water or shadow, so the median is the noise, not an echo.
//   detection    beam k's first bin i (nearest first) with code >= floor_i + ceil(threshold / step), step the
//                output level of one code [dB]; none: no point for that beam.
//   point        (r_i cos a_k, r_i sin a_k, 0) in the sonar's frame (+x the fan's axis, +y port, +z up), r_i the
//                bin's centre range [m], a_k the beam's azimuth [rad].
// Elevation ambiguity: a sonar beam is wide across its vertical aperture fov_v, and the image keeps no elevation, so
// the echo may come from any elevation in [-fov_v / 2, fov_v / 2]: the point's true height lies within
// +- r tan(fov_v / 2) of the one given (+- 1.76 m at 10 m for 20 deg). Knows no ROS.
#pragma once

#include <unexmin/sensors/sonar/imaging_sonar_sensor.h>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace unexmin {
namespace sensors {
namespace sonar {

/// One detection: at most one per beam.
struct SonarPoint {
  Eigen::Vector3f xyz;  ///< sonar frame [m]
  std::uint8_t code;    ///< the detected bin's code, 0 .. 255
  std::size_t beam;     ///< column of the polar image
  std::size_t bin;      ///< row of the polar image
};

class SonarCloud {
public:
  /// `azimuths` [rad] one per beam (column), `ranges` [m] one per bin (row, bin centres), `step` [dB] the output
  /// level of one code (> 0), `threshold` [dB] above the noise floor (> 0). Throws ParameterError for a bad value.
  SonarCloud(std::vector<double> azimuths, std::vector<double> ranges, double step, double threshold);
  /// The geometry of `sensor` (its azimuths, bin centres and code step).
  SonarCloud(const ImagingSonarSensor& sensor, double threshold);

  double threshold() const { return threshold_; }  ///< [dB]
  int thresholdCodes() const { return threshold_codes_; }
  /// The detections of `image` (bins x beams as the geometry's), in beam order. Throws ParameterError when the
  /// image's size is not the geometry's.
  const std::vector<SonarPoint>& build(const PolarImage& image);
  /// The noise floor of the last build(): one code per range bin.
  const std::vector<std::uint8_t>& floor() const { return floor_; }

private:
  std::vector<double> azimuths_, ranges_;
  double threshold_ = 0.0;
  int threshold_codes_ = 0;
  std::vector<float> cos_, sin_;
  std::vector<std::uint8_t> floor_;
  std::vector<SonarPoint> points_;
};

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

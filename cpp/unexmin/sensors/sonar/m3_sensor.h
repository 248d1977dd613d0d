// Kongsberg M3 multibeam sonar in profiling mode (thesis 5.4.4; docs/sonars.md). Type name "m3".
// Frame: the M3 link; the fan lies in its x-y plane, centred on +x (the LaserScan convention).
// Each ping (the sensor's rate, 40 Hz):
//   - beam k (k = 0 .. beams-1) at azimuth a_k = -fov_h/2 + k fov_h / (beams - 1) about z;
//   - rays_per_beam rays across the vertical beam width, elevations e_j = -fov_v/2 + (j + 1/2) fov_v / n,
//     direction (cos e cos a, cos e sin a, sin e), cast from the link origin up to range_max;
//   - the beam's range is its first return (the nearest hit of its rays), plus Gaussian noise
//     (range_noise, 1 sigma; noise = none: off), rounded to range_resolution;
//   - REP-117: +inf when nothing is within range_max (or the noisy range exceeds it), -inf when the
//     return is nearer than range_min;
//   - rays stop at the free surface (sound does not leave the water; the first return keeps to direct paths);
//   - intensity of the beam: its first return's echo level by the sonar equation of echo_model.h (the beam's
//     solid angle fov_h / beams x 2 sin(fov_v / 2) at the return's incidence), receiver gain, TVG and 8-bit
//     quantisation, 0 without a return.
// Parameters (defaults in brackets): beams (256), fov_h [rad] (120 deg), fov_v [rad] (3 deg),
// rays_per_beam (4), range_min [m] (0.2), range_max [m] (150), range_resolution [m] (0.01),
// range_noise [m] (0), noise gaussian|none (gaussian), backscatter_exponent (2), gain (0.5), gain_span [dB] (40),
// source_level [dB re 1 uPa at 1 m] (210), backscatter_strength [dB] (-20), absorption [dB/m] (0.1),
// tvg_spreading [dB/decade] (20), display_min [dB re 1 uPa] (125), display_span [dB] (80).
#pragma once

#include <unexmin/sensors/sensor.h>
#include <unexmin/sensors/sonar/echo_model.h>

#include <Eigen/Core>

#include <vector>

namespace unexmin {
namespace sonar {

struct M3Scan
{
  double time = -1.0;              ///< ping time [s]
  std::vector<float> ranges;       ///< per beam [m]; +inf no return, -inf nearer than range_min (REP-117)
  std::vector<float> intensities;  ///< per beam, 0..1 [-]
};

class M3Sensor : public sensors::Sensor
{
public:
  /// Throws ConfigError naming the robot, the sensor and the parameter.
  M3Sensor(const sim::SensorSpec& spec, const sensors::SensorSetup& setup);

  const M3Scan& last() const { return last_; }
  std::size_t beams() const { return static_cast<std::size_t>(beams_); }
  double angleMin() const { return -fov_h_ / 2.0; }                  ///< [rad]
  double angleMax() const { return fov_h_ / 2.0; }                   ///< [rad]
  double angleIncrement() const { return beams_ > 1 ? fov_h_ / (beams_ - 1) : 0.0; }  ///< [rad]
  double beamAngle(std::size_t k) const  ///< [rad]; one beam points along +x
  {
    return beams_ > 1 ? angleMin() + static_cast<double>(k) * angleIncrement() : 0.0;
  }
  double rangeMin() const { return range_min_; }                     ///< [m]
  double rangeMax() const { return range_max_; }                     ///< [m]
  double rangeResolution() const { return resolution_; }             ///< [m]
  int raysPerBeam() const { return rays_per_beam_; }
  /// The sonar equation of the intensities (one bin over the range window).
  const EchoModel& echo() const { return echo_; }
  /// Ray j of beam k in the sensor frame (unit).
  Eigen::Vector3d rayDirection(std::size_t k, int j) const;

protected:
  void onReset() override;
  void sample(const sensors::SensorContext& ctx) override;

private:
  int beams_ = 256, rays_per_beam_ = 4;
  double fov_h_ = 0.0, fov_v_ = 0.0, range_min_ = 0.0, range_max_ = 0.0, resolution_ = 0.0;
  double range_noise_ = 0.0;
  EchoModel echo_{EchoParams()};  ///< the intensities' sonar equation
  std::vector<Eigen::Vector3d> dirs_;
  std::vector<raycast::Ray> rays_;
  std::vector<raycast::Hit> hits_;
  M3Scan last_;
};

}  // namespace sonar
}  // namespace unexmin

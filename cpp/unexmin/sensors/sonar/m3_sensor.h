// Kongsberg M3 multibeam sonar in profiling mode (thesis 5.4.4; docs/sonars.md). Type name "m3".
// Frame: the M3 link; the fan lies in its x-y plane, centred on +x (the LaserScan convention).
// Each ping (the sensor's rate, 40 Hz):
//   - beam k (k = 0 .. beams-1) at azimuth a_k = -fov_h/2 + k fov_h / (beams - 1) about z;
//   - rays_per_beam rays across the vertical beam width, elevations e_j = -fov_v/2 + (j + 1/2) fov_v / n,
//     direction (cos e cos a, cos e sin a, sin e), cast from the link origin up to range_max;
//   - each ray's echo has the beam's echo level EL by the sonar equation of echo_model.h (the beam's solid
//     angle fov_h / beams x 2 sin(fov_v / 2) at the echo's incidence); it is a detection when
//     EL >= noise_level + detection_threshold (the receiver's noise in its band and the signal-to-noise ratio
//     a detection needs: a profiling multibeam reports the first sample of a beam above its threshold);
//   - rays stop at the free surface. With multipath (the sonar submerged), a ray that reaches it within range
//     has the surface's own echo there (backscatter surface_backscatter at incidence cos = d_z) and, when that
//     echo is not a detection and nothing of its beam is detected nearer, a reflected ray (d_z -> -d_z) cast
//     from the surface for the rest of the range: what it meets at r2 is a ghost at the unfolded range s + r2
//     (out and back the same way), 40 log10 |surface_reflection| weaker than a direct echo from there;
//   - the beam's range is its first detection (the nearest detected echo of its rays: direct, surface or
//     ghost) as the sonar times it: the path times sound_speed / c_water, c_water the world's water column's sound
//     speed at the sonar (docs/worlds.md "Water column"; sound_speed itself without a column), plus Gaussian noise
//     (range_noise, 1 sigma; noise = none: off), rounded to range_resolution;
//   - REP-117: +inf when nothing is detected within range_max (or the noisy range exceeds it), -inf when the
//     detection is nearer than range_min;
//   - intensity of the beam: its detection's echo level with receiver gain, TVG and 8-bit quantisation,
//     0 without one.
// Parameters (defaults in brackets): beams (256), fov_h [rad] (120 deg), fov_v [rad] (3 deg),
// rays_per_beam (4), range_min [m] (0.2), range_max [m] (150), range_resolution [m] (0.01),
// range_noise [m] (0), noise gaussian|none (gaussian), backscatter_exponent (2), gain (0.5), gain_span [dB] (40),
// source_level [dB re 1 uPa at 1 m] (210), backscatter_strength [dB] (-20), absorption [dB/m] (0.1),
// tvg_spreading [dB/decade] (20), display_min [dB re 1 uPa] (125), display_span [dB] (80),
// noise_level [dB re 1 uPa] (72), detection_threshold [dB] (10), multipath (true), surface_reflection [-] (0.9),
// surface_backscatter [dB] (-30), sound_speed [m/s] (1500).
#pragma once

#include <unexmin/sensors/sensor.h>
#include <unexmin/sensors/sonar/echo_model.h>
#include <unexmin/sensors/sonar/equation_params.h>

#include <Eigen/Core>

#include <limits>
#include <vector>

namespace unexmin {
namespace sensors {
namespace sonar {

struct M3Scan {
  double time = -1.0;              ///< ping time [s]
  std::vector<float> ranges;       ///< per beam [m]; +inf no return, -inf nearer than range_min (REP-117)
  std::vector<float> intensities;  ///< per beam, 0..1 [-]
};

class M3Sensor : public sensors::Sensor {
public:
  /// Throws ConfigError naming the robot, the sensor and the parameter.
  M3Sensor(const sim::SensorSpec& spec, const sensors::SensorSetup& setup);

  const M3Scan& last() const { return last_; }
  std::size_t beams() const { return static_cast<std::size_t>(beams_); }
  double angleMin() const { return -fov_h_ / 2.0; }                                   ///< [rad]
  double angleMax() const { return fov_h_ / 2.0; }                                    ///< [rad]
  double angleIncrement() const { return beams_ > 1 ? fov_h_ / (beams_ - 1) : 0.0; }  ///< [rad]
  double beamAngle(std::size_t k) const  ///< [rad]; one beam points along +x
  {
    return beams_ > 1 ? angleMin() + static_cast<double>(k) * angleIncrement() : 0.0;
  }
  double rangeMin() const { return range_min_; }          ///< [m]
  double rangeMax() const { return range_max_; }          ///< [m]
  double rangeResolution() const { return resolution_; }  ///< [m]
  int raysPerBeam() const { return rays_per_beam_; }
  /// The sonar equation of the intensities (one bin over the range window).
  const EchoModel& echo() const { return echo_; }
  /// Ray j of beam k in the sensor frame (unit).
  Eigen::Vector3d rayDirection(std::size_t k, int j) const;
  /// Least echo level of a detection, noise_level + detection_threshold [dB re 1 uPa].
  double detectionLevel() const { return detection_level_; }

protected:
  void onReset() override;
  void sample(const sensors::SensorContext& ctx) override;
  void describeSample(SampleWriter& out) const override;

private:
  int beams_ = 256, rays_per_beam_ = 4;
  double fov_h_ = 0.0, fov_v_ = 0.0, range_min_ = 0.0, range_max_ = 0.0, resolution_ = 0.0;
  SoundSpeed sound_speed_;  ///< the speed it turns echo times into ranges with
  double scale_ = 1.0;      ///< this ping's apparent-range factor (sensor.h)
  double reach_ = 0.0;      ///< [m] this ping's farthest path in the water it can report
  double range_noise_ = 0.0;
  /// One echo that a beam may report: where from, and its echo for the level.
  struct Return {
    double range = std::numeric_limits<double>::infinity();  ///< [m]; inf: none
    Echo echo;
  };
  /// Whether an echo of one beam is a detection (EL >= detection level).
  bool detected(const Echo& e) const { return echo_.reaches(e, 1, detection_power_); }
  /// The beam's nearest detected echo of its direct hits and surface echoes (first_[k]); queues the reflected
  /// rays that could still give a nearer detection.
  void directAndSurface(int k, double surface_z);

  EchoModel echo_{EchoParams()};  ///< the intensities' sonar equation
  SurfaceParams reflector_;       ///< the free surface: multipath on/off, its echoes' extra levels
  double detection_level_ = 0.0;  ///< noise_level + detection_threshold [dB re 1 uPa]
  double detection_power_ = 0.0;  ///< 10^(detection_level / 10) [uPa^2]
  std::vector<Eigen::Vector3d> dirs_;
  std::vector<raycast::Ray> rays_;
  std::vector<raycast::Hit> hits_;
  std::vector<double> surface_;         ///< per ray: range to the free surface, -1 when not reached within range
  std::vector<raycast::Ray> mirrored_;  ///< the reflected rays
  std::vector<raycast::Hit> mirror_hits_;
  std::vector<std::size_t> mirror_of_;  ///< primary ray of each reflected ray
  std::vector<Return> first_;           ///< per beam: its first detection
  std::vector<std::size_t> order_;      ///< scratch: a beam's direct hits by range
  M3Scan last_;
};

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

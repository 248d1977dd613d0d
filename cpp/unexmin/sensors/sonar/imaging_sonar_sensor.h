// Forward-looking imaging sonar of the Oculus M750d class (docs/sonars.md "Imaging sonar"). Type name
// "imaging_sonar". Frame: the sensor link; the fan is centred on its +x, +y to port (left), +z up.
// Each ping (the sensor's rate, at most sound_speed / (2 range_max)):
//   - beam k (k = 0 .. beams-1) at azimuth a_k = fov_h/2 - (k + 1/2) fov_h / beams about z (beam 0 the leftmost,
//     to port, as an image column 0 is); rays_per_beam rays across the vertical aperture fov_v (BeamFan, elevation
//     about the link's y), cast from the link origin up to range_max; they stop at the free surface;
//   - every hit echoes by the sonar equation (echo_model.h; the beam's solid angle fov_h / beams x 2 sin(fov_v / 2)
//     shared by its rays), spread over its footprint's ranges; rays stop at the first surface they meet, so what
//     lies behind an object is in its acoustic shadow. The ranges are the echoes' as the sonar times them: the path x
//     sound_speed / c_water, c_water the world's water column's sound speed at the sonar (docs/worlds.md "Water
//     column"; 1 without a column), the rays cast up to range_max / min(1, that factor);
//   - the beam's nbins range bins from range_min to range_max become 8-bit codes (BeamReceiver: speckle, noise
//     floor, gain, TVG, quantisation);
//   - the polar image: row i = range bin i (centre range_min + (i + 1/2) (range_max - range_min) / nbins), column
//     k = beam k; mono8.
// Parameters (defaults in brackets): beams (512), fov_h [rad] (130 deg), fov_v [rad] (20 deg), rays_per_beam (16),
// range_min [m] (0.1), range_max [m] (30), nbins (500), gain (0.5), noise gaussian|none (gaussian), speckle (true),
// noise_floor (true), noise_level [dB re 1 uPa] (85), sound_speed [m/s] (1500), fan_height [px] (500), and the
// sonar equation's (equation_params.h) with source_level 210 dB re 1 uPa at 1 m. Knows no ROS.
#pragma once

#include <unexmin/sensors/sensor.h>
#include <unexmin/sensors/sonar/beam_fan.h>
#include <unexmin/sensors/sonar/beam_receiver.h>
#include <unexmin/sensors/sonar/beam_set.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace unexmin {
namespace sensors {
namespace sonar {

/// One ping of the imaging sonar: range bins x beams.
struct PolarImage {
  double time = -1.0;               ///< ping time [s]
  std::size_t beams = 0;            ///< columns
  std::size_t bins = 0;             ///< rows
  std::vector<std::uint8_t> codes;  ///< row-major: codes[i * beams + k] = bin i of beam k, 0 .. 255
  bool built = false;               ///< false: the ping was not wanted (setDemand) and codes hold an older ping
  std::uint8_t at(std::size_t bin, std::size_t beam) const { return codes[bin * beams + beam]; }
};

class ImagingSonarSensor : public Sensor {
public:
  /// Throws ConfigError naming the robot, the sensor and the parameter.
  ImagingSonarSensor(const sim::SensorSpec& spec, const SensorSetup& setup);

  const PolarImage& last() const { return last_; }
  /// Builds a ping (rays, echoes, receiver) only at samples where `wanted()` is true (e.g. one of its image topics has
  /// a subscriber); null: always. Each ping draws one seed from the sensor's stream, built or not, so the images do
  /// not depend on who watched before.
  void setDemand(std::function<bool()> wanted) { demand_ = std::move(wanted); }
  std::size_t beams() const { return beams_.size(); }
  std::size_t bins() const { return static_cast<std::size_t>(beams_.receiver().echo().params().nbins); }
  double fovH() const { return fov_h_; }  ///< [rad]
  double fovV() const { return fov_v_; }  ///< [rad]
  /// Azimuth of beam k about the link's z [rad]: fov_h/2 - (k + 1/2) fov_h / beams.
  double azimuth(std::size_t k) const;
  double rangeMin() const { return beams_.receiver().echo().params().range_min; }          ///< [m]
  double rangeMax() const { return beams_.receiver().echo().params().range_max; }          ///< [m]
  double rangeResolution() const { return beams_.receiver().echo().binWidth(); }           ///< bin width [m]
  double binCenter(std::size_t i) const { return beams_.receiver().echo().binCenter(i); }  ///< [m]
  /// Height of the Cartesian fan image [px] (the publisher's).
  int fanHeight() const { return fan_height_; }
  const BeamReceiver& receiver() const { return beams_.receiver(); }
  const BeamFan& fan(std::size_t k) const { return beams_.fan(k); }
  std::size_t raysPerPing() const { return beams_.raysPerPing(); }

protected:
  void onReset() override;
  void sample(const SensorContext& ctx) override;
  void describeSample(SampleWriter& out) const override;

private:
  double fov_h_ = 0.0, fov_v_ = 0.0;
  int beam_count_ = 1;
  int fan_height_ = 500;
  BeamSet beams_;
  std::vector<raycast::Hit> hits_;
  PolarImage last_;
  std::function<bool()> demand_;
};

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

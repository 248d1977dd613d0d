// Mechanical scanning imaging sonar, Tritech Micron DST (thesis 5.4.1; docs/sonars.md). Type name "msis".
// Frame: the head link (on a continuous/revolute joint, axis usually z); the beam is along the head's +x.
// Each sample (one ping per mechanical step; the sensor's rate is the step rate [steps/s]):
//   1. the head is at angle a_k (the joint position): the first ping at sector_left, then one `step` per
//      ping towards sector_right; at a limit the head turns back (sector scan), or with continuous = true
//      it keeps turning the same way, the angle wrapped to (-pi, pi];
//   2. a fan of hpr x vpr rays covers the beam: horizontal angles h_i = -bw_h/2 + (i + 1/2) bw_h / hpr
//      about the head's z, elevations v_j = -bw_v/2 + (j + 1/2) bw_v / vpr, direction
//      (cos v cos h, cos v sin h, sin v) in the head frame, cast from the head origin up to range_max (range_max /
//      scale where the water is faster than sound_speed);
//   3. rays that reach the free surface within range stop there: the surface's own echo, and (multipath) a
//      reflected ray cast from it for the rest of the range, whose hit is a ghost at the unfolded range;
//      the hits become one line of nbins 8-bit intensities in [0, 1] (EchoModel: the sonar equation per ray at its
//      path, power summed per bin, gain, TVG, quantisation), with the noise models on the bins' power, each
//      switchable. An echo is binned at its range as the sonar times it: the path x scale, scale = sound_speed /
//      c_water, c_water the world's water column's sound speed at the head (docs/worlds.md "Water column"; 1
//      without a column):
//        range_noise  [m]  Gaussian noise on every ray's range (0: off)
//        speckle           exponential (Rayleigh amplitude) factor on each bin's echo power
//        noise_floor       + the noise power 10^(noise_level / 10) x an exponential draw per bin
//        salt_pepper  [-]  probability per bin of a spike up to salt_level dB above the noise level (salt) or a
//                          dropped bin (pepper), half and half
//        shadow            true: no echo behind the first bin whose echo reaches shadow_threshold (bins
//                          flagged shadow)
//        artifacts         true: echoes between the hits of neighbouring rays of a column that are within
//                          artifacts_gap of each other (fills the sparse-ray gaps on the ground)
//      noise = none turns them all off;
//   4. each bin gets a level for the colour map: none (< threshold_low), low, medium (>= threshold_medium),
//      high (>= threshold_high), shadow (a shadowed bin with no echo).
// Presets (parameter `preset`): "thesis_tank" = the thesis's tank configuration (6.1.1): range 3 m,
// 400 bins, low gain (0.2). Parameters given explicitly override the preset. Scanning is continuous (360 deg)
// unless `continuous` is false. docs/sonars.md lists every parameter with its unit, default and source.
#pragma once

#include <unexmin/sensors/sensor.h>
#include <unexmin/sensors/sonar/echo_model.h>
#include <unexmin/sensors/sonar/equation_params.h>

#include <Eigen/Geometry>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace unexmin {
namespace sensors {
namespace sonar {

/// Colour-map class of one bin.
enum class EchoLevel : std::uint8_t { none, low, medium, high, shadow };

/// One ping: the intensity line along the head's +x.
struct MsisLine {
  double time = -1.0;            ///< ping time [s]
  double angle = 0.0;            ///< head joint position of the ping [rad]
  std::vector<float> intensity;  ///< per bin, 0..1 [-]
  std::vector<EchoLevel> level;  ///< per bin
};

class MsisSensor : public sensors::Sensor {
public:
  /// The named gains (low, medium, high) as shares of gain_span [-].
  static const std::map<std::string, double>& gainSettings();
  /// The mechanical steps of the Micron DST [deg].
  static const std::vector<double>& mechanicalSteps();

  /// Throws ConfigError naming the robot, the sensor and the parameter.
  MsisSensor(const sim::SensorSpec& spec, const sensors::SensorSetup& setup);

  const MsisLine& last() const { return last_; }
  const EchoModel& echo() const { return echo_; }
  const std::string& joint() const { return joint_; }
  /// Head angle now: of the next ping [rad] (the joint position between pings is the last ping's).
  double headAngle() const { return last_.time < 0.0 ? angle_ : last_.angle; }
  /// The head joint at headAngle(), at rest (a stepper between steps).
  void movedJoints(std::vector<sensors::MovedJoint>& out) const override { out.push_back({joint_, headAngle(), 0.0}); }
  /// Mean head speed while scanning: step x rate [rad/s].
  double headSpeed() const { return step_ * rate(); }
  double step() const { return step_; }  ///< [rad]
  std::size_t raysPerPing() const { return dirs_.size(); }
  /// Ray directions of the fan in the head frame (column h, then elevation v: index h * vpr + v).
  const std::vector<Eigen::Vector3d>& fan() const { return dirs_; }
  /// Head link pose in the base link frame at head angle a [rad].
  Eigen::Isometry3d headPose(double a) const;

protected:
  void onReset() override;
  void sample(const sensors::SensorContext& ctx) override;
  void describeSample(SampleWriter& out) const override;

private:
  /// What one ping's stages pass along besides the sensor's buffers (rays_, hits_, energy_, ...).
  struct Ping {
    Eigen::Vector3d origin{0, 0, 0};  ///< head origin, world frame [m]
    double surface_z = 0.0;           ///< world z of the free surface [m]
    double scale = 1.0;               ///< timed range / path: sound_speed / c_water at the head [-]
    double reach = 0.0;               ///< longest path heard within range_max: range_max / min(1, scale) [m]
    std::vector<char> shadowed;       ///< per bin: 1 behind the first strong echo (shadow on)
  };
  // The stages of sample(), in order (see the steps above):
  /// 2, 3: the fan's rays from the head at angle_, each stopped at the free surface when it reaches it in range.
  void aim(const sensors::SensorContext& ctx, Ping& ping);
  /// 3: the reflected rays of those that reached the surface, cast; ghost_ maps each ray to its reflection.
  void castReflections(const sensors::SensorContext& ctx, const Ping& ping);
  /// 3: the echo power of the hits, the surface and the ghosts summed per bin into energy_ (range noise drawn).
  void depositEchoes(const Ping& ping);
  /// 3: no echo behind the first bin that reaches shadow_threshold (shadow on); flags those bins.
  void shadowBins(Ping& ping);
  /// 3: speckle, noise floor, salt and pepper on energy_ (each when on).
  void addReceiverNoise();
  /// 3, 4: last_ from energy_: intensities (EchoModel::finish) and levels.
  void writeLine(const sensors::SensorContext& ctx, const Ping& ping);
  EchoLevel level(float intensity) const;
  /// 1: the head angle of the next ping.
  void advance();

  EchoModel echo_{EchoParams()};
  std::string joint_;
  Eigen::Vector3d axis_{0, 0, 1};
  double step_ = 0.0, left_ = 0.0, right_ = 0.0;
  bool continuous_ = true;
  int hpr_ = 1, vpr_ = 1;
  double range_noise_ = 0.0, salt_pepper_ = 0.0, shadow_threshold_ = 0.5, artifacts_gap_ = 0.5;
  bool shadow_ = false, artifacts_ = false, speckle_ = false, noise_floor_ = false;
  double salt_level_ = 10.0;           ///< [dB] above the noise level: the highest spike
  SoundSpeed sound_speed_;             ///< the speed it turns echo times into ranges with
  double noise_power_ = 0.0;           ///< 10^(noise_level / 10) [uPa^2]
  SurfaceParams reflector_;            ///< the free surface: multipath on/off, its echoes' extra levels
  int shadow_code_ = 1;                ///< least code of a shadowing echo
  std::vector<double> noise_visible_;  ///< per bin: uniform draw from which the noise floor alone shows
  double threshold_low_ = 0.05, threshold_medium_ = 0.25, threshold_high_ = 0.6;
  std::vector<Eigen::Vector3d> dirs_;
  double angle_ = 0.0;  ///< head angle of the next ping [rad]
  int dir_ = 1;         ///< +1 / -1: direction of the next step
  std::vector<raycast::Ray> rays_;
  std::vector<raycast::Hit> hits_;
  std::vector<double> surface_;         ///< per ray: range to the free surface, -1 when not within range
  std::vector<raycast::Ray> mirrored_;  ///< the reflected rays
  std::vector<raycast::Hit> mirror_hits_;
  std::vector<std::size_t> mirror_of_;  ///< primary ray of each reflected ray
  std::vector<long> ghost_;             ///< per ray: its reflected ray, -1 none
  std::vector<Echo> column_;
  std::vector<double> energy_;
  MsisLine last_;
};

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

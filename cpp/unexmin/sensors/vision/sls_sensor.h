// Structured-light scanner (SLS, thesis 5.4.5; INESC-TEC's unit on the UX-1): a green laser line fan swept by a
// motor, seen by its own camera, which triangulates the points of the line it can see.
//
// Frame: the laser head link (spec.link, child of the motor joint, axis usually z). The fan lies in the head's
// x-z plane, centred on +x: ray j at elevation e_j = -fan/2 + j fan/(rays - 1) has direction (cos e, 0, sin e).
// The motor sweeps the head between motor_min and motor_max at motor_speed (a triangle wave starting at
// motor_start, default 0 (facing the camera's side of the unit), moving up), reported in joint_states. Each sample (the
// camera's frame rate):
//   1. every ray of the fan is cast against the world (own hull invisible): the raw fan (LaserScan ranges from
//      the head origin; +inf beyond range_max, -inf nearer than range_min, REP-117);
//   2. a laser point is kept when the unit's camera (optical frame `camera_frame`, a link of the robot; image
//      and plumb_bob intrinsics from camera_width, camera_height, camera_hfov, camera_distortion, written by the
//      xacro from the same properties as the camera sensor's) sees it: it projects inside the (distorted) image,
//      nothing lies between it and the lens, and its line is bright enough:
//        S = albedo_g cos(phi) exp(-c_g (R_L + R_C)) R_ref / R_L   >=   threshold (1 + b_g L_b)
//      with R_L the laser range, R_C the camera range, phi the incidence of the laser on the surface, c_g and
//      b_g the water's green attenuation and scattering (WaterOptics of the world's visibility; a line laser
//      spreads in one dimension: 1 / R_L), R_ref = 1 m, L_b = backscatter_length (the laser sheet's glow
//      seen along the pixel raises the background) and albedo_g the surface's green albedo at the hit (its
//      material in the world file, textured or not: SurfaceMaterials); where the thrusters raised silt
//      (sim::SedimentField) S is also multiplied by exp(-tau_L - tau_C), the silt's optical depths along the laser
//      ray and the sight line, and the level's b_g L_b gains the silt's optical depth over the first L_b of the
//      sight line;
//   3. triangulation noise along the camera ray: depth error sigma_Z = Z^2 sigma_u / (f B) with Z the depth in
//      the camera, f its focal length [px] at full resolution, B the camera-laser baseline [m], sigma_u the
//      sub-pixel accuracy of the line detector [px].
// Points are given in the camera's optical frame (the triangulating camera is the sensor origin).
//
// Parameters: camera_frame (required, a link), camera_width/height [px] (2054 x 1544), camera_hfov [rad]
// (80 deg), camera_distortion (0 0 0 0 0), fan [rad] (100 deg), rays (200), range_min [m] (0.1),
// range_max [m] (5), motor_min/motor_max [rad] (-45/45 deg), motor_speed [rad/s] (10 deg/s; 0 = still),
// motor_start [rad] (0 within the limits), subpixel_noise [px] (0.2), threshold [-] (1e-3), backscatter_length [m] (1),
// noise gaussian|none (gaussian), scan_frame (head link), joint (default: the joint whose child is the link). Knows no
// ROS.
#pragma once

#include <unexmin/sensors/sensor.h>
#include <unexmin/sensors/vision/camera_model.h>
#include <unexmin/sensors/vision/surface_materials.h>
#include <unexmin/sensors/vision/water_optics.h>

#include <Eigen/Geometry>

#include <memory>
#include <vector>

namespace unexmin {
namespace sensors {
namespace vision {

/// One sample of an SLS unit.
struct SlsScan {
  double time = -1.0;                   ///< sim time [s]
  double motor_angle = 0.0;             ///< head joint position [rad]
  std::vector<float> ranges;            ///< raw fan from the head origin [m] (REP-117 markers)
  std::vector<Eigen::Vector3f> points;  ///< visible laser points, camera optical frame [m]
  std::vector<float> intensity;         ///< their line strength S / detection level [-] (>= 1)
};

class SlsSensor : public Sensor {
public:
  SlsSensor(const sim::SensorSpec& spec, const SensorSetup& setup);

  const SlsScan& last() const { return last_; }
  /// Head joint position at sim time t [s] (the motor's triangle wave) [rad].
  double motorAngle(double t) const;
  double motorVelocity(double t) const;  ///< [rad/s]
  /// Laser head pose at motor angle `a` in the base link frame.
  Eigen::Isometry3d headPose(double a) const;
  /// Unit direction of fan ray j in the head frame.
  Eigen::Vector3d rayDirection(int j) const;
  int rays() const { return static_cast<int>(dirs_.size()); }
  double fan() const { return fan_; }
  double rangeMin() const { return range_min_; }
  double rangeMax() const { return range_max_; }
  const std::string& joint() const { return joint_; }
  /// frame_id of the raw fan's LaserScan: a link whose x-y plane is the fan plane (`scan_frame`, default the
  /// head link).
  const std::string& scanFrame() const { return scan_frame_; }
  /// The camera that sees this unit: its optical frame (link) and that frame's pose in the base frame.
  const std::string& cameraFrame() const { return camera_frame_; }
  const Eigen::Isometry3d& cameraPose() const { return camera_pose_; }
  /// The camera's model at full resolution (triangulation and visibility).
  const CameraModel& camera() const { return camera_; }
  /// Depth noise sigma_Z [m] at depth Z [m] in the camera (0 with noise none).
  double depthSigma(double z) const;
  /// Baseline B [m] between the camera's centre and the laser origin (at motor angle 0).
  double baseline() const { return baseline_; }
  double threshold() const { return threshold_; }
  double backscatterLength() const { return backscatter_length_; }

  void movedJoints(std::vector<MovedJoint>& out) const override;

protected:
  void onReset() override { last_ = SlsScan(); }
  void track(const SensorContext& ctx) override { now_ = ctx.world.time(); }
  void sample(const SensorContext& ctx) override;
  void describeSample(SampleWriter& out) const override;

private:
  double fan_ = 0.0, range_min_ = 0.1, range_max_ = 5.0;
  double motor_min_ = 0.0, motor_max_ = 0.0, motor_speed_ = 0.0, motor_start_ = 0.0;
  double subpixel_ = 0.2, threshold_ = 1e-3, backscatter_length_ = 1.0;
  bool noise_ = true;
  std::string joint_, scan_frame_;
  Eigen::Vector3d axis_{0, 0, 1};
  std::string camera_frame_;
  Eigen::Isometry3d camera_pose_ = Eigen::Isometry3d::Identity();
  CameraModel camera_;
  double baseline_ = 0.0;
  double now_ = 0.0;
  WaterOptics water_;  ///< the world's water, derived at the first sample in it
  const sim::World* water_world_ = nullptr;
  double water_turbidity_ = -1.0;  ///< [NTU] water_ was derived for (-1: the level's)
  std::vector<Eigen::Vector3d> dirs_;
  std::vector<raycast::Ray> rays_, sight_;
  std::vector<raycast::Hit> hits_, sight_hits_;
  std::vector<int> candidates_;
  std::unique_ptr<SurfaceMaterials> materials_;  ///< the world's, for the green albedo at each hit
  SlsScan last_;
};

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin

// The records a robot description (URDF, expanded from xacro) is read into: the joint tree for the actuator and
// sensor poses, the sensors as written, and the <unexmin> element's hydrodynamic, thruster, fin, pendulum and VBS
// parameters (sim::parseRobotDescription fills them, sim/robot_description.h). See docs/robot_description.md.
#pragma once

#include <unexmin/hydro/fin.h>
#include <unexmin/hydro/fossen_model.h>
#include <unexmin/hydro/pendulum.h>
#include <unexmin/hydro/thruster.h>
#include <unexmin/hydro/thruster_factory.h>

#include <map>
#include <string>
#include <vector>

namespace unexmin {
namespace sim {

struct JointInfo {
  std::string name;
  std::string type;                                          ///< URDF joint type (fixed, continuous, revolute, ...).
  std::string parent;                                        ///< Parent link.
  std::string child;                                         ///< Child link.
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  ///< Child frame in parent frame.
  Eigen::Vector3d xyz{0, 0, 0};                              ///< <origin xyz> as written [m].
  Eigen::Vector3d rpy{0, 0, 0};                              ///< <origin rpy> as written [rad].
  Eigen::Vector3d axis{1, 0, 0};                             ///< In the joint frame.
};

/// A sensor as written in the robot description:
///   <sensor name="imu" type="imu" link="UX_1/imu_link" rate="500">
///     <param name="gyro_noise_density" value="1.2e-5"/>  <param name="model" value="kvh_1775"/>
///   </sensor>
/// The sensor factory of each type checks its parameters.
struct SensorSpec {
  std::string name;  ///< Unique within the robot; also the topic base name.
  std::string type;  ///< Family name, e.g. "imu", "dvl", "pressure".
  std::string link;  ///< URDF link of the sensor frame (frame_id of its messages).
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< link in the base link frame
  double rate = 0.0;                                       ///< Update rate [Hz of sim time] > 0.
  hydro::ParamMap params;                                  ///< numeric parameters
  std::map<std::string, std::string> text;                 ///< non-numeric parameters (model names, ...)
};

/// The robot's own magnetic field at its magnetometers (<magnetic> of <unexmin>, docs/magnetometer.md), one for
/// every magnetometer of the robot (the IMU's and the fluxgate's), body frame: what a magnetometer reads is
///   B_read = S B_ext + h + sum_i v_i I_i,   I_i = k |T_i|^n
/// with B_ext the external field, S the soft iron, h the hard iron, v_i the field of thruster i per ampere of its
/// current I_i, T_i its thrust [N] (an assumed electrical law: no thruster current model exists). None: zero field.
struct RobotMagnetics {
  Eigen::Vector3d hard_iron{0, 0, 0};                       ///< h [nT]
  Eigen::Matrix3d soft_iron = Eigen::Matrix3d::Identity();  ///< S, applied to the external field
  std::vector<Eigen::Vector3d> thruster_field;              ///< v_i [nT/A] by thruster id (empty: none)
  double current_coefficient = 0.0;                         ///< k [A / N^n]
  double current_exponent = 1.5;                            ///< n
  /// The thrusters' currents [A] of thrusts `thrust` [N] (by id): k |T_i|^n.
  double current(double thrust) const;
  /// B_read [nT, body] of the external field `external` [nT, body] and the thrusts `thrust` [N] (by id).
  Eigen::Vector3d read(const Eigen::Vector3d& external, const std::vector<double>& thrust) const;
};

struct RobotDescription {
  std::string source;     ///< File or parameter it came from (for messages).
  std::string name;       ///< <robot name="...">
  std::string base_link;  ///< Link carrying the hydrodynamics (the rigid body).
  hydro::HydroParams hydro;
  std::vector<hydro::ThrusterParams> thrusters;  ///< Sorted by id 0..n-1.
  std::vector<std::string> thruster_joints;      ///< Same order as `thrusters`.
  /// The families that know the thrusters' <dynamics type> and <conversion type> (the parser's), and build them.
  hydro::ThrusterFactory thruster_families = hydro::ThrusterFactory::builtin();
  std::vector<hydro::FinParams> fins;   ///< Control surfaces, sorted by id 0..n-1 (none on the UX-1).
  std::vector<std::string> fin_joints;  ///< Same order as `fins`.
  /// The families that know the fins' <model type> (the parser's), and build them.
  hydro::FinFactory fin_families = hydro::FinFactory::builtin();
  /// Length, width, height of the hull's box centred on the body origin [m] (<bounding_box size>); zero when the
  /// description gives none, the actuators must then lie within the hull radius.
  Eigen::Vector3d hull_box{0, 0, 0};
  hydro::PendulumParams pendulum;
  std::string pendulum_joint;  ///< Empty when the robot has no pendulum.
  hydro::VbsParams vbs;
  std::vector<JointInfo> joints;
  std::vector<SensorSpec> sensors;
  RobotMagnetics magnetics;  ///< the robot's own field (zero without a <magnetic> element)

  /// Pose of `link` in the base link's frame, through fixed joint origins (moving joints at zero).
  Eigen::Isometry3d linkPose(const std::string& link) const;
  /// Movable (non-fixed) joints, in document order.
  std::vector<std::string> movableJoints() const;
};

}  // namespace sim
}  // namespace unexmin

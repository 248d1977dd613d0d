// One vehicle in the world: a Bullet rigid body driven by the Fossen model, its thrusters,
// pendulum and variable ballast. Knows no ROS; time is a double in seconds.
#pragma once

#include <unexmin/hydro/current.h>
#include <unexmin/hydro/fin.h>
#include <unexmin/hydro/fossen_model.h>
#include <unexmin/hydro/pendulum.h>
#include <unexmin/hydro/thruster.h>
#include <unexmin/sim/robot_description.h>
#include <unexmin/sim/robot_spawn.h>

#include <memory>

class btRigidBody;
class btCollisionShape;
struct btDefaultMotionState;

namespace unexmin {
namespace sim {

/// What the water is doing where the robot is.
struct WaterState {
  double density = 1000.0;                 ///< [kg/m^3] at the robot (its world's water column there, if any)
  double gravity = 9.81;                   ///< [m/s^2]
  double surface_z = 0.0;                  ///< [m]
  Eigen::Vector3d current{0, 0, 0};        ///< Water velocity, world frame [m/s].
  Eigen::Vector3d current_accel{0, 0, 0};  ///< Its rate of change, world frame [m/s^2].
};

/// Kinematic state of the base link in the world frame.
struct RobotState {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::Vector3d linear_velocity{0, 0, 0};      ///< World frame [m/s].
  Eigen::Vector3d angular_velocity{0, 0, 0};     ///< World frame [rad/s].
  Eigen::Vector3d linear_acceleration{0, 0, 0};  ///< World frame, over the last step [m/s^2].
};

class Robot {
public:
  Robot(const RobotDescription& description, const RobotSpawn& spawn);
  ~Robot();
  Robot(const Robot&) = delete;
  Robot& operator=(const Robot&) = delete;

  const std::string& name() const { return name_; }
  const RobotDescription& description() const { return description_; }
  btRigidBody* body() { return body_.get(); }

  /// Actuators and forces for the step from t to t + dt [s]; call before the engine steps.
  void applyForces(double t, double dt, const WaterState& water);
  /// Bookkeeping after the engine stepped (accelerations, propeller angles).
  void afterStep(double dt);

  RobotState state() const;
  /// Body velocity relative to the water [u v w p q r] of the last applyForces.
  const hydro::Vector6d& relativeVelocity() const { return nu_r_; }
  /// Body wrench of the last applyForces, split by origin [N | N m].
  const hydro::Vector6d& thrustWrench() const { return thrust_wrench_; }
  const hydro::Vector6d& hydroWrench() const { return hydro_wrench_; }
  const hydro::Vector6d& restoringWrench() const { return restoring_wrench_; }

  std::size_t thrusterCount() const { return thrusters_.size(); }
  hydro::Thruster& thruster(std::size_t i) { return *thrusters_.at(i); }
  const hydro::Thruster& thruster(std::size_t i) const { return *thrusters_.at(i); }
  /// Propeller joint angle for the visual [rad].
  double propellerAngle(std::size_t i) const { return propeller_angle_.at(i); }
  std::size_t finCount() const { return fins_.size(); }
  hydro::Fin& fin(std::size_t i) { return *fins_.at(i); }
  const hydro::Fin& fin(std::size_t i) const { return *fins_.at(i); }
  /// Body wrench of the fins in the last applyForces [N | N m] (zero without fins).
  const hydro::Vector6d& finWrench() const { return fin_wrench_; }
  bool hasPendulum() const { return pendulum_ != nullptr; }
  hydro::Pendulum& pendulum() { return *pendulum_; }
  const hydro::Pendulum& pendulum() const { return *pendulum_; }
  hydro::Vbs& vbs() { return vbs_; }
  const hydro::Vbs& vbs() const { return vbs_; }

  /// Total mass, pendulum and ballast included [kg], and its centre in the body frame [m].
  double totalMass() const;
  Eigen::Vector3d centerOfGravity() const;
  /// Mass and inertia the engine integrates (rigid body + folded added mass + ballast + payload).
  double engineMass() const;
  /// Mass the robot's payload carries besides its description [kg] >= 0 (the water its samplers took), centred at
  /// `centre` (body frame [m]): part of totalMass() and centerOfGravity() from the next applyForces on (its weight, its
  /// inertia along the translations; the rotational inertia keeps the description's). Zero after reset().
  void setPayloadMass(double mass, const Eigen::Vector3d& centre);
  double payloadMass() const { return payload_mass_; }  ///< [kg]

  /// Back to the spawn pose at rest, actuators zeroed.
  void reset();
  /// Teleport to a pose at rest (tests, resets).
  void setPose(const Eigen::Isometry3d& pose);

private:
  void updateMassProperties();

  std::string name_;
  RobotDescription description_;
  Eigen::Isometry3d spawn_pose_;
  hydro::FossenModel model_;
  std::vector<std::unique_ptr<hydro::Thruster>> thrusters_;
  std::vector<double> propeller_angle_;
  /// Per thruster: its dynamics state is a rotor speed (hydro::ThrustConversion::stateIsRotorSpeed), decided once.
  std::vector<bool> rotor_speed_state_;
  std::vector<std::unique_ptr<hydro::Fin>> fins_;
  std::unique_ptr<hydro::Pendulum> pendulum_;
  hydro::Vbs vbs_;
  double engine_vbs_mass_ = 0.0;
  double payload_mass_ = 0.0;                ///< [kg]
  Eigen::Vector3d payload_centre_{0, 0, 0};  ///< body frame [m]
  double engine_payload_mass_ = 0.0;         ///< the payload mass the rigid body has

  std::unique_ptr<btCollisionShape> shape_;
  std::unique_ptr<btDefaultMotionState> motion_state_;
  std::unique_ptr<btRigidBody> body_;

  hydro::Vector6d nu_r_ = hydro::Vector6d::Zero();
  hydro::Vector6d nu_r_prev_ = hydro::Vector6d::Zero();
  hydro::Vector6d nu_r_dot_ = hydro::Vector6d::Zero();
  bool have_prev_ = false;
  Eigen::Vector3d velocity_before_{0, 0, 0};
  Eigen::Vector3d acceleration_{0, 0, 0};
  hydro::Vector6d thrust_wrench_ = hydro::Vector6d::Zero();
  hydro::Vector6d hydro_wrench_ = hydro::Vector6d::Zero();
  hydro::Vector6d restoring_wrench_ = hydro::Vector6d::Zero();
  hydro::Vector6d fin_wrench_ = hydro::Vector6d::Zero();
};

}  // namespace sim
}  // namespace unexmin

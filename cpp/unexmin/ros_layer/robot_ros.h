// ROS plumbing of one robot: command subscribers (guarded), state publishers, tf.
#pragma once

#include <unexmin/ros_layer/sensors_ros.h>
#include <unexmin/sim/robot.h>
#include <unexmin/sim/world.h>

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <std_msgs/Float64.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace unexmin {
namespace ros_layer {

/// A command message with its publisher's name (to count applied commands).
using Float64Event = ros::MessageEvent<std_msgs::Float64 const>;

struct PublishRates {
  double odom = 50.0;          ///< nav_msgs/Odometry and tf [Hz of sim time]
  double joint_states = 50.0;  ///< sensor_msgs/JointState [Hz of sim time]
  double thrust = 50.0;        ///< achieved thrust per thruster [Hz of sim time]
  double contacts = 50.0;      ///< unexmin/Contacts of the hull [Hz of sim time]
};

class RobotRos {
public:
  /// Subscribes /<robot>/thrusters/<i>/input, fins/<i>/input, pendulum, vbs on `command_nh`'s callback queue.
  /// `received` counts the command messages applied, per publishing node (shared by all robots).
  /// `suite`: the robot's sensors (of the `selection`'s families) that the engine runs in `world`; their samples go
  /// out through SensorsRos. `world` and `suite` must outlive this.
  RobotRos(sim::World& world, sim::Robot& robot, sensors::SensorSuite& suite, ros::NodeHandle& command_nh,
           ros::NodeHandle& nh, const PublishRates& rates, double physics_rate,
           std::map<std::string, std::uint64_t>& received, const SensorRegistry& registry,
           const sensors::SensorSelection& selection);

  /// Publishes whatever is due at this physics step (after the engine's step): the robot's state streams (all of
  /// them when `all`: end of a /sim/step, reset) and the samples its sensors took at this step.
  void publish(std::uint64_t step, const ros::Time& stamp, bool all = false);

  /// Ground truth of the base link: pose in `world`, twist in the body frame (REP-105).
  nav_msgs::Odometry odometry(const ros::Time& stamp) const;

  /// Whether streams for viewers (joint_states) may go out now: in lockstep they are limited
  /// to a wall-clock rate, as nothing that consumes them needs more (see docs/simulator_node.md).
  void setWallGate(const ros::WallTime& now, double min_period) {
    wall_now_ = now;
    min_wall_period_ = min_period;
  }

  /// Hands every message of this robot (its streams, its sensors, the commands it receives) to `recorder`
  /// too (null: none); it must outlive this.
  void attach(BagRecorder* recorder) {
    recorder_ = recorder;
    sensors_->attach(recorder);
  }

  /// Forget what was published (the world was reset to step 0).
  void restart() {
    last_odom_ = last_joint_ = last_thrust_ = last_contacts_ = UINT64_MAX;
    sensors_->restart();
  }

private:
  /// Counts and records a command on `topic`, drops a non-finite one, hands the rest to `set`; a command `set`
  /// refuses is warned about (throttled) as outside [min, max] `unit`.
  void onActuatorInput(const std::string& topic, const Float64Event& event, const std::function<bool(double)>& set,
                       double min, double max, const char* what, const char* unit);
  void onThrusterInput(std::size_t i, const Float64Event& event);
  /// /<robot>/fins/<i>/input [rad]: NaN or out-of-range angles are rejected with a throttled warning.
  void onFinInput(std::size_t i, const Float64Event& event);
  void onPendulum(const Float64Event& event);
  void onVbs(const Float64Event& event);
  /// Writes a received command to the recording (when its topic is recorded).
  void record(const std::string& topic, const Float64Event& event) const;
  /// Shared edge check: rejects (warns, returns false) a non-finite command.
  bool finite(const std::string& topic, double value) const;

  /// /<robot>/contacts: sim::contacts of the robot at this step, stamped with its time.
  void publishContacts(const ros::Time& stamp);

  sim::World& world_;
  sim::Robot& robot_;
  std::map<std::string, std::uint64_t>& received_;
  double now_ = 0.0;  ///< sim time of the last publish call [s]
  std::vector<ros::Subscriber> subs_;
  std::vector<Stream> thrust_pubs_;
  Stream odom_pub_;
  Stream joint_pub_;
  Stream contacts_pub_;
  /// /tf (world -> base_link at the odometry rate). Not tf2_ros's TransformBroadcaster: its queue of 100
  /// messages overflowed in lockstep when a subscriber (the mapper) read late, and the dropped samples left gaps
  /// that tf2 interpolated over.
  Stream tf_pub_;
  ros::WallTime wall_now_;
  double min_wall_period_ = 0.0;  ///< [s] of wall time between viewer-stream messages (0: none)
  ros::WallTime last_joint_wall_;
  std::uint64_t odom_every_ = 1;
  std::uint64_t joint_every_ = 1;
  std::uint64_t thrust_every_ = 1;
  std::uint64_t contacts_every_ = 1;
  // Step of the last publication of each stream (none yet: max).
  std::uint64_t last_odom_ = UINT64_MAX;
  std::uint64_t last_joint_ = UINT64_MAX;
  std::uint64_t last_thrust_ = UINT64_MAX;
  std::uint64_t last_contacts_ = UINT64_MAX;
  std::vector<std::string> joint_names_;
  std::unique_ptr<SensorsRos> sensors_;
  BagRecorder* recorder_ = nullptr;
};

}  // namespace ros_layer
}  // namespace unexmin

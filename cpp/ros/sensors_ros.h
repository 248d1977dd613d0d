// ROS plumbing of one robot's simulated sensors (IMU, DVL, pressure; cpp/sensors): runs the sensor
// suite after every physics step and publishes each fresh sample through the publisher of its
// family. Sensors publish on their own schedule only (their rate in sim time), never extra at the end
// of a /sim/step: the latest sample of a sensor at rate f is at most 1/f old. See docs/sensors.md.
//
// ROS parameters (read at start-up):
//   /<robot>/kvh_from_simulator (bool, default true): the simulator itself publishes the IMU's
//       kvh_1775/ImuRawKvh (its kvh_topic); false leaves that topic to the rospy KVH translator.
//   /<robot>/kvh_raw (bool, default: not kvh_from_simulator): advertise the IMU's unexmin/ImuRaw
//       (its raw_topic), the KVH translator's input. Off by default with kvh_from_simulator: it
//       would duplicate kvh/imu_raw at 500 Hz in every "record all" bag.
#pragma once

#include "ros/sensor_publisher.h"
#include "sensors/sensor_suite.h"
#include "sim/world.h"

#include <ros/ros.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace unexmin {
namespace ros_layer {

class SensorsRos
{
public:
  /// Builds the robot's sensors from its description (throws sim::ConfigError naming the sensor and
  /// the parameter on a bad one) and advertises their topics under /<robot>/.
  SensorsRos(sim::World& world, sim::Robot& robot, ros::NodeHandle& nh);

  /// Call after every physics step with the world's step count; a repeated call for the same step
  /// (end of a /sim/step, after a reset) does nothing.
  void publish(std::uint64_t step);
  /// [sonar] Position [rad] and velocity [rad/s] of a joint a sensor moves (the MSIS head); false when no
  /// sensor moves `joint`.
  bool jointState(const std::string& joint, double& position, double& velocity) const;
  /// The world was reset (new seed, step 0): sensors back to turn-on.
  void restart();

  sensors::SensorSuite& suite() { return *suite_; }

private:
  sim::World& world_;
  std::unique_ptr<sensors::SensorSuite> suite_;
  std::vector<std::unique_ptr<SensorPublisher>> publishers_;  ///< one per suite sensor (null: none)
  std::uint64_t last_step_ = 0;
};

}  // namespace ros_layer
}  // namespace unexmin

// Topics of an "imu" sensor (names from its _topic parameters, relative to /<robot>/):
//   topic      (default <name>)       sensor_msgs/Imu: rate, specific force, white-noise covariances;
//                                     no orientation (orientation_covariance[0] = -1)
//   mag_topic  (default <name>/mag)   sensor_msgs/MagneticField [T]
//   raw_topic  (default <name>/raw)   unexmin/ImuRaw: every raw field in SI units, input of the rospy
//                                     KVH translator; advertised only when `raw`
//   kvh_topic  (default none)         kvh_1775/ImuRawKvh, built here when `kvh_direct` (the rospy
//                                     translator cannot keep up with 500 Hz at high real-time factors)
#pragma once

#include <unexmin/ros_layer/sensor_publisher.h>
#include <unexmin/sensors/imu_sensor.h>

namespace unexmin {
namespace ros_layer {

class ImuPublisher : public SensorPublisher {
public:
  /// Reads the robot's parameters kvh_from_simulator and kvh_raw (docs/sensors.md).
  ImuPublisher(const sensors::ImuSensor& sensor, const PublisherContext& ctx);
  void publish() override;

private:
  const sensors::ImuSensor& sensor_;
  Stream imu_, mag_, raw_, kvh_;
};

}  // namespace ros_layer
}  // namespace unexmin

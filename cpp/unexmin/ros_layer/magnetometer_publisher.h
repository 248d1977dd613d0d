// Topic of a "magnetometer" sensor (docs/magnetometer.md): `topic` (default <name>, relative to /<robot>/),
// sensor_msgs/MagneticField [T] in the sensor frame (REP 103/145), the covariance diagonal the white-noise and
// quantisation variance [T^2].
#pragma once

#include <unexmin/ros_layer/sensor_publisher.h>
#include <unexmin/sensors/science/magnetometer_sensor.h>

namespace unexmin {
namespace ros_layer {

class MagnetometerPublisher : public SensorPublisher {
public:
  MagnetometerPublisher(const sensors::science::MagnetometerSensor& sensor, const PublisherContext& ctx);
  void publish() override;

private:
  const sensors::science::MagnetometerSensor& sensor_;
  Stream pub_;
};

}  // namespace ros_layer
}  // namespace unexmin

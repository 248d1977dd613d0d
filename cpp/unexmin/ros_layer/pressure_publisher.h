// Topic of a "pressure" sensor: `topic` (default <name>, relative to /<robot>/),
// sensor_msgs/FluidPressure [Pa] with the white-noise variance [Pa^2].
#pragma once

#include <unexmin/ros_layer/sensor_publisher.h>
#include <unexmin/sensors/pressure_sensor.h>

namespace unexmin {
namespace ros_layer {

class PressurePublisher : public SensorPublisher {
public:
  PressurePublisher(const sensors::PressureSensor& sensor, const PublisherContext& ctx);
  void publish() override;

private:
  const sensors::PressureSensor& sensor_;
  Stream pub_;
};

}  // namespace ros_layer
}  // namespace unexmin

// Topics of a "water_probe" sensor (docs/water_probe.md), each relative to /<robot>/ and every sample on each:
//   `temperature_topic`    (probe/temperature)    sensor_msgs/Temperature [degC], variance [degC^2]
//   `pressure_topic`       (probe/pressure)       sensor_msgs/FluidPressure [Pa] absolute, variance [Pa^2]
//   `water_quality_topic`  (probe/water_quality)  unexmin/WaterQuality (msg/WaterQuality.msg): every channel
// Frame: the probe link.
#pragma once

#include <unexmin/ros_layer/sensor_publisher.h>
#include <unexmin/sensors/science/water_probe_sensor.h>

namespace unexmin {
namespace ros_layer {

class WaterProbePublisher : public SensorPublisher {
public:
  WaterProbePublisher(const sensors::science::WaterProbeSensor& sensor, const PublisherContext& ctx);
  void publish() override;

private:
  const sensors::science::WaterProbeSensor& sensor_;
  Stream temperature_, pressure_, quality_;
};

}  // namespace ros_layer
}  // namespace unexmin

// Topic and service of a "water_sampler" sensor (docs/water_sampler.md), under `topic` (default "sampler", relative
// to /<robot>/):
//   <topic>/result: unexmin/WaterSample, one message per filled bottle, stamped with the end of its fill;
//   <topic>/fire: std_srvs/Trigger, fires the next bottle (Sensor::fire); success false and the reason when every
//   bottle is full or one is filling. Served on the simulator's service queue, so between physics steps.
#pragma once

#include <unexmin/ros_layer/sensor_publisher.h>
#include <unexmin/sensors/science/water_sampler_sensor.h>

#include <std_srvs/Trigger.h>

#include <cstddef>

namespace unexmin {
namespace ros_layer {

class WaterSamplerPublisher : public SensorPublisher {
public:
  WaterSamplerPublisher(sensors::science::WaterSamplerSensor& sensor, const PublisherContext& ctx);
  /// Emits every bottle filled since the last call (none is left out: the topic is not gated on subscribers).
  void publish() override;

private:
  bool onFire(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);

  sensors::science::WaterSamplerSensor& sensor_;
  Stream pub_;
  ros::ServiceServer fire_srv_;
  std::size_t sent_ = 0;    ///< results emitted
  double last_end_ = -1.0;  ///< end_time of the latest result emitted (a reset clears the results)
};

}  // namespace ros_layer
}  // namespace unexmin

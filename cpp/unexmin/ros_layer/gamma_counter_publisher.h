// Topic of a "gamma_counter" sensor (docs/gamma_counter.md): `topic` (default <name>, relative to /<robot>/),
// unexmin/GammaCounts: the counts of one integration (total, K, U, Th windows), the count rates corrected for dead
// time [cps] and the dead-time fraction; frame: the detector link.
#pragma once

#include <unexmin/ros_layer/sensor_publisher.h>
#include <unexmin/sensors/science/gamma_counter_sensor.h>

namespace unexmin {
namespace ros_layer {

class GammaCounterPublisher : public SensorPublisher {
public:
  GammaCounterPublisher(const sensors::science::GammaCounterSensor& sensor, const PublisherContext& ctx);
  void publish() override;

private:
  const sensors::science::GammaCounterSensor& sensor_;
  Stream pub_;
};

}  // namespace ros_layer
}  // namespace unexmin

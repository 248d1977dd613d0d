#include <unexmin/ros_layer/pressure_publisher.h>

#include <sensor_msgs/FluidPressure.h>

namespace unexmin {
namespace ros_layer {

PressurePublisher::PressurePublisher(const sensors::PressureSensor& sensor, const PublisherContext& ctx)
    : sensor_(sensor) {
  pub_ = ctx.nh.advertise<sensor_msgs::FluidPressure>(resolve(ctx.ns, topicParam(sensor, "topic", sensor.name())),
                                                      queueSize(sensor.rate()));
}

void PressurePublisher::publish() {
  if (!wanted(pub_))
    return;
  const sensors::PressureSample& s = sensor_.last();
  sensor_msgs::FluidPressure m;
  m.header.stamp.fromSec(s.time);
  m.header.frame_id = sensor_.frame();
  m.fluid_pressure = s.pressure;
  m.variance = s.variance;
  emit(pub_, m);
}

}  // namespace ros_layer
}  // namespace unexmin

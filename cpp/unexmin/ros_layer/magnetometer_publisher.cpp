#include <unexmin/ros_layer/magnetometer_publisher.h>

#include <sensor_msgs/MagneticField.h>

namespace unexmin {
namespace ros_layer {
namespace {

constexpr double kTeslaPerNanotesla = 1e-9;

}  // namespace

MagnetometerPublisher::MagnetometerPublisher(const sensors::science::MagnetometerSensor& sensor,
                                             const PublisherContext& ctx)
    : sensor_(sensor) {
  pub_ = ctx.nh.advertise<sensor_msgs::MagneticField>(resolve(ctx.ns, topicParam(sensor, "topic", sensor.name())),
                                                      queueSize(sensor.rate()));
}

void MagnetometerPublisher::publish() {
  if (!wanted(pub_))
    return;
  const sensors::science::MagnetometerSample& s = sensor_.last();
  sensor_msgs::MagneticField m;
  m.header.stamp.fromSec(s.time);
  m.header.frame_id = sensor_.frame();
  m.magnetic_field.x = s.field.x() * kTeslaPerNanotesla;
  m.magnetic_field.y = s.field.y() * kTeslaPerNanotesla;
  m.magnetic_field.z = s.field.z() * kTeslaPerNanotesla;
  for (int i = 0; i < 3; ++i)
    m.magnetic_field_covariance[4 * i] = s.variance * kTeslaPerNanotesla * kTeslaPerNanotesla;
  emit(pub_, m);
}

}  // namespace ros_layer
}  // namespace unexmin

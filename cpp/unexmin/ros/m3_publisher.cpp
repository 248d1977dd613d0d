#include <unexmin/ros/m3_publisher.h>

#include <sensor_msgs/LaserScan.h>

namespace unexmin {
namespace ros_layer {

M3Publisher::M3Publisher(const sonar::M3Sensor& sensor, const PublisherContext& ctx) : sensor_(sensor)
{
  pub_ = ctx.nh.advertise<sensor_msgs::LaserScan>(resolve(ctx.ns, topicParam(sensor, "topic", "m3/scan")),
                                              queueSize(sensor.rate()));
}

void M3Publisher::publish()
{
  if (!wanted(pub_)) return;
  const sonar::M3Scan& s = sensor_.last();
  sensor_msgs::LaserScan m;
  m.header.stamp.fromSec(s.time);
  m.header.frame_id = sensor_.frame();
  m.angle_min = static_cast<float>(sensor_.beamAngle(0));
  m.angle_max = static_cast<float>(sensor_.beamAngle(sensor_.beams() - 1));
  m.angle_increment = static_cast<float>(sensor_.angleIncrement());
  m.time_increment = 0.0f;
  m.scan_time = static_cast<float>(1.0 / sensor_.rate());
  m.range_min = static_cast<float>(sensor_.rangeMin());
  m.range_max = static_cast<float>(sensor_.rangeMax());
  m.ranges = s.ranges;
  m.intensities = s.intensities;
  emit(pub_, m);
}

}  // namespace ros_layer
}  // namespace unexmin

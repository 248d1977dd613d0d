#include <unexmin/ros_layer/sls_publisher.h>

#include <sensor_msgs/PointField.h>

#include <cstring>

namespace unexmin {
namespace ros_layer {

SlsPublisher::SlsPublisher(const sensors::vision::SlsSensor& sensor, const PublisherContext& ctx) : sensor_(sensor) {
  const int queue = queueSize(sensor.rate());
  points_ = ctx.nh.advertise<sensor_msgs::PointCloud2>(
      resolve(ctx.ns, topicParam(sensor, "topic", sensor.name() + "/points")), queue);
  scan_ = ctx.nh.advertise<sensor_msgs::LaserScan>(
      resolve(ctx.ns, topicParam(sensor, "scan_topic", sensor.name() + "/scan")), queue);
}

sensor_msgs::PointCloud2 SlsPublisher::cloud() const {
  const auto& s = sensor_.last();
  sensor_msgs::PointCloud2 m;
  m.header.stamp.fromSec(s.time);
  m.header.frame_id = sensor_.cameraFrame();
  floatCloud(m, {"x", "y", "z", "intensity"}, s.points.size());
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const float p[4] = {s.points[i].x(), s.points[i].y(), s.points[i].z(), s.intensity[i]};
    std::memcpy(&m.data[i * m.point_step], p, sizeof(p));
  }
  return m;
}

sensor_msgs::LaserScan SlsPublisher::scan() const {
  const auto& s = sensor_.last();
  sensor_msgs::LaserScan m;
  m.header.stamp.fromSec(s.time);
  m.header.frame_id = sensor_.scanFrame();
  m.angle_min = static_cast<float>(-sensor_.fan() / 2.0);
  m.angle_max = static_cast<float>(sensor_.fan() / 2.0);
  m.angle_increment = static_cast<float>(sensor_.fan() / (sensor_.rays() - 1));
  m.time_increment = 0.0f;
  m.scan_time = static_cast<float>(1.0 / sensor_.rate());
  m.range_min = static_cast<float>(sensor_.rangeMin());
  m.range_max = static_cast<float>(sensor_.rangeMax());
  m.ranges = s.ranges;
  return m;
}

void SlsPublisher::publish() {
  if (wanted(points_))
    emit(points_, cloud());
  if (wanted(scan_))
    emit(scan_, scan());
}

}  // namespace ros_layer
}  // namespace unexmin

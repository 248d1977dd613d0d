#include <unexmin/ros_layer/msis_publisher.h>

#include <sensor_msgs/PointField.h>
#include <std_msgs/Float64.h>

#include <cstring>

namespace unexmin {
namespace ros_layer {

const std::array<std::uint32_t, 5>& MsisPublisher::colours() {
  static const std::array<std::uint32_t, 5> rgb = {
      0x0000ffu,  // none: blue
      0xffffb4u,  // low: white-yellow
      0xffff00u,  // medium: yellow
      0xff0000u,  // high: red
      0x000064u,  // shadow: dark blue
  };
  return rgb;
}

MsisPublisher::MsisPublisher(const sensors::sonar::MsisSensor& sensor, const PublisherContext& ctx) : sensor_(sensor) {
  const int queue = queueSize(sensor.rate());
  scan_ = ctx.nh.advertise<sensor_msgs::PointCloud2>(
      resolve(ctx.ns, topicParam(sensor, "topic", "tritech_micron/scan")), queue);
  angle_ =
      ctx.nh.advertise<std_msgs::Float64>(resolve(ctx.ns, topicParam(sensor, "angle_topic", "msis/msis_r")), queue);
}

sensor_msgs::PointCloud2 MsisPublisher::cloud() const {
  const sensors::sonar::MsisLine& line = sensor_.last();
  sensor_msgs::PointCloud2 m;
  m.header.stamp.fromSec(line.time);
  m.header.frame_id = sensor_.frame();
  const std::size_t n = line.intensity.size();
  floatCloud(m, {"x", "y", "z", "intensity", "rgb"}, n);
  for (std::size_t i = 0; i < n; ++i) {
    const float point[4] = {static_cast<float>(sensor_.echo().binCenter(i)), 0.0f, 0.0f, line.intensity[i]};
    const std::uint32_t rgb = colours()[static_cast<std::size_t>(line.level[i])];
    std::uint8_t* p = &m.data[i * m.point_step];
    std::memcpy(p, point, sizeof(point));
    std::memcpy(p + 16, &rgb, 4);
  }
  return m;
}

void MsisPublisher::publish() {
  if (wanted(angle_)) {
    std_msgs::Float64 a;
    a.data = sensor_.last().angle;
    emit(angle_, a);
  }
  if (wanted(scan_))
    emit(scan_, cloud());
}

}  // namespace ros_layer
}  // namespace unexmin

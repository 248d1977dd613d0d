#include <unexmin/ros_layer/camera_publisher.h>

#include <sensor_msgs/Image.h>
#include <sensor_msgs/image_encodings.h>

namespace unexmin {
namespace ros_layer {

CameraPublisher::CameraPublisher(sensors::vision::CameraSensor& sensor, const PublisherContext& ctx)
    : sensor_(sensor), info_(cameraInfo(sensor)) {
  info_.header.frame_id = sensor.frame();
  // Frames are large: a short queue (a slow subscriber drops frames rather than filling the memory).
  const int queue = std::max(2, static_cast<int>(2.0 * sensor.rate()));
  info_pub_ = ctx.nh.advertise<sensor_msgs::CameraInfo>(
      resolve(ctx.ns, topicParam(sensor, "info_topic", sensor.name() + "/camera_info")), queueSize(sensor.rate()));
  if (sensor.visual()) {
    image_pub_ = ctx.nh.advertise<sensor_msgs::Image>(
        resolve(ctx.ns, topicParam(sensor, "topic", sensor.name() + "/image_raw")), queue);
    // Render only while someone subscribes or the simulator records the image topic.
    sensor_.setDemand([this] { return wanted(image_pub_); });
  }
}

CameraPublisher::~CameraPublisher() {
  sensor_.setDemand(nullptr);
}

sensor_msgs::CameraInfo CameraPublisher::cameraInfo(const sensors::vision::CameraSensor& sensor) {
  const sensors::vision::CameraModel& m = sensor.model();
  sensor_msgs::CameraInfo info;
  info.width = static_cast<std::uint32_t>(m.width());
  info.height = static_cast<std::uint32_t>(m.height());
  info.distortion_model = "plumb_bob";
  info.D.assign(m.distortion().begin(), m.distortion().end());
  const auto k = m.K();
  const auto p = m.P();
  std::copy(k.begin(), k.end(), info.K.begin());
  std::copy(p.begin(), p.end(), info.P.begin());
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  return info;
}

void CameraPublisher::publish() {
  const sensors::vision::CameraFrame& f = sensor_.last();
  const ros::Time stamp(f.time);
  if (wanted(info_pub_)) {
    info_.header.stamp = stamp;
    emit(info_pub_, info_);
  }
  if (!f.rendered || !image_pub_ || !wanted(image_pub_))
    return;
  sensor_msgs::Image m;
  m.header.stamp = stamp;
  m.header.frame_id = sensor_.frame();
  m.width = static_cast<std::uint32_t>(f.width);
  m.height = static_cast<std::uint32_t>(f.height);
  m.encoding = sensor_msgs::image_encodings::RGB8;
  m.is_bigendian = 0;
  m.step = static_cast<std::uint32_t>(3 * f.width);
  m.data = f.rgb;
  emit(image_pub_, m);
}

}  // namespace ros_layer
}  // namespace unexmin

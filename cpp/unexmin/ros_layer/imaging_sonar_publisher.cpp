#include <unexmin/ros_layer/imaging_sonar_publisher.h>

#include <sensor_msgs/image_encodings.h>

#include <algorithm>
#include <vector>

namespace unexmin {
namespace ros_layer {

ImagingSonarPublisher::ImagingSonarPublisher(sensors::sonar::ImagingSonarSensor& sensor, const PublisherContext& ctx)
    : sensor_(sensor),
      fan_(sensor.beams(), sensor.fovH(), sensor.bins(), sensor.rangeMin(), sensor.rangeMax(), sensor.fanHeight()) {
  // Images are large: a short queue (a slow subscriber drops images rather than filling the memory).
  const int queue = std::max(2, static_cast<int>(2.0 * sensor.rate()));
  polar_pub_ = ctx.nh.advertise<sensor_msgs::Image>(
      resolve(ctx.ns, topicParam(sensor, "topic", sensor.name() + "/polar")), queue);
  fan_pub_ = ctx.nh.advertise<sensor_msgs::Image>(
      resolve(ctx.ns, topicParam(sensor, "fan_topic", sensor.name() + "/fan")), queue);
  std::vector<double> azimuths(sensor.beams());
  for (std::size_t k = 0; k < azimuths.size(); ++k)
    azimuths[k] = sensor.azimuth(k);
  const std::string params = ctx.ns + sensor.name() + "/";
  ctx.nh.setParam(params + "beam_azimuths", azimuths);
  ctx.nh.setParam(params + "range_min", sensor.rangeMin());
  ctx.nh.setParam(params + "range_max", sensor.rangeMax());
  ctx.nh.setParam(params + "range_resolution", sensor.rangeResolution());
  ctx.nh.setParam(params + "fan_pixel_size", fan_.pixelSize());
  // Ping only while someone subscribes to an image or the simulator records one.
  sensor_.setDemand([this] { return wanted(polar_pub_) || wanted(fan_pub_); });
}

ImagingSonarPublisher::~ImagingSonarPublisher() {
  sensor_.setDemand(nullptr);
}

sensor_msgs::Image ImagingSonarPublisher::mono8(double time, const std::string& frame, std::size_t rows,
                                                std::size_t cols) {
  sensor_msgs::Image m;
  m.header.stamp.fromSec(time);
  m.header.frame_id = frame;
  m.height = static_cast<std::uint32_t>(rows);
  m.width = static_cast<std::uint32_t>(cols);
  m.encoding = sensor_msgs::image_encodings::MONO8;
  m.is_bigendian = 0;
  m.step = static_cast<std::uint32_t>(cols);
  m.data.resize(rows * cols);
  return m;
}

sensor_msgs::Image ImagingSonarPublisher::polar() const {
  const sensors::sonar::PolarImage& p = sensor_.last();
  sensor_msgs::Image m = mono8(p.time, sensor_.frame(), p.bins, p.beams);
  m.data = p.codes;
  return m;
}

sensor_msgs::Image ImagingSonarPublisher::fan() const {
  const sensors::sonar::PolarImage& p = sensor_.last();
  sensor_msgs::Image m = mono8(p.time, sensor_.frame(), fan_.height(), fan_.width());
  fan_.render(p.codes, m.data);
  return m;
}

void ImagingSonarPublisher::publish() {
  if (!sensor_.last().built)
    return;
  if (wanted(polar_pub_))
    emit(polar_pub_, polar());
  if (wanted(fan_pub_))
    emit(fan_pub_, fan());
}

}  // namespace ros_layer
}  // namespace unexmin

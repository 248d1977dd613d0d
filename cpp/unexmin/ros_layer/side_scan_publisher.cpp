#include <unexmin/ros_layer/side_scan_publisher.h>

#include <unexmin/ros_layer/imaging_sonar_publisher.h>

#include <algorithm>

namespace unexmin {
namespace ros_layer {

SideScanPublisher::SideScanPublisher(sensors::sonar::SideScanSensor& sensor, const PublisherContext& ctx)
    : sensor_(sensor) {
  const int lines = queueSize(sensor.rate());
  const std::string& name = sensor.name();
  port_pub_ =
      ctx.nh.advertise<sensor_msgs::Image>(resolve(ctx.ns, topicParam(sensor, "port_topic", name + "/port")), lines);
  starboard_pub_ = ctx.nh.advertise<sensor_msgs::Image>(
      resolve(ctx.ns, topicParam(sensor, "starboard_topic", name + "/starboard")), lines);
  // The waterfall is large: a short queue (a slow subscriber drops images rather than filling the memory).
  waterfall_pub_ =
      ctx.nh.advertise<sensor_msgs::Image>(resolve(ctx.ns, topicParam(sensor, "topic", name + "/waterfall")),
                                           std::max(2, static_cast<int>(2.0 * sensor.rate())));
  const std::string params = ctx.ns + name + "/";
  ctx.nh.setParam(params + "range_min", sensor.rangeMin());
  ctx.nh.setParam(params + "range_max", sensor.rangeMax());
  ctx.nh.setParam(params + "range_resolution", sensor.rangeResolution());
  // Ping only while someone subscribes to a line or the waterfall, or the simulator records one.
  sensor_.setDemand([this] { return wanted(port_pub_) || wanted(starboard_pub_) || wanted(waterfall_pub_); });
}

SideScanPublisher::~SideScanPublisher() {
  sensor_.setDemand(nullptr);
}

sensor_msgs::Image SideScanPublisher::line(int side) const {
  const sensors::sonar::SideScanPing& p = sensor_.last();
  sensor_msgs::Image m = ImagingSonarPublisher::mono8(p.time, sensor_.frame(), 1, sensor_.bins());
  m.data = side == 0 ? p.port : p.starboard;
  return m;
}

sensor_msgs::Image SideScanPublisher::waterfall() const {
  const sensors::sonar::Waterfall& w = sensor_.waterfall();
  sensor_msgs::Image m = ImagingSonarPublisher::mono8(sensor_.last().time, sensor_.frame(), w.lines(), w.width());
  w.image(m.data);
  return m;
}

void SideScanPublisher::publish() {
  if (!sensor_.last().built)
    return;
  if (wanted(port_pub_))
    emit(port_pub_, line(0));
  if (wanted(starboard_pub_))
    emit(starboard_pub_, line(1));
  if (wanted(waterfall_pub_))
    emit(waterfall_pub_, waterfall());
}

}  // namespace ros_layer
}  // namespace unexmin

#include <unexmin/engine/mapper.h>
#include <unexmin/ros_layer/m3_cloud.h>
#include <unexmin/ros_layer/m3_publisher.h>

#include <sensor_msgs/LaserScan.h>

namespace unexmin {
namespace ros_layer {

M3Publisher::M3Publisher(const sensors::sonar::M3Sensor& sensor, const PublisherContext& ctx) : sensor_(sensor) {
  pub_ = ctx.nh.advertise<sensor_msgs::LaserScan>(resolve(ctx.ns, topicParam(sensor, "topic", "m3/scan")),
                                                  queueSize(sensor.rate()));
  bool translate = true;
  ctx.nh.param(ctx.ns + "m3_from_simulator", translate, true);
  if (translate)
    points_ = ctx.nh.advertise<sensor_msgs::PointCloud2>(
        resolve(ctx.ns, topicParam(sensor, "points_topic", "m3/points")), queueSize(sensor.rate()));
}

void M3Publisher::publish() {
  const bool points = points_ && wanted(points_);
  if (!wanted(pub_) && !points)
    return;
  const sensors::sonar::M3Scan& s = sensor_.last();
  sensor_msgs::LaserScan m;
  m.header.stamp.fromSec(s.time);
  m.header.frame_id = sensor_.frame();
  const mapping::ScanGeometry g = engine::m3ScanGeometry(sensor_);  // the in-process mapper's numbers too
  m.angle_min = g.angle_min;
  m.angle_max = static_cast<float>(sensor_.beamAngle(sensor_.beams() - 1));
  m.angle_increment = g.angle_increment;
  m.time_increment = 0.0f;
  m.scan_time = static_cast<float>(1.0 / sensor_.rate());
  m.range_min = g.range_min;
  m.range_max = g.range_max;
  m.ranges = s.ranges;
  m.intensities = s.intensities;
  if (wanted(pub_))
    emit(pub_, m);
  if (points)
    emit(points_, scanToCloud(m));
}

}  // namespace ros_layer
}  // namespace unexmin

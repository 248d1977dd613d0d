// Topics of an "sls" sensor (cpp/unexmin/sensors/vision/sls_sensor.h; names from its _topic parameters,
// relative to /<robot>/ unless absolute):
//   topic       (default <name>/points)  sensor_msgs/PointCloud2: the laser points the unit's camera sees, in the
//               camera's optical frame; fields x y z intensity (FLOAT32; intensity = line strength over the
//               detection level, >= 1); stamp = the sample time.
//   scan_topic  (default <name>/scan)    sensor_msgs/LaserScan: the raw fan from the laser head, frame =
//               scan_frame (x-y plane = fan plane, angle = elevation in the head's x-z plane), REP-117 markers.
#pragma once

#include <unexmin/ros_layer/sensor_publisher.h>
#include <unexmin/sensors/vision/sls_sensor.h>

#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>

namespace unexmin {
namespace ros_layer {

class SlsPublisher : public SensorPublisher {
public:
  SlsPublisher(const sensors::vision::SlsSensor& sensor, const PublisherContext& ctx);
  void publish() override;
  sensor_msgs::PointCloud2 cloud() const;
  sensor_msgs::LaserScan scan() const;

private:
  const sensors::vision::SlsSensor& sensor_;
  Stream points_, scan_;
};

}  // namespace ros_layer
}  // namespace unexmin

// Topics of a "side_scan" sensor (cpp/unexmin/sensors/sonar/side_scan_sensor.h; docs/sonars.md), names from its _topic
// parameters, relative to /<robot>/ unless absolute; every one a sensor_msgs/Image mono8, frame = the sensor link,
// stamp = the ping time:
//   port_topic       (default <sensor name>/port)       one ping's port line: 1 row x nbins, column i = range bin i
//   starboard_topic  (default <sensor name>/starboard)  likewise to starboard
//   topic            (default <sensor name>/waterfall)  the waterfall after this ping: waterfall_lines rows (row 0 the
//                    newest ping) x 2 nbins columns, the port line reversed then the starboard line (waterfall.h)
// The geometry as ROS parameters under /<robot>/<sensor name>/: range_min, range_max, range_resolution [m].
#pragma once

#include <unexmin/ros_layer/sensor_publisher.h>
#include <unexmin/sensors/sonar/side_scan_sensor.h>

#include <sensor_msgs/Image.h>

namespace unexmin {
namespace ros_layer {

class SideScanPublisher : public SensorPublisher {
public:
  /// Makes the sensor ping only while one of its topics is wanted (subscribed or recorded).
  SideScanPublisher(sensors::sonar::SideScanSensor& sensor, const PublisherContext& ctx);
  ~SideScanPublisher() override;
  void publish() override;
  /// The latest ping's line of one side (0 port, 1 starboard).
  sensor_msgs::Image line(int side) const;
  /// The waterfall after the latest ping.
  sensor_msgs::Image waterfall() const;

private:
  sensors::sonar::SideScanSensor& sensor_;
  Stream port_pub_, starboard_pub_, waterfall_pub_;
};

}  // namespace ros_layer
}  // namespace unexmin

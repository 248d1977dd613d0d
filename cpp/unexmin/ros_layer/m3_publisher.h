// Topic of an "m3" sensor (cpp/unexmin/sensors/sonar/m3_sensor.h): `topic` (default m3/scan, relative to /<robot>/
// unless absolute), sensor_msgs/LaserScan of the first echoes, frame = the M3 link, stamp = the ping
// time: angle_min/max = -/+ fov_h / 2, angle_increment = fov_h / (beams - 1), time_increment 0 (all
// beams at once), scan_time = 1 / rate, range_min/max, ranges [m] (REP-117: +inf no return within
// range_max, -inf nearer than range_min), intensities = cos(incidence)^n of the return (0: none).
// `points_topic` (default m3/points): sensor_msgs/PointCloud2 x y z, the translation of
// python/unexmin/translators/m3.py (m3_cloud.h), built here when the robot's parameter m3_from_simulator is
// true (default); the rospy translator stays for the real robot (sensors.launch m3_translator:=true).
#pragma once

#include <unexmin/ros_layer/sensor_publisher.h>
#include <unexmin/sensors/sonar/m3_sensor.h>

namespace unexmin {
namespace ros_layer {

class M3Publisher : public SensorPublisher {
public:
  M3Publisher(const sensors::sonar::M3Sensor& sensor, const PublisherContext& ctx);
  void publish() override;

private:
  const sensors::sonar::M3Sensor& sensor_;
  Stream pub_, points_;
};

}  // namespace ros_layer
}  // namespace unexmin

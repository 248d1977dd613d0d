// Topics of an "imaging_sonar" sensor (cpp/unexmin/sensors/sonar/imaging_sonar_sensor.h; docs/sonars.md), names from
// its _topic parameters, relative to /<robot>/ unless absolute:
//   topic      (default <sensor name>/polar)  sensor_msgs/Image mono8, one ping: height = nbins rows (row i = range bin
//              i, row 0 the nearest), width = beams columns (column k = beam k, column 0 the leftmost, to port),
//              frame = the sensor link, stamp = the ping time
//   fan_topic  (default <sensor name>/fan)    sensor_msgs/Image mono8: the Cartesian fan (fan_image.h), the sonar at
//   the
//              middle of the bottom edge, +x up, port left; fan_height rows
//   points_topic (default <sensor name>/points) sensor_msgs/PointCloud2 x, y, z, intensity (float32): per beam the
//              first bin above the noise floor (sensors/sonar/sonar_cloud.h), frame = the sensor link, stamp = the
//              ping time; at most one point per beam
// The geometry, for receivers of the images, as ROS parameters under /<robot>/<sensor name>/: beam_azimuths [rad]
// (one per column), range_min, range_max, range_resolution (bin width) and fan_pixel_size [m]. Read from there:
// cloud_threshold [dB] (default 15, > 0), the cloud's detection threshold above the noise floor.
#pragma once

#include <unexmin/ros_layer/sensor_publisher.h>
#include <unexmin/sensors/sonar/fan_image.h>
#include <unexmin/sensors/sonar/imaging_sonar_sensor.h>
#include <unexmin/sensors/sonar/sonar_cloud.h>

#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

namespace unexmin {
namespace ros_layer {

class ImagingSonarPublisher : public SensorPublisher {
public:
  /// Sets the sensor's demand: a ping is built only while one of its image or cloud topics is wanted (a subscriber
  /// or the recorder). Throws ParameterError for a bad cloud_threshold.
  ImagingSonarPublisher(sensors::sonar::ImagingSonarSensor& sensor, const PublisherContext& ctx);
  ~ImagingSonarPublisher() override;
  void publish() override;
  /// The latest ping as a polar image message.
  sensor_msgs::Image polar() const;
  /// The latest ping as a Cartesian fan image message.
  sensor_msgs::Image fan() const;
  /// The latest ping's detections as a point cloud message (intensity = code / 255).
  sensor_msgs::PointCloud2 points();
  /// A mono8 image message of `rows` x `cols` stamped `time` [s] in `frame`, its data sized (not filled).
  static sensor_msgs::Image mono8(double time, const std::string& frame, std::size_t rows, std::size_t cols);

private:
  sensors::sonar::ImagingSonarSensor& sensor_;
  sensors::sonar::FanImage fan_;
  sensors::sonar::SonarCloud cloud_;
  Stream polar_pub_, fan_pub_, points_pub_;
};

}  // namespace ros_layer
}  // namespace unexmin

// Topics of an "msis" sensor (cpp/unexmin/sensors/sonar/msis_sensor.h; names from its _topic parameters, relative to
// /<robot>/ unless absolute):
//   topic        (default tritech_micron/scan)  sensor_msgs/PointCloud2, one ping: nbins points at the bin
//                centres along the head's +x (x = range [m], y = z = 0), fields x y z intensity rgb (FLOAT32;
//                intensity 0..1; rgb packed as PCL does: 0x00RRGGBB reinterpreted as a float), frame = the
//                head link, stamp = the ping time. Colours: high red, medium yellow, low white-yellow,
//                none blue, shadow dark blue.
//   angle_topic  (default msis/msis_r)          std_msgs/Float64: the head angle of the ping [rad].
#pragma once

#include <unexmin/ros_layer/sensor_publisher.h>
#include <unexmin/sensors/sonar/msis_sensor.h>

#include <sensor_msgs/PointCloud2.h>

#include <array>
#include <cstdint>

namespace unexmin {
namespace ros_layer {

class MsisPublisher : public SensorPublisher {
public:
  /// RGB of each sensors::sonar::EchoLevel (none, low, medium, high, shadow), packed 0x00RRGGBB.
  static const std::array<std::uint32_t, 5>& colours();

  MsisPublisher(const sensors::sonar::MsisSensor& sensor, const PublisherContext& ctx);
  void publish() override;
  /// The cloud of the sensor's latest ping.
  sensor_msgs::PointCloud2 cloud() const;

private:
  const sensors::sonar::MsisSensor& sensor_;
  Stream scan_, angle_;
};

}  // namespace ros_layer
}  // namespace unexmin

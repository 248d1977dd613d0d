// Topics of a "camera" sensor (cpp/unexmin/sensors/vision/camera_sensor.h), image_transport naming, relative to
// /<robot>/ unless absolute:
//   `topic` (default <name>/image_raw): sensor_msgs/Image, encoding rgb8, the rendered frame; advertised in visual
//       mode only, and frames are rendered only while it has a subscriber;
//   `info_topic` (default <name>/camera_info): sensor_msgs/CameraInfo of exactly the published image (width and
//       height after render_scale, distortion_model plumb_bob, D = k1 k2 p1 p2 k3, K, R = I, P = [K | 0]), one per
//       sample in both modes (in operational mode it is the camera's only output).
// frame_id = the camera's optical frame (its <sensor link>), stamp = the sample's sim time, at the camera's fps.
#pragma once

#include <unexmin/ros_layer/sensor_publisher.h>
#include <unexmin/sensors/vision/camera_sensor.h>

#include <sensor_msgs/CameraInfo.h>

namespace unexmin {
namespace ros_layer {

class CameraPublisher : public SensorPublisher {
public:
  /// Tells the camera to render only while its image topic has a subscriber.
  CameraPublisher(sensors::vision::CameraSensor& sensor, const PublisherContext& ctx);
  ~CameraPublisher() override;
  void publish() override;

  /// CameraInfo of `sensor`'s published image (header left empty).
  static sensor_msgs::CameraInfo cameraInfo(const sensors::vision::CameraSensor& sensor);

private:
  sensors::vision::CameraSensor& sensor_;
  Stream image_pub_;  ///< visual mode only
  Stream info_pub_;
  sensor_msgs::CameraInfo info_;
};

}  // namespace ros_layer
}  // namespace unexmin

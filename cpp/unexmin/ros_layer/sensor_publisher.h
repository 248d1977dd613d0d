// ROS face of one simulated sensor: publishes its latest sample. One implementation per sensor family,
// registered under its model's family name (SensorRegistry, ros_layer/sensor_publishers.cpp) and constructed as
// Publisher(const Model& sensor, const PublisherContext& ctx).
#pragma once

#include <unexmin/ros_layer/bag_recorder.h>
#include <unexmin/sensors/sensor.h>

#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/PointField.h>

#include <algorithm>

#include <string>

namespace unexmin {
namespace ros_layer {

/// What a publisher is built with: the node handle (topics, the robot's parameters) and the robot's namespace.
struct PublisherContext {
  ros::NodeHandle& nh;
  std::string ns;  ///< "/<robot>/"
};

class SensorPublisher {
public:
  virtual ~SensorPublisher() = default;
  /// Publishes the sensor's latest sample, stamped with its sample time, on every topic that has
  /// a subscriber or is recorded (other messages are not built). Implementations test a topic with
  /// wanted() and send with emit(), the one way to the simulator's recorder.
  virtual void publish() = 0;

  /// The simulator's recorder (may be null: nothing recorded); must outlive this publisher.
  void attach(BagRecorder* recorder) { recorder_ = recorder; }

  /// `topic` relative to the robot's namespace `ns` ("/UX_1/"), unless it is absolute.
  static std::string resolve(const std::string& ns, const std::string& topic) {
    return sensors::resolveTopic(ns, topic);
  }

  /// Sets `cloud`'s fields to FLOAT32 `names` at offsets 0, 4, 8, ... (point_step = 4 per name), one row of
  /// `points` points, little-endian, dense, and sizes its data.
  static void floatCloud(sensor_msgs::PointCloud2& cloud, const std::vector<std::string>& names, std::size_t points) {
    cloud.fields.clear();
    for (std::size_t f = 0; f < names.size(); ++f) {
      sensor_msgs::PointField field;
      field.name = names[f];
      field.offset = static_cast<std::uint32_t>(4 * f);
      field.datatype = sensor_msgs::PointField::FLOAT32;
      field.count = 1;
      cloud.fields.push_back(field);
    }
    cloud.height = 1;
    cloud.width = static_cast<std::uint32_t>(points);
    cloud.is_bigendian = false;
    cloud.point_step = static_cast<std::uint32_t>(4 * names.size());
    cloud.row_step = cloud.point_step * cloud.width;
    cloud.is_dense = true;
    cloud.data.resize(cloud.row_step);
  }

  /// The sensor's text parameter `key` (a topic name), `fallback` when absent.
  static std::string topicParam(const sensors::Sensor& s, const std::string& key, const std::string& fallback) {
    return sensors::textParam(s, key, fallback);
  }

protected:
  /// Whether a message for `pub` must be built: it has a subscriber or its topic is recorded.
  bool wanted(const Stream& pub) const { return ros_layer::wanted(pub, recorder_); }
  /// Publishes `m` on `pub` and writes it to the recording when its topic is recorded.
  template <class M>
  void emit(const Stream& pub, const M& m) const {
    publishRecorded(pub, recorder_, m);
  }

private:
  BagRecorder* recorder_ = nullptr;
};

}  // namespace ros_layer
}  // namespace unexmin

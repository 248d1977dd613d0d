// The one registration point of sensor families: each family registers its model (a sensors::Sensor, ROS-free)
// and its publisher together, under the type name of <sensor type="..."> in the robot description. Joints a
// family moves are reported by its model (Sensor::movedJoints) and published in joint_states. The built-in
// families are registered in ros/sensor_families.cpp; a test or a user program may add its own.
// See docs/adding_a_sensor.md.
#pragma once

#include <unexmin/ros_layer/sensor_publisher.h>
#include <unexmin/sensors/sensor_factory.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace unexmin {
namespace ros_layer {

class SensorRegistry {
public:
  using PublisherCreator = std::function<std::unique_ptr<SensorPublisher>(sensors::Sensor&, const PublisherContext&)>;

  /// Registers (or replaces) family `type`: sensors built as Model(const sim::SensorSpec&, const
  /// sensors::SensorSetup&), published by Publisher(const Model&, const PublisherContext&) (or Publisher(Model&,
  /// ...) when the publisher tells its model something, e.g. a camera renders only while someone subscribes).
  template <class Model, class Publisher>
  void add(const std::string& type) {
    models_.add<Model>(type);
    // The model of this family was built by the line above: the downcast cannot fail.
    publishers_[type] = [](sensors::Sensor& s, const PublisherContext& ctx) -> std::unique_ptr<SensorPublisher> {
      return std::make_unique<Publisher>(static_cast<Model&>(s), ctx);
    };
  }

  /// The models of every registered family (what sensors::SensorSuite builds from).
  const sensors::SensorFactory& models() const { return models_; }
  /// Family names, sorted.
  std::vector<std::string> types() const { return models_.types(); }
  /// The publisher of `sensor` (of a registered family; throws ConfigError otherwise).
  std::unique_ptr<SensorPublisher> publisher(sensors::Sensor& sensor, const PublisherContext& ctx) const;

  /// The simulator's families (ros/sensor_families.cpp).
  static SensorRegistry builtin();

private:
  sensors::SensorFactory models_;
  std::map<std::string, PublisherCreator> publishers_;
};

}  // namespace ros_layer
}  // namespace unexmin

// The ROS face of the sensor families: the models of sensors::SensorFactory (the one registration of a family, its
// model and its sample description; engine/sensor_families.cpp) with one publisher per family on top, under the
// same type name. check() refuses a registry where a model family has no publisher; the simulator calls it at
// start-up. Joints a family moves are reported by its model (Sensor::movedJoints) and published in joint_states.
// The built-in publishers are in ros_layer/sensor_publishers.cpp; a test or a user program may add its own
// families. See docs/adding_a_sensor.md.
#pragma once

#include <unexmin/core/error.h>
#include <unexmin/engine/sensor_families.h>
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

  /// A registry of the families of `models`, with no publisher yet.
  explicit SensorRegistry(sensors::SensorFactory models = sensors::SensorFactory()) : models_(std::move(models)) {}

  /// Publishes family `type` with Publisher(const Model&, const PublisherContext&) (or Publisher(Model&, ...) when the
  /// publisher tells its model something, e.g. a camera renders only while someone subscribes). A sensor of that
  /// type that is not a Model stops start-up with a ConfigError naming it.
  template <class Model, class Publisher>
  void addPublisher(const std::string& type) {
    publishers_[type] = [type](sensors::Sensor& s, const PublisherContext& ctx) -> std::unique_ptr<SensorPublisher> {
      auto* model = dynamic_cast<Model*>(&s);
      if (model == nullptr)
        throw ConfigError(s.robotName() + ": sensor '" + s.name() + "': the publisher of family '" + type +
                          "' does not publish this model");
      return std::make_unique<Publisher>(*model, ctx);
    };
  }
  /// Registers (or replaces) family `type` with both its model (built as Model(const sim::SensorSpec&, const
  /// sensors::SensorSetup&)) and its publisher.
  template <class Model, class Publisher>
  void add(const std::string& type) {
    models_.add<Model>(type);
    addPublisher<Model, Publisher>(type);
  }

  /// The models of every registered family (what sensors::SensorSuite builds from).
  const sensors::SensorFactory& models() const { return models_; }
  /// Family names, sorted.
  std::vector<std::string> types() const { return models_.types(); }
  /// Throws ConfigError naming every model family without a publisher.
  void check() const;
  /// The publisher of `sensor` (of a registered family; throws ConfigError otherwise).
  std::unique_ptr<SensorPublisher> publisher(sensors::Sensor& sensor, const PublisherContext& ctx) const;

  /// The simulator's families (engine::sensorFamilies()) with their publishers (ros_layer/sensor_publishers.cpp).
  static SensorRegistry builtin();

private:
  sensors::SensorFactory models_;
  std::map<std::string, PublisherCreator> publishers_;
};

}  // namespace ros_layer
}  // namespace unexmin

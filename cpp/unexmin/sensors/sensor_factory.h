// Sensor models by family name (the type of a <sensor type="..."> element). Knows no family itself: the simulator's
// are registered once, in engine/sensor_families.cpp (both front ends build from it, the ROS layer adding one
// publisher per family on top, ros_layer/sensor_registry.h); a test or a user program adds its own families with
// add<Model>("type"). docs/adding_a_sensor.md.
#pragma once

#include <unexmin/sensors/sensor.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace unexmin {
namespace sensors {

class SensorFactory {
public:
  using Creator = std::function<std::unique_ptr<Sensor>(const sim::SensorSpec&, const SensorSetup&)>;

  /// Registers (or replaces) the family `type`, built by `creator`. Throws ConfigError on an empty name or
  /// creator.
  void add(const std::string& type, Creator creator);
  /// Registers `Model` (constructed from (const sim::SensorSpec&, const SensorSetup&)) as family `type`.
  template <class Model>
  void add(const std::string& type) {
    add(type,
        [](const sim::SensorSpec& spec, const SensorSetup& setup) { return std::make_unique<Model>(spec, setup); });
  }

  bool has(const std::string& type) const { return creators_.count(type) > 0; }
  /// Family names, sorted.
  std::vector<std::string> types() const;

  /// The sensor of `spec`; throws ConfigError for an unknown type (naming the robot, the sensor and the known
  /// types) or a bad parameter (naming the robot, the sensor and the parameter).
  std::unique_ptr<Sensor> create(const sim::SensorSpec& spec, const SensorSetup& setup) const;

private:
  std::map<std::string, Creator> creators_;
};

}  // namespace sensors
}  // namespace unexmin

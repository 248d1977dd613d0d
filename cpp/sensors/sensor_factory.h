// Sensor families by type name (the <sensor type="..."> of the robot description). A user adds a
// model with add() without touching the engine; the built-in families are "imu", "dvl" and
// "pressure".
#pragma once

#include "sensors/sensor.h"

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace unexmin {
namespace sensors {

class SensorFactory
{
public:
  using Creator = std::function<std::unique_ptr<Sensor>(const sim::SensorSpec&, const SensorSetup&)>;

  /// A factory that knows the built-in families.
  SensorFactory();

  /// Registers (or replaces) the family `type`.
  void add(const std::string& type, Creator creator);
  bool has(const std::string& type) const { return creators_.count(type) > 0; }
  std::vector<std::string> types() const;

  /// The sensor of `spec`; throws sim::ConfigError for an unknown type or a bad parameter (the
  /// message names the robot, the sensor and the parameter).
  std::unique_ptr<Sensor> create(const sim::SensorSpec& spec, const SensorSetup& setup) const;

private:
  std::map<std::string, Creator> creators_;
};

}  // namespace sensors
}  // namespace unexmin

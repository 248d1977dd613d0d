#include <unexmin/ros_layer/sensor_registry.h>

namespace unexmin {
namespace ros_layer {

void SensorRegistry::check() const {
  std::string missing;
  for (const auto& type : models_.types())
    if (publishers_.count(type) == 0)
      missing += (missing.empty() ? "'" : ", '") + type + "'";
  if (!missing.empty())
    throw ConfigError("sensor families without a publisher: " + missing +
                      " (register one with SensorRegistry::addPublisher, docs/adding_a_sensor.md)");
}

std::unique_ptr<SensorPublisher> SensorRegistry::publisher(sensors::Sensor& sensor, const PublisherContext& ctx) const {
  const auto it = publishers_.find(sensor.type());
  if (it == publishers_.end())
    throw ConfigError(sensor.robotName() + ": sensor '" + sensor.name() + "': no publisher for type '" + sensor.type() +
                      "'");
  return it->second(sensor, ctx);
}

}  // namespace ros_layer
}  // namespace unexmin

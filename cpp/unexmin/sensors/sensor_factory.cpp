#include <unexmin/sensors/sensor_factory.h>

namespace unexmin {
namespace sensors {

void SensorFactory::add(const std::string& type, Creator creator) {
  if (type.empty())
    throw ConfigError("sensor factory: a sensor family needs a non-empty type name");
  if (!creator)
    throw ConfigError("sensor factory: family '" + type + "' has no creator");
  creators_[type] = std::move(creator);
}

std::vector<std::string> SensorFactory::types() const {
  std::vector<std::string> out;
  for (const auto& kv : creators_)
    out.push_back(kv.first);
  return out;
}

std::unique_ptr<Sensor> SensorFactory::create(const sim::SensorSpec& spec, const SensorSetup& setup) const {
  const auto it = creators_.find(spec.type);
  if (it == creators_.end()) {
    std::string known;
    for (const auto& t : types())
      known += (known.empty() ? "" : ", ") + t;
    throw ConfigError(setup.robot + ": sensor '" + spec.name + "': unknown type '" + spec.type +
                      "' (known: " + (known.empty() ? "none" : known) + ")");
  }
  return it->second(spec, setup);
}

}  // namespace sensors
}  // namespace unexmin

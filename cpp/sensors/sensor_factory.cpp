#include "sensors/sensor_factory.h"

#include "sensors/dvl_sensor.h"
#include "sensors/imu_sensor.h"
#include "sensors/pressure_sensor.h"
#include "sonar/m3_sensor.h"    // [sonar]
#include "sonar/msis_sensor.h"  // [sonar]

namespace unexmin {
namespace sensors {
namespace {

template <class T>
SensorFactory::Creator creator()
{
  return [](const sim::SensorSpec& spec, const SensorSetup& setup) { return std::make_unique<T>(spec, setup); };
}

}  // namespace

SensorFactory::SensorFactory()
{
  add("imu", creator<ImuSensor>());
  add("dvl", creator<DvlSensor>());
  add("pressure", creator<PressureSensor>());
  add("msis", creator<sonar::MsisSensor>());  // [sonar] cpp/sonar/msis_sensor.h
  add("m3", creator<sonar::M3Sensor>());      // [sonar] cpp/sonar/m3_sensor.h
}

void SensorFactory::add(const std::string& type, Creator creator) { creators_[type] = std::move(creator); }

std::vector<std::string> SensorFactory::types() const
{
  std::vector<std::string> out;
  for (const auto& kv : creators_) out.push_back(kv.first);
  return out;
}

std::unique_ptr<Sensor> SensorFactory::create(const sim::SensorSpec& spec, const SensorSetup& setup) const
{
  const auto it = creators_.find(spec.type);
  if (it == creators_.end()) {
    std::string known;
    for (const auto& t : types()) known += (known.empty() ? "" : ", ") + t;
    throw sim::ConfigError(setup.robot + ": sensor '" + spec.name + "': unknown type '" + spec.type +
                           "' (known: " + known + ")");
  }
  return it->second(spec, setup);
}

}  // namespace sensors
}  // namespace unexmin

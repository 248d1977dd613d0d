#include <unexmin/engine/sensor_families.h>

#include <unexmin/sensors/dvl_sensor.h>
#include <unexmin/sensors/imu_sensor.h>
#include <unexmin/sensors/pressure_sensor.h>
#include <unexmin/sensors/science/gamma_counter_sensor.h>
#include <unexmin/sensors/science/magnetometer_sensor.h>
#include <unexmin/sensors/science/water_probe_sensor.h>
#include <unexmin/sensors/science/water_sampler_sensor.h>
#include <unexmin/sensors/sonar/imaging_sonar_sensor.h>
#include <unexmin/sensors/sonar/m3_sensor.h>
#include <unexmin/sensors/sonar/msis_sensor.h>
#include <unexmin/sensors/sonar/side_scan_sensor.h>
#include <unexmin/sensors/vision/camera_sensor.h>
#include <unexmin/sensors/vision/sls_sensor.h>

namespace unexmin {
namespace engine {

sensors::SensorFactory sensorFamilies() {
  sensors::SensorFactory f;
  f.add<sensors::ImuSensor>("imu");                            // docs/sensors.md
  f.add<sensors::DvlSensor>("dvl");                            // docs/sensors.md
  f.add<sensors::PressureSensor>("pressure");                  // docs/sensors.md
  f.add<sensors::sonar::MsisSensor>("msis");                   // docs/sonars.md
  f.add<sensors::sonar::M3Sensor>("m3");                       // docs/sonars.md
  f.add<sensors::sonar::ImagingSonarSensor>("imaging_sonar");  // docs/sonars.md
  f.add<sensors::sonar::SideScanSensor>("side_scan");          // docs/sonars.md
  f.add<sensors::vision::SlsSensor>("sls");                    // docs/sls.md
  f.add<sensors::vision::CameraSensor>("camera");              // docs/vision.md
  // the science payload
  f.add<sensors::science::WaterProbeSensor>("water_probe");      // docs/water_probe.md
  f.add<sensors::science::MagnetometerSensor>("magnetometer");   // docs/magnetometer.md
  f.add<sensors::science::GammaCounterSensor>("gamma_counter");  // docs/gamma_counter.md
  f.add<sensors::science::WaterSamplerSensor>("water_sampler");  // docs/water_sampler.md
  return f;
}

}  // namespace engine
}  // namespace unexmin

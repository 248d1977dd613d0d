// The publishers of the simulator's sensor families (engine/sensor_families.cpp): one line each, under the family's
// type name. Adding a family: docs/adding_a_sensor.md.
#include <unexmin/ros_layer/sensor_registry.h>

#include <unexmin/ros_layer/camera_publisher.h>
#include <unexmin/ros_layer/dvl_publisher.h>
#include <unexmin/ros_layer/gamma_counter_publisher.h>
#include <unexmin/ros_layer/imaging_sonar_publisher.h>
#include <unexmin/ros_layer/imu_publisher.h>
#include <unexmin/ros_layer/m3_publisher.h>
#include <unexmin/ros_layer/magnetometer_publisher.h>
#include <unexmin/ros_layer/msis_publisher.h>
#include <unexmin/ros_layer/pressure_publisher.h>
#include <unexmin/ros_layer/side_scan_publisher.h>
#include <unexmin/ros_layer/sls_publisher.h>
#include <unexmin/ros_layer/water_probe_publisher.h>
#include <unexmin/ros_layer/water_sampler_publisher.h>

namespace unexmin {
namespace ros_layer {

SensorRegistry SensorRegistry::builtin() {
  SensorRegistry r(engine::sensorFamilies());
  r.addPublisher<sensors::ImuSensor, ImuPublisher>("imu");                                     // docs/sensors.md
  r.addPublisher<sensors::DvlSensor, DvlPublisher>("dvl");                                     // docs/sensors.md
  r.addPublisher<sensors::PressureSensor, PressurePublisher>("pressure");                      // docs/sensors.md
  r.addPublisher<sensors::sonar::MsisSensor, MsisPublisher>("msis");                           // docs/sonars.md
  r.addPublisher<sensors::sonar::M3Sensor, M3Publisher>("m3");                                 // docs/sonars.md
  r.addPublisher<sensors::sonar::ImagingSonarSensor, ImagingSonarPublisher>("imaging_sonar");  // docs/sonars.md
  r.addPublisher<sensors::sonar::SideScanSensor, SideScanPublisher>("side_scan");              // docs/sonars.md
  r.addPublisher<sensors::vision::SlsSensor, SlsPublisher>("sls");                             // docs/sls.md
  r.addPublisher<sensors::vision::CameraSensor, CameraPublisher>("camera");                    // docs/vision.md
  // the science payload: docs/water_probe.md, docs/magnetometer.md, docs/gamma_counter.md, docs/water_sampler.md
  r.addPublisher<sensors::science::WaterProbeSensor, WaterProbePublisher>("water_probe");
  r.addPublisher<sensors::science::MagnetometerSensor, MagnetometerPublisher>("magnetometer");
  r.addPublisher<sensors::science::GammaCounterSensor, GammaCounterPublisher>("gamma_counter");
  r.addPublisher<sensors::science::WaterSamplerSensor, WaterSamplerPublisher>("water_sampler");
  return r;
}

}  // namespace ros_layer
}  // namespace unexmin

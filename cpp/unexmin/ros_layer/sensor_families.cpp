// The simulator's sensor families: one line each, the model (cpp/unexmin/sensors) with its publisher
// (cpp/unexmin/ros_layer). Adding a family: docs/adding_a_sensor.md.
#include <unexmin/ros_layer/sensor_registry.h>

#include <unexmin/ros_layer/camera_publisher.h>
#include <unexmin/ros_layer/dvl_publisher.h>
#include <unexmin/ros_layer/imaging_sonar_publisher.h>
#include <unexmin/ros_layer/imu_publisher.h>
#include <unexmin/ros_layer/m3_publisher.h>
#include <unexmin/ros_layer/msis_publisher.h>
#include <unexmin/ros_layer/pressure_publisher.h>
#include <unexmin/ros_layer/side_scan_publisher.h>
#include <unexmin/ros_layer/sls_publisher.h>

namespace unexmin {
namespace ros_layer {

SensorRegistry SensorRegistry::builtin() {
  SensorRegistry r;
  r.add<sensors::ImuSensor, ImuPublisher>("imu");                                     // docs/sensors.md
  r.add<sensors::DvlSensor, DvlPublisher>("dvl");                                     // docs/sensors.md
  r.add<sensors::PressureSensor, PressurePublisher>("pressure");                      // docs/sensors.md
  r.add<sensors::sonar::MsisSensor, MsisPublisher>("msis");                           // docs/sonars.md
  r.add<sensors::sonar::M3Sensor, M3Publisher>("m3");                                 // docs/sonars.md
  r.add<sensors::sonar::ImagingSonarSensor, ImagingSonarPublisher>("imaging_sonar");  // docs/sonars.md
  r.add<sensors::sonar::SideScanSensor, SideScanPublisher>("side_scan");              // docs/sonars.md
  r.add<sensors::vision::SlsSensor, SlsPublisher>("sls");                             // docs/sls.md
  r.add<sensors::vision::CameraSensor, CameraPublisher>("camera");                    // docs/vision.md
  return r;
}

}  // namespace ros_layer
}  // namespace unexmin

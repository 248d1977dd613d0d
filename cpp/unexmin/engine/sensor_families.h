// The simulator's sensor families: the one registration of each, its type name (<sensor type="..."> in the robot
// description) and its model, one line each in sensor_families.cpp. A model describes its own sample
// (Sensor::describe), so the in-process module needs nothing more; the ROS layer adds one publisher per family on
// top (ros_layer/sensor_publishers.cpp) and refuses to start when one has none. Adding a family:
// docs/adding_a_sensor.md. Knows no ROS.
#pragma once

#include <unexmin/sensors/sensor_factory.h>

namespace unexmin {
namespace engine {

/// The models of the simulator's sensor families by type name.
sensors::SensorFactory sensorFamilies();

}  // namespace engine
}  // namespace unexmin

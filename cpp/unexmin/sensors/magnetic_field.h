// What a magnetometer on a robot reads before its own errors (docs/magnetometer.md): the world's total field at its
// origin (the Earth's and the geology's anomalies, sim::World::magneticField) through the robot's own field
// (sim::RobotMagnetics: soft and hard iron, the thrusters' currents), in the sensor frame. Shared by the IMU's
// magnetometer and the fluxgate (sensors/science). Knows no ROS.
#pragma once

#include <unexmin/sensors/sensor.h>

#include <Eigen/Geometry>

namespace unexmin {
namespace sensors {

/// The field [nT] in the frame `mount` (a sensor frame in the base link frame) of the robot of `ctx`:
/// R_m^T (S R^T B(p) + h + sum_i v_i I_i), R the base link's orientation, p the mount's origin in the world.
Eigen::Vector3d magnetometerField(const SensorContext& ctx, const Eigen::Isometry3d& mount);

}  // namespace sensors
}  // namespace unexmin

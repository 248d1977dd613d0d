// Poses written as xyz and roll-pitch-yaw, as world files and URDF origins give them. Knows no ROS.
#pragma once

#include <Eigen/Geometry>

namespace unexmin {
namespace sim {

/// Pose from xyz [m] and roll-pitch-yaw [rad] (URDF convention: R = Rz(yaw) Ry(pitch) Rx(roll)).
Eigen::Isometry3d poseFromXyzRpy(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy);

}  // namespace sim
}  // namespace unexmin

// A URDF joint origin as robot_state_publisher puts it on tf, number for number: urdfdom turns the origin's rpy [rad]
// into a quaternion (half-angle products, normalised), kdl_parser makes it KDL's rotation matrix and
// robot_state_publisher reads the quaternion back off that matrix (KDL's trace method); the translation is the
// origin's xyz [m] as written. The mapper places clouds through those published mounts, so the in-process mapper
// (engine::Mapper) takes them from here to place its clouds on the same floats. test_joint_transform.cpp checks it
// against urdfdom and KDL bit for bit. Knows no ROS.
#pragma once

#include <unexmin/mapping/rigid_transform.h>

#include <Eigen/Core>

namespace unexmin {
namespace mapping {

/// The child link in the parent link of a joint at its zero position (a fixed joint's /tf_static sample):
/// origin xyz [m] and rpy (roll about x, pitch about y, yaw about z, applied in that order) [rad].
RigidTransform jointOriginTransform(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy);

}  // namespace mapping
}  // namespace unexmin

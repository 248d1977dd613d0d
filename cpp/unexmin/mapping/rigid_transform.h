// A rigid transform (translation and unit quaternion) with the arithmetic of tf2's buffer, operation for
// operation: interpolation between two samples (linear in translation, slerp in rotation), composition along
// a chain of frames and inversion give the numbers tf2_ros's lookupTransform would, and a cloud transformed
// here lands on the same floats as one transformed through a tf2::Matrix3x3. Knows no ROS.
#pragma once

#include <octomap/octomap_types.h>

#include <Eigen/Geometry>

#include <vector>

namespace unexmin {
namespace mapping {

/// x_parent = rotation * x_child + translation: the pose of a child frame in its parent frame.
struct RigidTransform {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();         ///< child origin in the parent frame [m]
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  ///< child axes in the parent frame (unit)

  /// The transform at ratio (0: a, 1: b) between two samples: translation (1 - ratio) a + ratio b, rotation
  /// the shortest-path slerp.
  static RigidTransform interpolate(const RigidTransform& a, const RigidTransform& b, double ratio);
  /// parent_from_child * child_from_x = parent_from_x.
  RigidTransform operator*(const RigidTransform& child_from_x) const;
  /// The transform back: child_from_parent.
  RigidTransform inverse() const;
  /// v [m, child frame] in the parent frame, rotated by the quaternion product q v q*.
  Eigen::Vector3d rotate(const Eigen::Vector3d& v) const;
  /// Points [m, child frame] in the parent frame, through the rotation matrix of the quaternion, each
  /// coordinate computed in double and rounded to float.
  std::vector<octomap::point3d> apply(const std::vector<octomap::point3d>& points) const;
};

}  // namespace mapping
}  // namespace unexmin

#include <unexmin/mapping/joint_transform.h>

#include <cmath>

namespace unexmin {
namespace mapping {

namespace {

/// urdfdom's Rotation::setFromRPY: the quaternion of the half angles, divided by its norm (identity at norm 0).
Eigen::Quaterniond urdfQuaternion(const Eigen::Vector3d& rpy) {
  const double phi = rpy.x() / 2.0, the = rpy.y() / 2.0, psi = rpy.z() / 2.0;
  double x = std::sin(phi) * std::cos(the) * std::cos(psi) - std::cos(phi) * std::sin(the) * std::sin(psi);
  double y = std::cos(phi) * std::sin(the) * std::cos(psi) + std::sin(phi) * std::cos(the) * std::sin(psi);
  double z = std::cos(phi) * std::cos(the) * std::sin(psi) - std::sin(phi) * std::sin(the) * std::cos(psi);
  double w = std::cos(phi) * std::cos(the) * std::cos(psi) + std::sin(phi) * std::sin(the) * std::sin(psi);
  const double s = std::sqrt(x * x + y * y + z * z + w * w);
  if (s == 0.0)
    return Eigen::Quaterniond::Identity();
  x /= s;
  y /= s;
  z /= s;
  w /= s;
  return Eigen::Quaterniond(w, x, y, z);
}

/// KDL's Rotation::Quaternion: the rotation matrix of a unit quaternion, from the squares and products.
Eigen::Matrix3d kdlMatrix(const Eigen::Quaterniond& q) {
  const double x = q.x(), y = q.y(), z = q.z(), w = q.w();
  const double x2 = x * x, y2 = y * y, z2 = z * z, w2 = w * w;
  Eigen::Matrix3d m;
  m << w2 + x2 - y2 - z2, 2 * x * y - 2 * w * z, 2 * x * z + 2 * w * y,  //
      2 * x * y + 2 * w * z, w2 - x2 + y2 - z2, 2 * y * z - 2 * w * x,   //
      2 * x * z - 2 * w * y, 2 * y * z + 2 * w * x, w2 - x2 - y2 + z2;
  return m;
}

/// KDL's Rotation::GetQuaternion: from the trace when it is positive, else from the largest diagonal element.
Eigen::Quaterniond kdlQuaternion(const Eigen::Matrix3d& m) {
  double x, y, z, w;
  const double trace = m(0, 0) + m(1, 1) + m(2, 2);
  if (trace > 1e-12) {
    const double s = 0.5 / std::sqrt(trace + 1.0);
    w = 0.25 / s;
    x = (m(2, 1) - m(1, 2)) * s;
    y = (m(0, 2) - m(2, 0)) * s;
    z = (m(1, 0) - m(0, 1)) * s;
  } else if (m(0, 0) > m(1, 1) && m(0, 0) > m(2, 2)) {
    const double s = 2.0 * std::sqrt(1.0 + m(0, 0) - m(1, 1) - m(2, 2));
    w = (m(2, 1) - m(1, 2)) / s;
    x = 0.25 * s;
    y = (m(0, 1) + m(1, 0)) / s;
    z = (m(0, 2) + m(2, 0)) / s;
  } else if (m(1, 1) > m(2, 2)) {
    const double s = 2.0 * std::sqrt(1.0 + m(1, 1) - m(0, 0) - m(2, 2));
    w = (m(0, 2) - m(2, 0)) / s;
    x = (m(0, 1) + m(1, 0)) / s;
    y = 0.25 * s;
    z = (m(1, 2) + m(2, 1)) / s;
  } else {
    const double s = 2.0 * std::sqrt(1.0 + m(2, 2) - m(0, 0) - m(1, 1));
    w = (m(1, 0) - m(0, 1)) / s;
    x = (m(0, 2) + m(2, 0)) / s;
    y = (m(1, 2) + m(2, 1)) / s;
    z = 0.25 * s;
  }
  return Eigen::Quaterniond(w, x, y, z);
}

}  // namespace

RigidTransform jointOriginTransform(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy) {
  RigidTransform t;
  t.translation = xyz;
  t.rotation = kdlQuaternion(kdlMatrix(urdfQuaternion(rpy)));
  return t;
}

}  // namespace mapping
}  // namespace unexmin

#include <unexmin/mapping/rigid_transform.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace mapping {

namespace {

// The quaternion products below keep one order of terms: the results are compared bit for bit with tf2's.
using Quat = Eigen::Quaterniond;

Quat multiply(const Quat& a, const Quat& b) {
  return Quat(a.w() * b.w() - a.x() * b.x() - a.y() * b.y() - a.z() * b.z(),
              a.w() * b.x() + a.x() * b.w() + a.y() * b.z() - a.z() * b.y(),
              a.w() * b.y() + a.y() * b.w() + a.z() * b.x() - a.x() * b.z(),
              a.w() * b.z() + a.z() * b.w() + a.x() * b.y() - a.y() * b.x());
}

/// a * (v, 0).
Quat multiply(const Quat& a, const Eigen::Vector3d& v) {
  return Quat(-a.x() * v.x() - a.y() * v.y() - a.z() * v.z(), a.w() * v.x() + a.y() * v.z() - a.z() * v.y(),
              a.w() * v.y() + a.z() * v.x() - a.x() * v.z(), a.w() * v.z() + a.x() * v.y() - a.y() * v.x());
}

Quat conjugate(const Quat& q) {
  return Quat(q.w(), -q.x(), -q.y(), -q.z());
}

double dot(const Quat& a, const Quat& b) {
  return a.x() * b.x() + a.y() * b.y() + a.z() * b.z() + a.w() * b.w();
}

double clampedAcos(double c) {
  return std::acos(std::min(1.0, std::max(-1.0, c)));
}

Quat slerp(const Quat& a, const Quat& b, double t) {
  const double s = std::sqrt(dot(a, a) * dot(b, b));
  const double d = dot(a, b);
  const double half = (d < 0 ? clampedAcos(-d / s) : clampedAcos(d / s)) * 2.0 / 2.0;
  if (half == 0.0)
    return a;
  const double k = 1.0 / std::sin(half);
  const double s0 = std::sin((1.0 - t) * half);
  const double s1 = std::sin(t * half);
  const double sign = d < 0 ? -1.0 : 1.0;
  return Quat((a.w() * s0 + sign * b.w() * s1) * k, (a.x() * s0 + sign * b.x() * s1) * k,
              (a.y() * s0 + sign * b.y() * s1) * k, (a.z() * s0 + sign * b.z() * s1) * k);
}

}  // namespace

RigidTransform RigidTransform::interpolate(const RigidTransform& a, const RigidTransform& b, double ratio) {
  const double s = 1.0 - ratio;
  RigidTransform out;
  out.translation = Eigen::Vector3d(s * a.translation.x() + ratio * b.translation.x(),
                                    s * a.translation.y() + ratio * b.translation.y(),
                                    s * a.translation.z() + ratio * b.translation.z());
  out.rotation = slerp(a.rotation, b.rotation, ratio);
  return out;
}

Eigen::Vector3d RigidTransform::rotate(const Eigen::Vector3d& v) const {
  const Quat q = multiply(multiply(rotation, v), conjugate(rotation));
  return Eigen::Vector3d(q.x(), q.y(), q.z());
}

RigidTransform RigidTransform::operator*(const RigidTransform& child_from_x) const {
  RigidTransform out;
  const Eigen::Vector3d r = rotate(child_from_x.translation);
  out.translation = Eigen::Vector3d(r.x() + translation.x(), r.y() + translation.y(), r.z() + translation.z());
  out.rotation = multiply(rotation, child_from_x.rotation);
  return out;
}

RigidTransform RigidTransform::inverse() const {
  RigidTransform out;
  out.rotation = conjugate(rotation);
  const Eigen::Vector3d back = out.rotate(Eigen::Vector3d(-translation.x(), -translation.y(), -translation.z()));
  out.translation = back;
  return out;
}

std::vector<octomap::point3d> RigidTransform::apply(const std::vector<octomap::point3d>& points) const {
  const Quat& q = rotation;
  const double s = 2.0 / dot(q, q);
  const double xs = q.x() * s, ys = q.y() * s, zs = q.z() * s;
  const double wx = q.w() * xs, wy = q.w() * ys, wz = q.w() * zs;
  const double xx = q.x() * xs, xy = q.x() * ys, xz = q.x() * zs;
  const double yy = q.y() * ys, yz = q.y() * zs, zz = q.z() * zs;
  const double m[3][3] = {
      {1.0 - (yy + zz), xy - wz, xz + wy}, {xy + wz, 1.0 - (xx + zz), yz - wx}, {xz - wy, yz + wx, 1.0 - (xx + yy)}};
  const Eigen::Vector3d& t = translation;
  std::vector<octomap::point3d> out;
  out.reserve(points.size());
  for (const octomap::point3d& p : points) {
    const double x = p.x(), y = p.y(), z = p.z();
    out.emplace_back(static_cast<float>(m[0][0] * x + m[0][1] * y + m[0][2] * z + t.x()),
                     static_cast<float>(m[1][0] * x + m[1][1] * y + m[1][2] * z + t.y()),
                     static_cast<float>(m[2][0] * x + m[2][1] * y + m[2][2] * z + t.z()));
  }
  return out;
}

}  // namespace mapping
}  // namespace unexmin

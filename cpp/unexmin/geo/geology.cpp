#include <unexmin/geo/geology.h>

#include <cmath>

namespace unexmin {
namespace geo {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Inside test of a body in its own frame: q = pose^-1 p.
bool containsLocal(const Body& b, const Eigen::Vector3d& q) {
  switch (b.kind) {
    case BodyKind::ellipsoid:
      return (q.array() / b.size.array()).matrix().squaredNorm() <= 1.0;
    case BodyKind::box:
      return (q.array().abs() <= 0.5 * b.size.array()).all();
    case BodyKind::vein:
      return std::abs(q.z()) <= 0.5 * b.size.z() && q.head<2>().squaredNorm() <= b.size.x() * b.size.x();
    case BodyKind::stratum:
      return q.z() >= 0.0 && q.z() <= b.size.z();
  }
  return false;
}

/// World-frame bounding box of a body.
Eigen::AlignedBox3d boundsOf(const Body& b) {
  Eigen::AlignedBox3d box;
  const Eigen::Matrix3d& R = b.pose.linear();
  const Eigen::Vector3d c = b.pose.translation();
  Eigen::Vector3d half;
  switch (b.kind) {
    case BodyKind::ellipsoid:  // the ellipsoid's extent along world axis i: sqrt(sum_j (R_ij a_j)^2)
      half = (R.array().rowwise() * b.size.transpose().array()).matrix().rowwise().norm();
      break;
    case BodyKind::box:
      half = R.cwiseAbs() * (0.5 * b.size);
      break;
    case BodyKind::vein: {
      if (!std::isfinite(b.size.x()))
        return Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-kInf), Eigen::Vector3d::Constant(kInf));
      // a disc of radius e normal to n: extent e sqrt(1 - n_i^2) in the plane plus t/2 |n_i| across it
      const Eigen::Vector3d n = R.col(2);
      for (int i = 0; i < 3; ++i)
        half[i] = b.size.x() * std::sqrt(std::max(0.0, 1.0 - n[i] * n[i])) + 0.5 * b.size.z() * std::abs(n[i]);
      break;
    }
    case BodyKind::stratum:
      return Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-kInf), Eigen::Vector3d::Constant(kInf));
  }
  box.extend(c - half);
  box.extend(c + half);
  return box;
}

}  // namespace

const std::vector<std::string>& bodyKindNames() {
  static const std::vector<std::string> names = {"ellipsoid", "box", "vein", "stratum"};
  return names;
}

bool Body::contains(const Eigen::Vector3d& p) const {
  return containsLocal(*this, pose.inverse(Eigen::Isometry) * p);
}

Geology::Geology(Rock host, std::vector<Body> bodies) : host_(std::move(host)), bodies_(std::move(bodies)) {
  for (const auto& b : bodies_) {
    bounds_.push_back(boundsOf(b));
    inverse_.push_back(b.pose.inverse(Eigen::Isometry));
  }
}

int Geology::bodyAt(const Eigen::Vector3d& p) const {
  for (std::size_t k = bodies_.size(); k-- > 0;)
    if (bounds_[k].contains(p) && containsLocal(bodies_[k], inverse_[k] * p))
      return static_cast<int>(k) + 1;
  return 0;
}

const std::string& Geology::name(int id) const {
  return id == 0 ? host_name_ : bodies_.at(static_cast<std::size_t>(id) - 1).name;
}

}  // namespace geo
}  // namespace unexmin

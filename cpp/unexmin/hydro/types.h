// Common types of the hydrodynamics core. No ROS in here.
#pragma once

#include <unexmin/core/error.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <map>
#include <string>
#include <vector>

namespace unexmin {
namespace hydro {

/// Generalised 6-vector in Fossen's order [u v w p q r] or [X Y Z K M N] (body frame, SNAME).
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// Named numeric parameters of a model chosen by name (e.g. {"tau": {0.1}}), as read from the
/// robot description. Scalars are one-element vectors; tables are longer vectors.
using ParamMap = std::map<std::string, std::vector<double>>;

/// Value of a required scalar parameter; throws ParameterError naming `what` and `key`.
double requireScalar(const ParamMap& params, const std::string& key, const std::string& what);

/// Skew-symmetric matrix S(a) with S(a) b = a x b.
inline Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d s;
  s << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return s;
}

}  // namespace hydro
}  // namespace unexmin

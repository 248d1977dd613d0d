// The joint-tree queries of RobotDescription.
#include <unexmin/sim/description_types.h>

#include <unexmin/core/error.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace sim {

Eigen::Isometry3d RobotDescription::linkPose(const std::string& link) const {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  std::string current = link;
  for (std::size_t guard = 0; current != base_link && guard <= joints.size(); ++guard) {
    const auto it = std::find_if(joints.begin(), joints.end(), [&](const JointInfo& j) { return j.child == current; });
    if (it == joints.end())
      throw ConfigError(source + ": link '" + link + "' is not connected to '" + base_link + "'");
    pose = it->origin * pose;
    current = it->parent;
  }
  if (current != base_link)
    throw ConfigError(source + ": joint loop above link '" + link + "'");
  return pose;
}

std::vector<std::string> RobotDescription::movableJoints() const {
  std::vector<std::string> out;
  for (const auto& j : joints)
    if (j.type != "fixed")
      out.push_back(j.name);
  return out;
}

double RobotMagnetics::current(double thrust) const {
  return current_coefficient * std::pow(std::abs(thrust), current_exponent);
}

Eigen::Vector3d RobotMagnetics::read(const Eigen::Vector3d& external, const std::vector<double>& thrust) const {
  Eigen::Vector3d b = soft_iron * external + hard_iron;
  for (std::size_t i = 0; i < thruster_field.size() && i < thrust.size(); ++i)
    b += thruster_field[i] * current(thrust[i]);
  return b;
}

}  // namespace sim
}  // namespace unexmin

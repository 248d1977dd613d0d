// What the actuator parsers share: the joint an actuator hangs on, its id, the hull it must lie in, the id order.
#include <unexmin/sim/description_entities.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace sim {
namespace description {
namespace {

std::string xyz(const Eigen::Vector3d& v) {
  return "(" + formatNumber(v.x()) + ", " + formatNumber(v.y()) + ", " + formatNumber(v.z()) + ")";
}

}  // namespace

const JointInfo& actuatorJoint(const DescriptionReader& r, const RobotDescription& d, const char* name,
                               const std::string& where) {
  if (!name)
    r.fail(where + " has no 'joint' attribute");
  const auto it = std::find_if(d.joints.begin(), d.joints.end(), [&](const JointInfo& j) { return j.name == name; });
  if (it == d.joints.end())
    r.fail(where + ": joint '" + std::string(name) + "' does not exist");
  return *it;
}

int actuatorId(const DescriptionReader& r, const tinyxml2::XMLElement* e, const std::string& tag) {
  const double id = r.attr(e, "id", "<" + tag + ">");
  if (id < 0 || id != std::floor(id))
    r.fail("<" + tag + ">@id must be a non-negative integer");
  return static_cast<int>(id);
}

void requireInsideHull(const DescriptionReader& r, const RobotDescription& d, const Eigen::Vector3d& at,
                       const std::string& where) {
  constexpr double kSlack = 1e-6;  // [m] rounding of the expanded description
  if (d.hull_box.minCoeff() > 0.0) {
    const Eigen::Vector3d half = 0.5 * d.hull_box;
    if ((at.cwiseAbs() - half).maxCoeff() > kSlack)
      r.fail(where + ": position " + xyz(at) +
             " [m] is outside the hull's bounding box (accepted: |x| <= " + formatNumber(half.x()) +
             ", |y| <= " + formatNumber(half.y()) + ", |z| <= " + formatNumber(half.z()) + " [m])");
  } else if (d.hydro.radius > 0.0 && at.norm() > d.hydro.radius + kSlack) {
    r.fail(where + ": position " + xyz(at) +
           " [m] is outside the hull (accepted: distance from the centre <= " + formatNumber(d.hydro.radius) + " [m])");
  }
}

std::vector<std::size_t> idOrder(const DescriptionReader& r, const std::vector<int>& ids, const std::string& what) {
  std::vector<std::size_t> order(ids.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
  for (std::size_t k = 0; k < order.size(); ++k)
    if (ids[order[k]] != static_cast<int>(k))
      r.fail(what + " ids must be 0.." + formatNumber(order.size() - 1) + " without gaps or repeats");
  return order;
}

}  // namespace description
}  // namespace sim
}  // namespace unexmin

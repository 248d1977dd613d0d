// What ray-cast sensors need from the world's geometry: the first hit along each of a batch of
// rays. Implementations: BulletRayCaster (btCollisionWorld::rayTest on the dynamics world) and,
// later, a faster caster with the same interface. Knows no ROS.
#pragma once

#include <Eigen/Core>

#include <limits>
#include <vector>

namespace unexmin {
namespace sensors {

struct Ray
{
  Eigen::Vector3d origin{0, 0, 0};     ///< World frame [m].
  Eigen::Vector3d direction{0, 0, 1};  ///< World frame, unit length.
  double max_range = 1.0;              ///< Nothing beyond this is reported [m] > 0.
};

struct RayHit
{
  bool hit = false;
  double range = std::numeric_limits<double>::infinity();  ///< Distance along the ray [m]; +inf when no hit.
  Eigen::Vector3d normal{0, 0, 0};                          ///< Surface normal at the hit, world frame.
};

class RayCaster
{
public:
  virtual ~RayCaster() = default;
  /// Casts every ray; `hits` is resized to rays.size() and hits[i] answers rays[i].
  virtual void cast(const std::vector<Ray>& rays, std::vector<RayHit>& hits) const = 0;
};

}  // namespace sensors
}  // namespace unexmin

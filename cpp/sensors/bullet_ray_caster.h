// RayCaster on Bullet's collision world (btCollisionWorld::rayTest with a closest-hit callback):
// sees the static world meshes and every robot's hull except the one it is told to ignore (the
// robot carrying the sensor).
#pragma once

#include "sensors/ray_caster.h"

class btCollisionWorld;
class btCollisionObject;

namespace unexmin {
namespace sensors {

class BulletRayCaster : public RayCaster
{
public:
  /// `world` must outlive this caster; `ignore` (may be null) is never hit.
  BulletRayCaster(const btCollisionWorld& world, const btCollisionObject* ignore);

  void cast(const std::vector<Ray>& rays, std::vector<RayHit>& hits) const override;

private:
  const btCollisionWorld& world_;
  const btCollisionObject* ignore_;
};

}  // namespace sensors
}  // namespace unexmin

#include "sensors/bullet_ray_caster.h"

#include <btBulletCollisionCommon.h>

namespace unexmin {
namespace sensors {
namespace {

/// Closest hit that skips one collision object.
struct ClosestExcept : public btCollisionWorld::ClosestRayResultCallback
{
  ClosestExcept(const btVector3& from, const btVector3& to, const btCollisionObject* ignore)
      : ClosestRayResultCallback(from, to), ignore_(ignore)
  {
  }
  bool needsCollision(btBroadphaseProxy* proxy) const override
  {
    if (ignore_ && proxy->m_clientObject == ignore_) return false;
    return ClosestRayResultCallback::needsCollision(proxy);
  }
  const btCollisionObject* ignore_;
};

}  // namespace

BulletRayCaster::BulletRayCaster(const btCollisionWorld& world, const btCollisionObject* ignore)
    : world_(world), ignore_(ignore)
{
}

void BulletRayCaster::cast(const std::vector<Ray>& rays, std::vector<RayHit>& hits) const
{
  hits.assign(rays.size(), RayHit());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Ray& r = rays[i];
    const Eigen::Vector3d end = r.origin + r.max_range * r.direction;
    const btVector3 from(r.origin.x(), r.origin.y(), r.origin.z());
    const btVector3 to(end.x(), end.y(), end.z());
    ClosestExcept cb(from, to, ignore_);
    world_.rayTest(from, to, cb);
    if (!cb.hasHit()) continue;
    RayHit& h = hits[i];
    h.hit = true;
    h.range = static_cast<double>(cb.m_closestHitFraction) * r.max_range;
    h.normal = Eigen::Vector3d(cb.m_hitNormalWorld.x(), cb.m_hitNormalWorld.y(), cb.m_hitNormalWorld.z());
  }
}

}  // namespace sensors
}  // namespace unexmin

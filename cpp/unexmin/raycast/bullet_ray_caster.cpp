#include <unexmin/raycast/bullet_ray_caster.h>

#include <unexmin/sim/collision_shape.h>
#include <unexmin/sim/world.h>

#include <BulletCollision/NarrowPhaseCollision/btRaycastCallback.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>

namespace unexmin {
namespace raycast {
namespace {

/// Barycentric coordinates (u, v) of point p in triangle `tri` of `mesh` (p = (1 - u - v) p0 + u p1 + v p2).
void barycentric(const sim::TriangleMesh& mesh, int tri, const Eigen::Vector3f& p, float& u, float& v) {
  const Eigen::Vector3f a = mesh.vertices[mesh.indices[3 * tri]], b = mesh.vertices[mesh.indices[3 * tri + 1]],
                        c = mesh.vertices[mesh.indices[3 * tri + 2]];
  const Eigen::Vector3f e1 = b - a, e2 = c - a, d = p - a;
  const float d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2), d1 = d.dot(e1), d2 = d.dot(e2);
  const float den = d11 * d22 - d12 * d12;
  u = den > 0.0f ? (d22 * d1 - d12 * d2) / den : 0.0f;
  v = den > 0.0f ? (d11 * d2 - d12 * d1) / den : 0.0f;
}

/// Bullet's closest-hit callback that also keeps the triangle hit.
struct ClosestTriangle : btCollisionWorld::ClosestRayResultCallback {
  using ClosestRayResultCallback::ClosestRayResultCallback;
  btScalar addSingleResult(btCollisionWorld::LocalRayResult& result, bool normal_in_world) override {
    const btScalar f = ClosestRayResultCallback::addSingleResult(result, normal_in_world);
    const btCollisionWorld::LocalShapeInfo* info = result.m_localShapeInfo;
    triangle = info ? sim::meshTriangle(info->m_shapePart, info->m_triangleIndex) : -1;
    return f;
  }
  int triangle = -1;
};

}  // namespace

struct BulletRayCaster::OwnBody {
  std::unique_ptr<sim::MeshCollisionShape> shape;
  btCollisionObject object;
};

BulletRayCaster::BulletRayCaster(std::vector<BulletTarget> targets, const RayCasterOptions& options)
    : RayCaster(options) {
  add(targets);
  update();
}

BulletRayCaster::BulletRayCaster(sim::World& world, const RayCasterOptions& options) : RayCaster(options) {
  std::vector<BulletTarget> targets;
  for (const SeenMesh& s : seenMeshes(world)) {
    BulletTarget t;
    t.kind = HitKind::mesh;
    t.seen_by = s.seen_by;
    t.index = s.sonar_index;
    t.camera_index = s.camera_index;
    t.mesh = s.mesh;
    for (std::size_t i = 0; i < world.meshCount() && !t.object; ++i)
      if (&world.mesh(i) == s.mesh)
        t.object = world.meshBody(i);
    if (!t.object) {  // physics does not hold it: a static object of our own on the same triangles
      auto own = std::make_unique<OwnBody>();
      own->shape = std::make_unique<sim::MeshCollisionShape>(*s.mesh);
      own->object.setCollisionShape(&own->shape->shape());
      t.object = &own->object;
      own_.push_back(std::move(own));
    }
    targets.push_back(t);
  }
  for (std::size_t i = 0; i < world.robotCount(); ++i)
    targets.push_back(BulletTarget{world.robot(i).body(), HitKind::robot, static_cast<int>(i)});
  add(targets);
  update();
}

void BulletRayCaster::add(const std::vector<BulletTarget>& targets) {
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const BulletTarget& t = targets[i];
    if (!t.object)
      throw RayCasterError("bullet ray caster: target " + formatNumber(i) + " has no collision object");
    if (t.kind != HitKind::mesh && t.kind != HitKind::robot)
      throw RayCasterError("bullet ray caster: target " + formatNumber(i) + " must be a mesh or a robot");
    const btCollisionShape* shape = t.object->getCollisionShape();
    const double radius =
        shape->getShapeType() == SPHERE_SHAPE_PROXYTYPE ? static_cast<const btSphereShape*>(shape)->getRadius() : 0.0;
    targets_.push_back(Target{t, btTransform::getIdentity(), btVector3(0, 0, 0), btVector3(0, 0, 0), radius});
  }
}

BulletRayCaster::~BulletRayCaster() = default;

void BulletRayCaster::update() {
  for (Target& t : targets_) {
    t.transform = t.target.object->getWorldTransform();
    t.target.object->getCollisionShape()->getAabb(t.transform, t.aabb_min, t.aabb_max);
  }
}

void BulletRayCaster::castBlock(const Ray* rays, Hit* hits, std::size_t n, int exclude_robot, SeenBy seen_by) const {
  const unsigned who = static_cast<unsigned>(seen_by);
  // btCollisionWorld::rayTest is this loop behind a broadphase whose ray traversal stack is shared (Debian
  // builds Bullet without BT_THREADSAFE), so we cull by AABB ourselves and call Bullet's per-object ray test,
  // which only reads shared state.
  for (std::size_t i = 0; i < n; ++i) {
    const Ray& ray = rays[i];
    const Eigen::Vector3f d = ray.direction.normalized();
    const Eigen::Vector3f end = ray.origin + ray.max_range * d;
    const btVector3 from(ray.origin.x(), ray.origin.y(), ray.origin.z());
    const btVector3 to(end.x(), end.y(), end.z());
    const btTransform from_tf(btQuaternion::getIdentity(), from);
    const btTransform to_tf(btQuaternion::getIdentity(), to);
    ClosestTriangle callback(from, to);
    // For convex shapes other than spheres: GJK (converges to 1 mm) rather than the default sub-simplex cast.
    callback.m_flags |= btTriangleRaycastCallback::kF_UseGjkConvexCastRaytest;
    const Target* nearest = nullptr;
    const Target* sphere = nullptr;
    int triangle = -1;
    double t_sphere = ray.max_range;
    for (const Target& t : targets_) {
      if ((t.target.kind == HitKind::robot && t.target.index == exclude_robot) || !(t.target.seen_by & who))
        continue;
      if (t.sphere_radius > 0.0) {
        const btVector3& c = t.transform.getOrigin();
        double ts;
        if (raySphere(ray.origin.cast<double>(), d.cast<double>(), Eigen::Vector3d(c.x(), c.y(), c.z()),
                      t.sphere_radius, ts) &&
            ts <= t_sphere) {
          t_sphere = ts;
          sphere = &t;
        }
        continue;
      }
      btScalar entry = callback.m_closestHitFraction;
      btVector3 box_normal;
      if (!btRayAabb(from, to, t.aabb_min, t.aabb_max, entry, box_normal))
        continue;
      const btScalar before = callback.m_closestHitFraction;
      btCollisionWorld::rayTestSingle(from_tf, to_tf, const_cast<btCollisionObject*>(t.target.object),
                                      t.target.object->getCollisionShape(), t.transform, callback);
      if (callback.m_closestHitFraction < before) {
        nearest = &t;
        triangle = callback.triangle;
      }
    }
    const float range = callback.m_closestHitFraction * ray.max_range;
    if (nearest && (!sphere || range <= t_sphere)) {
      const btVector3& nw = callback.m_hitNormalWorld;
      const BulletTarget& t = nearest->target;
      const int index = seen_by == SeenBy::cameras && t.camera_index >= 0 ? t.camera_index : t.index;
      float u = 0.0f, v = 0.0f;
      if (t.mesh && triangle >= 0 && static_cast<std::size_t>(triangle) < t.mesh->triangleCount())
        barycentric(*t.mesh, triangle, ray.origin + range * d, u, v);
      else
        triangle = -1;
      finishHit(ray, Eigen::Vector3f(nw.x(), nw.y(), nw.z()), range, t.kind, index, hits[i], triangle, u, v);
    } else if (sphere) {
      const btVector3& c = sphere->transform.getOrigin();
      const Eigen::Vector3d p = ray.origin.cast<double>() + t_sphere * d.cast<double>();
      finishHit(ray, (p - Eigen::Vector3d(c.x(), c.y(), c.z())).cast<float>(), static_cast<float>(t_sphere),
                sphere->target.kind, sphere->target.index, hits[i]);
    } else {
      hits[i] = Hit();
    }
  }
}

}  // namespace raycast
}  // namespace unexmin

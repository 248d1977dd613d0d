#include <unexmin/raycast/bullet_ray_caster.h>

#include <unexmin/sim/world.h>

#include <BulletCollision/NarrowPhaseCollision/btRaycastCallback.h>
#include <btBulletDynamicsCommon.h>

namespace unexmin {
namespace raycast {
namespace {

/// Start of the vertex array of a triangle-mesh shape (to recognise the world mesh it was built on), or null.
const void* vertexBase(const btCollisionShape* shape) {
  if (shape->getShapeType() != TRIANGLE_MESH_SHAPE_PROXYTYPE)
    return nullptr;
  const btStridingMeshInterface* mesh = static_cast<const btBvhTriangleMeshShape*>(shape)->getMeshInterface();
  if (!mesh || mesh->getNumSubParts() < 1)
    return nullptr;
  const unsigned char* vertices = nullptr;
  const unsigned char* indices = nullptr;
  int num_vertices = 0, vertex_stride = 0, index_stride = 0, num_faces = 0;
  PHY_ScalarType vertex_type, index_type;
  mesh->getLockedReadOnlyVertexIndexBase(&vertices, num_vertices, vertex_type, vertex_stride, &indices, index_stride,
                                         num_faces, index_type, 0);
  mesh->unLockReadOnlyVertexBase(0);
  return vertices;
}

std::vector<BulletTarget> worldTargets(sim::World& world) {
  std::vector<BulletTarget> targets;
  const btCollisionObjectArray& objects = world.physics().getCollisionObjectArray();
  for (int k = 0; k < objects.size(); ++k) {
    const btCollisionObject* object = objects[k];
    BulletTarget t;
    t.object = object;
    for (std::size_t i = 0; i < world.robotCount() && t.index < 0; ++i)
      if (world.robot(i).body() == object) {
        t.kind = HitKind::robot;
        t.index = static_cast<int>(i);
      }
    if (const void* base = t.index < 0 ? vertexBase(object->getCollisionShape()) : nullptr)
      for (std::size_t m = 0; m < world.meshes().size() && t.index < 0; ++m)
        if (static_cast<const void*>(world.meshes()[m].vertices.data()) == base) {
          t.kind = HitKind::mesh;
          t.index = static_cast<int>(m);
        }
    if (t.index >= 0)
      targets.push_back(t);
  }
  return targets;
}

}  // namespace

BulletRayCaster::BulletRayCaster(std::vector<BulletTarget> targets, const RayCasterOptions& options)
    : RayCaster(options) {
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
  update();
}

BulletRayCaster::BulletRayCaster(sim::World& world, const RayCasterOptions& options)
    : BulletRayCaster(worldTargets(world), options) {}

BulletRayCaster::~BulletRayCaster() = default;

void BulletRayCaster::update() {
  for (Target& t : targets_) {
    t.transform = t.target.object->getWorldTransform();
    t.target.object->getCollisionShape()->getAabb(t.transform, t.aabb_min, t.aabb_max);
  }
}

void BulletRayCaster::castBlock(const Ray* rays, Hit* hits, std::size_t n, int exclude_robot) const {
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
    btCollisionWorld::ClosestRayResultCallback callback(from, to);
    // For convex shapes other than spheres: GJK (converges to 1 mm) rather than the default sub-simplex cast.
    callback.m_flags |= btTriangleRaycastCallback::kF_UseGjkConvexCastRaytest;
    const Target* nearest = nullptr;
    const Target* sphere = nullptr;
    double t_sphere = ray.max_range;
    for (const Target& t : targets_) {
      if (t.target.kind == HitKind::robot && t.target.index == exclude_robot)
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
      if (callback.m_closestHitFraction < before)
        nearest = &t;
    }
    const float range = callback.m_closestHitFraction * ray.max_range;
    if (nearest && (!sphere || range <= t_sphere)) {
      const btVector3& nw = callback.m_hitNormalWorld;
      finishHit(ray, Eigen::Vector3f(nw.x(), nw.y(), nw.z()), range, nearest->target.kind, nearest->target.index,
                hits[i]);
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

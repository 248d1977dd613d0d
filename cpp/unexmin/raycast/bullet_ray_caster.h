// Ray caster on Bullet's own ray test against the physics world's collision objects: the fallback
// back end ("bullet"), about ten times slower than Embree on large meshes. Sphere shapes (the robots) are
// cast exactly: Bullet's convex ray test is iterative and only good to about a millimetre.
#pragma once

#include <unexmin/raycast/ray_caster.h>

#include <LinearMath/btTransform.h>

#include <memory>

class btCollisionObject;

namespace unexmin {
namespace raycast {

/// A collision object rays can hit and what a hit on it reports.
struct BulletTarget {
  const btCollisionObject* object = nullptr;
  HitKind kind = HitKind::mesh;  ///< mesh or robot
  int index = -1;                ///< Hit::index of a hit on it (cast for the sonars)
  unsigned seen_by = 3;          ///< SeenBy bits of the sensors that see it (1 sonars, 2 cameras)
  int camera_index = -1;         ///< Hit::index of a hit cast for the cameras; -1: `index`
  /// The triangles of the shape, for the barycentric coordinates of a hit (Hit::u, v); null: none computed.
  const sim::TriangleMesh* mesh = nullptr;
};

class BulletRayCaster : public RayCaster {
public:
  /// Casts against `targets` with their shapes and world transforms as of update(). The objects must
  /// outlive the caster. Throws RayCasterError on a null object or a kind that is not mesh or robot.
  explicit BulletRayCaster(std::vector<BulletTarget> targets, const RayCasterOptions& options = RayCasterOptions());
  /// The world's meshes as seenMeshes(world) gives them (a collision mesh through its physics body, another
  /// through a shape of the caster's own) and its robots; other objects of world.physics() are not seen. The world
  /// must outlive the caster.
  explicit BulletRayCaster(sim::World& world, const RayCasterOptions& options = RayCasterOptions());
  ~BulletRayCaster() override;

  const char* name() const override { return "bullet"; }
  void update() override;

  /// Targets found, in the physics world's order.
  std::size_t targetCount() const { return targets_.size(); }

protected:
  void castBlock(const Ray* rays, Hit* hits, std::size_t n, int exclude_robot, SeenBy seen_by) const override;

private:
  void add(const std::vector<BulletTarget>& targets);

  struct Target {
    BulletTarget target;
    btTransform transform;  // world transform as of update()
    btVector3 aabb_min, aabb_max;
    double sphere_radius;  // > 0: a sphere, cast exactly rather than by Bullet's iterative convex cast
  };
  std::vector<Target> targets_;
  struct OwnBody;                              ///< a shape and object for a mesh physics does not hold
  std::vector<std::unique_ptr<OwnBody>> own_;  ///< built before targets_ points at them
};

}  // namespace raycast
}  // namespace unexmin

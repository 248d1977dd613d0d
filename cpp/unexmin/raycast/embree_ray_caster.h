// Ray caster on Intel Embree 3: the static meshes in one BVH scene (robust, watertight by default), the
// robots as analytic spheres. The default back end ("embree").
#pragma once

#include <unexmin/raycast/ray_caster.h>
#include <unexmin/sim/mesh.h>

#include <embree3/rtcore.h>

#include <array>

namespace unexmin {
namespace raycast {

class EmbreeRayCaster : public RayCaster {
public:
  /// Casts against `meshes` (world frame; Hit::index of a mesh hit is its position in this list, nullptr
  /// entries are skipped, e.g. visual-only meshes) and the spheres `robots` fills on update() (may be empty:
  /// no robots). The triangles are copied: the meshes need not outlive the caster. Throws RayCasterError on a
  /// mesh index out of range or an Embree error.
  EmbreeRayCaster(const std::vector<const sim::TriangleMesh*>& meshes, RobotSphereSource robots,
                  const RayCasterOptions& options = RayCasterOptions());
  /// Casts against `meshes`, each seen by the sensors of its SeenMesh::seen_by and reporting its index for them,
  /// and the spheres `robots` fills on update(). Throws RayCasterError as above, and when a mesh is seen by some
  /// sensors only and this Embree library has no ray masks.
  EmbreeRayCaster(const std::vector<SeenMesh>& meshes, RobotSphereSource robots,
                  const RayCasterOptions& options = RayCasterOptions());
  /// The world's meshes, as seenMeshes(world) gives them, and its robots; the world must outlive the caster. The
  /// meshes' vertex and index arrays are used in place, not copied, when they have the spare vertex loadMesh()
  /// leaves (TriangleMesh::vertices).
  explicit EmbreeRayCaster(sim::World& world, const RayCasterOptions& options = RayCasterOptions());
  ~EmbreeRayCaster() override;

  const char* name() const override { return "embree"; }
  void update() override;

  /// The committed Embree scene (geometry ID = position in the meshes given; for a world: in seenMeshes(world)), for
  /// benchmarks and tools that call Embree directly.
  RTCScene scene() const { return scene_; }
  /// Robot spheres as of the last update().
  const std::vector<RobotSphere>& robots() const { return robots_; }

  /// A block counts as coherent (Embree's coherent stream mode) when every ray starts within this distance
  /// [m] of the block's first ray and points within kCoherentCos (cosine) of its direction: sensor fans.
  static constexpr float kCoherentOrigin = 0.5f;
  static constexpr float kCoherentCos = 0.7071f;  // 45 deg

protected:
  void castBlock(const Ray* rays, Hit* hits, std::size_t n, int exclude_robot, SeenBy seen_by) const override;

private:
  /// in_place: use the meshes' arrays where TriangleMesh::vertices has its spare slot, else copy them.
  void build(const std::vector<SeenMesh>& meshes, bool watertight, bool in_place);
  void check(const char* what) const;

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  RobotSphereSource source_;
  std::vector<RobotSphere> robots_;
  std::vector<std::array<int, 2>> index_;  ///< per geometry ID: Hit::index for the sonars, for the cameras
};

}  // namespace raycast
}  // namespace unexmin

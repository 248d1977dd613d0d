// Bullet's collision shape of a static triangle mesh, its BVH built once per mesh and kept in a cache file next to
// the mesh file (docs/worlds.md, "Large meshes").
#pragma once

#include <unexmin/sim/mesh.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

class btTriangleIndexVertexArray;
class btBvhTriangleMeshShape;
class btOptimizedBvh;

namespace unexmin {
namespace sim {

/// Meshes of at least this many triangles keep their BVH in a cache file (bvhCacheFile()); smaller ones build it in
/// well under a second.
constexpr std::size_t kBvhCacheMinTriangles = 1000000;

/// Triangles per part of a mesh as Bullet sees it. Bullet's quantised BVH keeps a triangle's part in the upper 10 bits
/// and its number within the part in the lower 21 of one int (btQuantizedBvh.h, MAX_NUM_PARTS_IN_BITS): a mesh of
/// more triangles is handed over in parts of this many, so that the leaf of triangle t names part t / 2^21 and
/// triangle t % 2^21 of it, which is t itself (the BVH is the one of a single part, byte for byte).
constexpr std::size_t kBulletPartTriangles = std::size_t(1) << 21;

/// The mesh's triangle number of triangle `index` of part `part` as Bullet reports a hit (LocalShapeInfo).
inline int meshTriangle(int part, int index) {
  return part * static_cast<int>(kBulletPartTriangles) + index;
}

/// The cache file of Bullet's BVH of mesh entry `entry` loaded as `mesh`: "<entry.file>.bvh" when the mesh has at
/// least kBvhCacheMinTriangles triangles, else "" (no cache).
std::string bvhCacheFile(const MeshEntry& entry, const TriangleMesh& mesh);

/// A static mesh as Bullet sees it: a btBvhTriangleMeshShape over the mesh's own vertex and index arrays (not copied;
/// the mesh must outlive the shape), in parts of kBulletPartTriangles triangles, its BVH quantised (Bullet's
/// compressed AABBs). A hit reports its triangle as (part, index): meshTriangle() gives the mesh's number.
class MeshCollisionShape {
public:
  /// Builds the BVH, or reads it from `cache_file` when that file holds the BVH of exactly these triangles: the same
  /// Bullet version, vertex and triangle counts and 64-bit hash of the vertices (world frame) and indices, and its
  /// contents intact (their own 64-bit hash). Any other file there (another mesh, a cut or damaged file, another
  /// Bullet) is ignored, the BVH built and the file replaced (written to a temporary file, then renamed: a reader never
  /// sees half a file). A folder that cannot be written keeps no cache; the shape is the same. `cache_file` empty: no
  /// cache. A BVH read from the cache is byte for byte the one built: contacts and ray casts are the same.
  explicit MeshCollisionShape(const TriangleMesh& mesh, const std::string& cache_file = "");
  ~MeshCollisionShape();
  MeshCollisionShape(const MeshCollisionShape&) = delete;
  MeshCollisionShape& operator=(const MeshCollisionShape&) = delete;

  btBvhTriangleMeshShape& shape() { return *shape_; }
  const btBvhTriangleMeshShape& shape() const { return *shape_; }
  /// Whether the BVH was read from the cache file (false: built here).
  bool fromCache() const { return from_cache_; }

private:
  /// Points in_place_ at the BVH of `cache_file` when it is that of `mesh` (hash `mesh_hash`); false otherwise.
  bool readCache(const std::string& cache_file, const TriangleMesh& mesh, std::uint64_t mesh_hash);
  /// Writes built_ to `cache_file` and uses its serialised copy from then on (one BVH in memory).
  void writeCache(const std::string& cache_file, const TriangleMesh& mesh, std::uint64_t mesh_hash);

  std::unique_ptr<btTriangleIndexVertexArray> array_;
  std::unique_ptr<btBvhTriangleMeshShape> shape_;
  std::unique_ptr<btOptimizedBvh> built_;  ///< the BVH built here, when the shape uses it
  /// The serialised BVH the shape uses (Bullet's in-place serialisation, 16-byte aligned), else null.
  void* buffer_ = nullptr;
  btOptimizedBvh* in_place_ = nullptr;
  bool from_cache_ = false;
};

}  // namespace sim
}  // namespace unexmin

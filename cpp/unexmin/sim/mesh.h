// Triangle meshes of the world (collision and ray casting): binary PLY read directly, every other format with assimp
// (STL, OBJ, DAE, ...).
#pragma once

#include <unexmin/sim/world_config.h>

#include <Eigen/Core>

#include <vector>

namespace unexmin {
namespace sim {

struct TriangleMesh {
  std::string name;
  /// World frame [m], scale and pose applied. loadMesh() leaves room for one more vertex (capacity > size), so that
  /// Embree's 16-byte loads of the last one stay inside the array and the ray caster uses it in place.
  std::vector<Eigen::Vector3f> vertices;
  std::vector<int> indices;  ///< Three per triangle.
  /// Texture coordinates (u, v) per vertex, the file's first set (empty: the file has none) [-].
  std::vector<Eigen::Vector2f> uvs;
  /// Colour per vertex, the file's first set, in linear light [0, 1] (the file's codes read as sRGB; empty: none) [-].
  std::vector<Eigen::Vector3f> colours;
  std::size_t triangleCount() const { return indices.size() / 3; }
};

/// Loads every triangle of the file at `entry.file`, applies its scale and pose; keeps its texture coordinates and
/// vertex colours when every part of the file has them. A binary PLY of triangles is read directly (readBinaryPly in
/// sim/ply_reader.h), any other file with loadMeshWithAssimp(): the same triangles, in the same order.
/// Throws ConfigError("<file>: ...") when it cannot be read or holds no triangle.
TriangleMesh loadMesh(const MeshEntry& entry);

/// loadMesh() through assimp alone, whatever the format: vertices welded where identical (position and attributes).
TriangleMesh loadMeshWithAssimp(const MeshEntry& entry);

}  // namespace sim
}  // namespace unexmin

// Triangle meshes of the world (collision and ray casting), loaded with assimp (STL, OBJ, DAE, ...).
#pragma once

#include <unexmin/sim/world_config.h>

#include <Eigen/Core>

#include <vector>

namespace unexmin {
namespace sim {

struct TriangleMesh {
  std::string name;
  std::vector<Eigen::Vector3f> vertices;  ///< World frame [m], scale and pose applied.
  std::vector<int> indices;               ///< Three per triangle.
  /// Texture coordinates (u, v) per vertex, the file's first set (empty: the file has none) [-].
  std::vector<Eigen::Vector2f> uvs;
  /// Colour per vertex, the file's first set, in linear light [0, 1] (the file's codes read as sRGB; empty: none) [-].
  std::vector<Eigen::Vector3f> colours;
  std::size_t triangleCount() const { return indices.size() / 3; }
};

/// Loads every triangle of the file at `entry.file`, applies its scale and pose; keeps its texture coordinates and
/// vertex colours when every part of the file has them.
/// Throws ConfigError("<file>: ...") when it cannot be read or holds no triangle.
TriangleMesh loadMesh(const MeshEntry& entry);

}  // namespace sim
}  // namespace unexmin

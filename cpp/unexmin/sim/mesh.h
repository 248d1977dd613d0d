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
  std::size_t triangleCount() const { return indices.size() / 3; }
};

/// Loads every triangle of the file at `entry.file`, applies its scale and pose.
/// Throws ConfigError("<file>: ...") when it cannot be read or holds no triangle.
TriangleMesh loadMesh(const MeshEntry& entry);

}  // namespace sim
}  // namespace unexmin

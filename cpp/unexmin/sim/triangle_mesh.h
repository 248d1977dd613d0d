// A triangle mesh of the world in memory, as the mesh readers fill it (sim/mesh.h, sim/ply_reader.h) and physics
// and the ray casters use it. Knows no ROS.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <string>
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

}  // namespace sim
}  // namespace unexmin

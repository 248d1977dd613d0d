// Triangle meshes of the world (collision and ray casting): binary PLY read directly, every other format with assimp
// (STL, OBJ, DAE, ...).
#pragma once

#include <unexmin/sim/triangle_mesh.h>
#include <unexmin/sim/world_config.h>

namespace unexmin {
namespace sim {

/// Loads every triangle of the file at `entry.file`, applies its scale and pose; keeps its texture coordinates and
/// vertex colours when every part of the file has them. A binary PLY of triangles is read directly (readBinaryPly in
/// sim/ply_reader.h), any other file with loadMeshWithAssimp(): the same triangles, in the same order.
/// Throws ConfigError("<file>: ...") when it cannot be read or holds no triangle.
TriangleMesh loadMesh(const MeshEntry& entry);

/// loadMesh() through assimp alone, whatever the format: vertices welded where identical (position and attributes).
TriangleMesh loadMeshWithAssimp(const MeshEntry& entry);

}  // namespace sim
}  // namespace unexmin

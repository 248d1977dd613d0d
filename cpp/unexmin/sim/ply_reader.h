// A direct reader of the binary PLY meshes the project writes (world_from_scan, the mine generator): a world of ten
// million triangles reads in a fraction of assimp's time and memory (docs/worlds.md, "Mesh files").
#pragma once

#include <unexmin/sim/triangle_mesh.h>
#include <unexmin/sim/world_config.h>

namespace unexmin {
namespace sim {

/// Reads `entry.file` when it is a binary little-endian PLY of triangles: vertex properties x, y, z (float or double)
/// with optional nx, ny, nz (skipped) and uchar red, green, blue (read as loadMesh documents colours; alpha skipped),
/// and a face element whose one property is a list of three int or uint indices. Fills `out` with the file's vertices
/// (scale and pose of the entry applied) and triangles, both in the file's order: the triangles assimp gives, corner
/// for corner (assimp also welds identical vertices, which changes the vertex numbers only). Returns false, `out`
/// left empty, for any other file (ASCII or big-endian PLY, texture coordinates, other properties or elements, a
/// polygon that is not a triangle, a file that cannot be opened or is no PLY): loadMesh then reads it with assimp.
/// Throws ConfigError("<file>: ...") when the file is cut short, its header declares more vertices or faces than the
/// bytes after it hold (or more than int indices number: 2^31 - 1 vertices, (2^31 - 1) / 3 faces), or a face names a
/// vertex the file has not; nothing is allocated for a count the file cannot hold.
bool readBinaryPly(const MeshEntry& entry, TriangleMesh& out);

}  // namespace sim
}  // namespace unexmin

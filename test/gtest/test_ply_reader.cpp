// The direct binary PLY reader (cpp/unexmin/sim/ply_reader.h) against assimp's reading of the same files, written
// here: the same triangles corner for corner, bit for bit (positions with scale and pose, vertex colours), vertices
// welded by assimp or not; the files it leaves to assimp (ASCII, a quad, texture coordinates) still load through
// loadMesh; a cut file and a face naming a missing vertex are errors naming the file; the generated mine's collision
// mesh reads as assimp reads it.
#include <unexmin/core/error.h>
#include <unexmin/sim/mesh.h>
#include <unexmin/sim/ply_reader.h>
#include "expect_error.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace unexmin {
namespace test {
namespace {

/// Appends the bytes of `x` (little-endian on this machine, as the files are).
template <typename T>
void put(std::string& out, T x) {
  char b[sizeof(T)];
  std::memcpy(b, &x, sizeof(T));
  out.append(b, sizeof(T));
}

std::string writeFile(const std::string& name, const std::string& content) {
  const std::string path = testTempDir() + name;
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

sim::MeshEntry entry(const std::string& file) {
  sim::MeshEntry e;
  e.name = "m";
  e.file = file;
  return e;
}

/// A tetrahedron with one corner written twice (vertices 0 and 4 at the same place and colour, which assimp welds):
/// float x y z, uchar red green blue, faces as uchar count and int indices.
std::string tetrahedron(bool colours) {
  const float v[5][3] = {{0, 0, 0}, {1.5f, 0, 0}, {0, 2.25f, 0}, {0, 0, 3.125f}, {0, 0, 0}};
  const unsigned char c[5][3] = {{10, 20, 30}, {200, 100, 0}, {255, 255, 255}, {0, 0, 0}, {10, 20, 30}};
  const int f[4][3] = {{0, 2, 1}, {4, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  std::string s = "ply\nformat binary_little_endian 1.0\ncomment a test\nelement vertex 5\n";
  s += "property float x\nproperty float y\nproperty float z\n";
  if (colours)
    s += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  s += "element face 4\nproperty list uchar int vertex_indices\nend_header\n";
  for (int i = 0; i < 5; ++i) {
    for (float x : v[i])
      put(s, x);
    if (colours)
      s.append(reinterpret_cast<const char*>(c[i]), 3);
  }
  for (const auto& t : f) {
    put(s, static_cast<unsigned char>(3));
    for (int i : t)
      put(s, i);
  }
  return s;
}

/// Both meshes have the same triangles in the same order, corner for corner, bit for bit (and the same colours).
void expectSameCorners(const sim::TriangleMesh& a, const sim::TriangleMesh& b) {
  ASSERT_EQ(a.triangleCount(), b.triangleCount());
  ASSERT_EQ(a.colours.empty(), b.colours.empty());
  EXPECT_EQ(a.uvs.empty(), b.uvs.empty());
  for (std::size_t k = 0; k < a.indices.size(); ++k) {
    const int i = a.indices[k], j = b.indices[k];
    ASSERT_TRUE(a.vertices[i] == b.vertices[j]) << "corner " << k;
    if (!a.colours.empty())
      ASSERT_TRUE(a.colours[i] == b.colours[j]) << "corner " << k;
  }
}

TEST(PlyReader, ReadsTheTrianglesAndColoursAssimpReadsWithScaleAndPose) {
  for (bool colours : {false, true}) {
    sim::MeshEntry e = entry(writeFile("ply_tetra.ply", tetrahedron(colours)));
    e.scale = Eigen::Vector3d(2.0, 0.5, -1.0);
    e.pose = sim::poseFromXyzRpy(Eigen::Vector3d(1.0, -2.0, 3.0), Eigen::Vector3d(0.3, -0.2, 1.1));
    sim::TriangleMesh direct;
    ASSERT_TRUE(sim::readBinaryPly(e, direct));
    EXPECT_EQ(direct.name, "m");
    EXPECT_EQ(direct.vertices.size(), 5u) << "the file's vertices, none welded";
    EXPECT_EQ(direct.indices, (std::vector<int>{0, 2, 1, 4, 1, 3, 1, 2, 3, 2, 0, 3}));
    const sim::TriangleMesh assimp = sim::loadMeshWithAssimp(e);
    EXPECT_EQ(assimp.vertices.size(), 4u) << "assimp welds the corner written twice";
    expectSameCorners(direct, assimp);
    // The far corner (0, 0, 3.125) from the documented order: scale, then rotation, then translation.
    const Eigen::Vector3d far = e.pose * Eigen::Vector3d(0.0, 0.0, -3.125);
    EXPECT_LT((direct.vertices[3].cast<double>() - far).norm(), 1e-5);
    if (colours) {
      ASSERT_EQ(direct.colours.size(), 5u);
      EXPECT_FLOAT_EQ(direct.colours[2].x(), 1.0f);  // code 255: linear 1
      EXPECT_FLOAT_EQ(direct.colours[3].x(), 0.0f);
      EXPECT_NEAR(direct.colours[1].x(), std::pow((200.0 / 255.0 + 0.055) / 1.055, 2.4), 1e-6);  // the sRGB curve
    }
    // loadMesh takes this reader, and leaves room for one more vertex (TriangleMesh::vertices).
    const sim::TriangleMesh loaded = sim::loadMesh(e);
    expectSameCorners(loaded, direct);
    EXPECT_GT(loaded.vertices.capacity(), loaded.vertices.size());
  }
}

TEST(PlyReader, ReadsDoublesUintIndicesAndSkipsNormals) {
  std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n";
  s += "property double z\nproperty float nx\nproperty float ny\nproperty float nz\n";
  s += "element face 1\nproperty list int uint vertex_index\nend_header\n";
  const double v[3][3] = {{0.1, 0.2, 0.3}, {1.1, 0.2, 0.3}, {0.1, 1.2, 0.3}};
  for (const auto& p : v) {
    for (double x : p)
      put(s, x);
    for (int k = 0; k < 3; ++k)
      put(s, 0.5f);
  }
  put(s, 3);
  for (std::uint32_t i : {0u, 1u, 2u})
    put(s, i);
  const sim::MeshEntry e = entry(writeFile("ply_doubles.ply", s));
  sim::TriangleMesh direct;
  ASSERT_TRUE(sim::readBinaryPly(e, direct));
  EXPECT_TRUE(direct.vertices[1] == Eigen::Vector3f(1.1f, 0.2f, 0.3f));
  expectSameCorners(direct, sim::loadMeshWithAssimp(e));
}

TEST(PlyReader, LeavesOtherFilesToAssimpWhichLoadMeshStillReads) {
  // ASCII; a quad (two triangles once triangulated); texture coordinates.
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  std::string quad =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const float q[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (const auto& p : q)
    for (float x : p)
      put(quad, x);
  put(quad, static_cast<unsigned char>(4));
  for (int i : {0, 1, 2, 3})
    put(quad, i);
  std::string uv =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float s\nproperty float t\nelement face 1\nproperty list uchar int "
      "vertex_indices\nend_header\n";
  for (int i = 0; i < 3; ++i)
    for (float x : {static_cast<float>(i == 1), static_cast<float>(i == 2), 0.0f, 0.25f * i, 0.5f})
      put(uv, x);
  put(uv, static_cast<unsigned char>(3));
  for (int i : {0, 1, 2})
    put(uv, i);
  const struct {
    const char* name;
    std::string content;
    std::size_t triangles;
    bool uvs;
  } cases[] = {{"ply_ascii.ply", ascii, 1, false}, {"ply_quad.ply", quad, 2, false}, {"ply_uv.ply", uv, 1, true}};
  for (const auto& c : cases) {
    const sim::MeshEntry e = entry(writeFile(c.name, c.content));
    sim::TriangleMesh direct;
    EXPECT_FALSE(sim::readBinaryPly(e, direct)) << c.name;
    EXPECT_TRUE(direct.indices.empty()) << c.name;
    const sim::TriangleMesh loaded = sim::loadMesh(e);
    EXPECT_EQ(loaded.triangleCount(), c.triangles) << c.name;
    EXPECT_EQ(loaded.uvs.empty(), !c.uvs) << c.name;
  }
}

TEST(PlyReader, ACutFileOrAMissingVertexIsAnErrorNamingTheFile) {
  const std::string whole = tetrahedron(false);
  const std::string cut = writeFile("ply_cut.ply", whole.substr(0, whole.size() - 5));
  const std::string short_message = thrownMessage<ConfigError>([&] { sim::loadMesh(entry(cut)); });
  EXPECT_TRUE(contains(short_message, cut + ": the PLY file ends before its last face")) << short_message;
  std::string bad = whole;
  const int missing = 7;
  std::memcpy(&bad[bad.size() - 4], &missing, 4);  // the last face's last index
  const std::string path = writeFile("ply_bad_index.ply", bad);
  const std::string index_message = thrownMessage<ConfigError>([&] { sim::loadMesh(entry(path)); });
  EXPECT_TRUE(contains(index_message, path + ": face 3 names vertex 7, expected [0, 5)")) << index_message;
}

TEST(PlyReader, AHeaderDeclaringMoreThanTheFileHoldsIsAnErrorNamingTheFileBeforeAnyAllocation) {
  // 2^50 vertices (12 PiB of floats): reserving them would throw std::bad_alloc, not an error naming the file.
  const std::string head = "ply\nformat binary_little_endian 1.0\nelement vertex ";
  const std::string tail =
      "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  const std::string huge = writeFile("ply_huge.ply", head + "1125899906842624" + tail + std::string(64, '\0'));
  const std::string message = thrownMessage<ConfigError>([&] { sim::loadMesh(entry(huge)); });
  EXPECT_TRUE(contains(message, huge + ": the PLY header declares 1125899906842624 vertices (12 bytes each) and 1 "
                                       "faces: expected no more than the 64 bytes after the header hold"))
      << message;
  // Three vertices, and more faces than the bytes after them hold (a count byte each at least).
  std::string faces = head + "3" + tail;
  faces.replace(faces.find("element face 1"), 14, "element face 4000000000");
  faces += std::string(36 + 13, '\0');
  const std::string many = writeFile("ply_many_faces.ply", faces);
  const std::string faces_message = thrownMessage<ConfigError>([&] { sim::loadMesh(entry(many)); });
  EXPECT_TRUE(contains(faces_message, many + ": the PLY header declares 3 vertices (12 bytes each) and 4000000000 "
                                             "faces: expected no more than the 49 bytes"))
      << faces_message;
}

TEST(PlyReader, TheGeneratedMineReadsAsAssimpReadsIt) {
  const std::string file = "worlds/meshes/mine/mine_collision.ply";  // made by scripts/setup.sh
  ASSERT_TRUE(std::ifstream(file).good()) << file << " is missing: run scripts/setup.sh";
  sim::TriangleMesh direct;
  ASSERT_TRUE(sim::readBinaryPly(entry(file), direct));
  EXPECT_GT(direct.triangleCount(), 1000000u);
  expectSameCorners(direct, sim::loadMeshWithAssimp(entry(file)));
}

}  // namespace
}  // namespace test
}  // namespace unexmin

// Mesh loader (cpp/unexmin/sim/mesh.h) on files the test writes itself: the triangle count of an STL and of an
// OBJ with a quad (triangulated), the vertices with scale, then rotation R = Rz Ry Rx, then translation applied
// (docs/worlds.md), computed here; the same mesh loaded by a world file and seen by the world's ray caster at
// the closed-form distances; and unreadable, empty or triangle-less files -> ConfigError naming the file.
#include <unexmin/raycast/ray_caster.h>
#include <unexmin/raycast/ray_caster_factory.h>
#include <unexmin/sim/mesh.h>
#include "mesh_fixture.h"
#include "sphere_fixture.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <type_traits>
#include <vector>

namespace unexmin {
namespace test {
namespace {

/// A file of the given content in the test process's temporary folder; returns its path.
std::string writeFile(const std::string& name, const std::string& content) {
  const std::string path = testTempDir() + name;
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

sim::MeshEntry entry(const std::string& name, const std::string& file) {
  sim::MeshEntry e;
  e.name = name;
  e.file = file;
  return e;
}

/// R = Rz(yaw) Ry(pitch) Rx(roll) from the elementary rotation matrices.
Eigen::Matrix3d rpyMatrix(double roll, double pitch, double yaw) {
  Eigen::Matrix3d rx, ry, rz;
  rx << 1, 0, 0, 0, std::cos(roll), -std::sin(roll), 0, std::sin(roll), std::cos(roll);
  ry << std::cos(pitch), 0, std::sin(pitch), 0, 1, 0, -std::sin(pitch), 0, std::cos(pitch);
  rz << std::cos(yaw), -std::sin(yaw), 0, std::sin(yaw), std::cos(yaw), 0, 0, 0, 1;
  return rz * ry * rx;
}

/// Loaded triangle t has the vertices of `expected` triangle t (any cyclic order) within `tol` [m].
void expectSameTriangles(const sim::TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& expected, double tol) {
  ASSERT_EQ(mesh.triangleCount() * 3, expected.size());
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    double best = INFINITY;
    for (int shift = 0; shift < 3; ++shift) {
      double worst = 0.0;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d got = mesh.vertices[mesh.indices[3 * t + (k + shift) % 3]].cast<double>();
        worst = std::max(worst, (got - expected[3 * t + k]).norm());
      }
      best = std::min(best, worst);
    }
    EXPECT_LT(best, tol) << "triangle " << t;
  }
}

/// The corners of every triangle of g, mapped by f.
template <typename F>
std::vector<Eigen::Vector3d> corners(const Geometry& g, F f) {
  std::vector<Eigen::Vector3d> out;
  for (int i : g.indices)
    out.push_back(f(g.vertices[i]));
  return out;
}

TEST(Mesh, AnStlLoadsWithItsTrianglesAndVertices) {
  const Geometry b = box(Eigen::Vector3d(-1, -2, -3), Eigen::Vector3d(4, 5, 6));
  const sim::TriangleMesh m = sim::loadMesh(entry("a_box", writeStl("mesh_test_box", b)));
  EXPECT_EQ(m.name, "a_box");
  EXPECT_EQ(m.triangleCount(), 12u);
  EXPECT_EQ(m.indices.size(), 36u);
  for (int i : m.indices) {
    ASSERT_GE(i, 0);
    ASSERT_LT(i, static_cast<int>(m.vertices.size()));
  }
  expectSameTriangles(m, corners(b, [](const Eigen::Vector3d& v) { return v; }), 1e-6);

  // An icosphere subdivided twice: 20 x 4^2 triangles.
  const sim::TriangleMesh s =
      sim::loadMesh(entry("ball", writeStl("mesh_test_ball", icosphere(Eigen::Vector3d(1, 2, 3), 0.5, 2))));
  EXPECT_EQ(s.triangleCount(), 320u);
  for (const auto& v : s.vertices)
    EXPECT_NEAR((v.cast<double>() - Eigen::Vector3d(1, 2, 3)).norm(), 0.5, 1e-6);
}

TEST(Mesh, ScaleThenRotationThenTranslationAsTheWorldFileDocumentsThem) {
  const Geometry b = box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  const Eigen::Vector3d scale(2.0, 0.5, 3.0), xyz(1.0, -2.0, 3.0), rpy(0.3, -0.2, 1.1);
  sim::MeshEntry e = entry("posed", writeStl("mesh_test_unit_box", b));
  e.scale = scale;
  e.pose = sim::poseFromXyzRpy(xyz, rpy);  // how loadWorldConfig fills it from xyz / rpy
  const Eigen::Matrix3d R = rpyMatrix(rpy.x(), rpy.y(), rpy.z());
  const auto world = [&](const Eigen::Vector3d& v) -> Eigen::Vector3d { return xyz + R * scale.cwiseProduct(v); };
  const sim::TriangleMesh m = sim::loadMesh(e);
  EXPECT_EQ(m.triangleCount(), 12u);
  expectSameTriangles(m, corners(b, world), 1e-5);
  // Scaling after the rotation (or not at all) would put the far corner elsewhere.
  const Eigen::Vector3d far = world(Eigen::Vector3d(1, 1, 1));
  ASSERT_GT((far - (xyz + scale.cwiseProduct(R * Eigen::Vector3d(1, 1, 1)))).norm(), 0.5);
  double nearest = INFINITY;
  for (const auto& v : m.vertices)
    nearest = std::min(nearest, (v.cast<double>() - far).norm());
  EXPECT_LT(nearest, 1e-5);
}

TEST(Mesh, AnObjQuadIsTriangulatedAndLinesCarryNoSurface) {
  // A unit square (one quad), a triangle above it and a line: 2 + 1 triangles.
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\n"
      "f 1 2 3 4\nf 5 6 7\nl 1 5\n";
  sim::MeshEntry e = entry("quad", writeFile("mesh_test_quad.obj", obj));
  e.scale = Eigen::Vector3d(3, 3, 3);
  const sim::TriangleMesh m = sim::loadMesh(e);
  EXPECT_EQ(m.triangleCount(), 3u);
  double area = 0.0;  // 3 x 3 square + half of it
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    const Eigen::Vector3f a = m.vertices[m.indices[3 * t]], b = m.vertices[m.indices[3 * t + 1]],
                          c = m.vertices[m.indices[3 * t + 2]];
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  EXPECT_NEAR(area, 9.0 + 4.5, 1e-5);
}

TEST(Mesh, AWorldFileLoadsTheMeshWhereTheRayCasterSeesItAtTheClosedFormDistance) {
  // The unit box scaled (2, 0.5, 3) and posed by a world file; rays from its centre along its own axes meet the
  // faces at half the scaled sizes: 1, 0.25 and 1.5 m.
  const Eigen::Vector3d scale(2.0, 0.5, 3.0), xyz(1.0, -2.0, 3.0), rpy(0.3, -0.2, 1.1);
  writeStl("mesh_test_world_box", box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1)));  // beside the world file
  const std::string world_file = writeFile("mesh_test.world",
                                           "name: mesh_test\nwater: {density: 1000.0, surface_z: 100.0}\nmeshes:\n"
                                           "  - {name: posed_box, file: mesh_test_world_box.stl, scale: [2, 0.5, 3], "
                                           "xyz: [1, -2, 3], rpy: [0.3, -0.2, 1.1]}\n"
                                           "robots:\n  - {name: T, xyz: [50, 50, -50]}\n");
  const sim::WorldConfig config = sim::loadWorldConfig(world_file);
  ASSERT_EQ(config.meshes.size(), 1u);
  const auto w = makeWorld(config, SphereSpec());
  ASSERT_EQ(w->meshCount(), 1u);
  EXPECT_EQ(w->mesh(0).name, "posed_box");
  EXPECT_EQ(w->mesh(0).triangleCount(), 12u);

  const Eigen::Matrix3d R = rpyMatrix(rpy.x(), rpy.y(), rpy.z());
  const Eigen::Vector3d centre = xyz + R * scale.cwiseProduct(Eigen::Vector3d(0.5, 0.5, 0.5));
  auto caster = raycast::makeRayCaster("embree", *w);
  caster->update();
  std::vector<raycast::Ray> rays;
  std::vector<double> expected;
  for (int a = 0; a < 3; ++a) {
    for (double sign : {1.0, -1.0}) {
      raycast::Ray r;
      r.origin = centre.cast<float>();
      r.direction = (sign * R.col(a)).cast<float>();
      r.max_range = 10.0f;
      rays.push_back(r);
      expected.push_back(0.5 * scale[a]);
    }
  }
  std::vector<raycast::Hit> hits;
  caster->cast(rays, hits);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    ASSERT_TRUE(hits[i].hit()) << "ray " << i;
    EXPECT_EQ(hits[i].kind, raycast::HitKind::mesh);
    EXPECT_NEAR(hits[i].range, expected[i], 1e-4) << "ray " << i;
    EXPECT_NEAR(hits[i].incidence, 0.0, 1e-3) << "ray " << i;  // along the box's own axes: head-on
  }
}

/// The what() of the ConfigError that loading `e` throws; a test failure if none.
std::string loadError(const sim::MeshEntry& e) {
  try {
    sim::loadMesh(e);
  } catch (const ConfigError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no ConfigError for " << e.file;
  return "";
}

TEST(Mesh, UnreadableEmptyOrTriangleLessFilesStopWithAConfigErrorNamingTheFile) {
  static_assert(std::is_base_of<Error, ConfigError>::value, "ConfigError is an unexmin::Error");
  // An STL header that announces no triangle.
  std::string no_triangles(80, '\0');
  const std::uint32_t zero = 0;
  no_triangles.append(reinterpret_cast<const char*>(&zero), 4);
  const std::vector<sim::MeshEntry> bad = {
      entry("missing", testTempDir() + "mesh_test_does_not_exist.stl"),
      entry("empty", writeFile("mesh_test_empty.stl", "")),
      entry("text", writeFile("mesh_test_text.stl", "this is not a mesh\n")),
      entry("no_triangles", writeFile("mesh_test_no_triangles.stl", no_triangles)),
      entry("points", writeFile("mesh_test_points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\n")),
  };
  for (const auto& e : bad) {
    const std::string m = loadError(e);
    EXPECT_NE(m.find(e.file), std::string::npos) << e.name << ": " << m;
    EXPECT_NE(m.find("'" + e.name + "'"), std::string::npos) << e.name << ": " << m;
  }
}

}  // namespace
}  // namespace test
}  // namespace unexmin

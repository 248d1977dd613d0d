// The checkerboard material (sim::checkerboardAlbedo, kind `checkerboard` of a world file's mesh; docs/worlds.md
// "Materials"): its squares, margin and plate against their closed-form layout, in the mesh's own frame, as the
// cameras see it through SurfaceMaterials; bad keys name the file and the key.
#include <unexmin/core/error.h>
#include <unexmin/sensors/vision/surface_materials.h>
#include <unexmin/sim/material.h>
#include <unexmin/sim/world_config.h>
#include "expect_error.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

using unexmin::sim::Material;
using unexmin::test::contains;
using unexmin::test::thrownMessage;

namespace {

/// A checkerboard of `rows` x `columns` squares of `square` [m], light 0.8, dark 0.1, margin `border` [m].
Material board(int rows, int columns, double square, double border) {
  Material m = unexmin::sim::materialDefaults("checkerboard");
  m.rows = rows;
  m.columns = columns;
  m.square = square;
  m.border = border;
  m.albedo = Eigen::Vector3d::Constant(0.8);
  m.dark = Eigen::Vector3d(0.1, 0.2, 0.3);
  return m;
}

/// A world file (in the test's folder) holding the target plate (worlds/meshes/target.stl) with `keys` after its file.
std::string plateWorld(const std::string& name, const std::string& keys) {
  const std::filesystem::path dir = unexmin::test::testTempDir();
  const std::filesystem::path plate = dir / "target.stl";
  if (!std::filesystem::exists(plate))
    std::filesystem::copy_file(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/meshes/target.stl", plate);
  const std::filesystem::path world = dir / name;
  std::ofstream out(world);
  out << "name: target\nrobots: [{name: UX_1}]\nmeshes:\n  - {name: plate, file: target.stl" << keys << "}\n";
  return world.string();
}

/// The ConfigError message of loading world file `path`.
std::string loadError(const std::string& path) {
  return thrownMessage<unexmin::ConfigError>([&] { unexmin::sim::loadWorldConfig(path); });
}

}  // namespace

TEST(Checkerboard, SquaresMarginAndPlate) {
  const Material m = board(5, 7, 0.1, 0.05);  // squares over x in [-0.35, 0.35], y in [-0.25, 0.25]
  const Eigen::Vector3f light(0.8f, 0.8f, 0.8f), dark(0.1f, 0.2f, 0.3f);
  int darks = 0;
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 5; ++j) {
      // Square (i, j), i along x and j along y from the corner at the most negative x and y: dark when i + j is
      // even. Its centre and points 1 mm inside its edges, at any z (the plate's both faces).
      const float x0 = -0.35f + 0.1f * i, y0 = -0.25f + 0.1f * j;
      const Eigen::Vector3f expected = (i + j) % 2 == 0 ? dark : light;
      darks += (i + j) % 2 == 0;
      for (const float z : {-0.005f, 0.0f, 0.005f})
        for (const auto& p : {Eigen::Vector3f(x0 + 0.05f, y0 + 0.05f, z), Eigen::Vector3f(x0 + 0.001f, y0 + 0.001f, z),
                              Eigen::Vector3f(x0 + 0.099f, y0 + 0.099f, z)})
          EXPECT_TRUE(unexmin::sim::checkerboardAlbedo(m, p).isApprox(expected)) << i << " " << j;
    }
  EXPECT_EQ(darks, 18);  // 35 squares, the corners dark
  // The light margin, 5 cm wide, and the dark plate beyond it.
  for (const auto& p :
       {Eigen::Vector3f(0.36f, 0.0f, 0.0f), Eigen::Vector3f(-0.39f, 0.29f, 0.0f), Eigen::Vector3f(0.0f, -0.26f, 0.0f)})
    EXPECT_TRUE(unexmin::sim::checkerboardAlbedo(m, p).isApprox(light)) << p.transpose();
  for (const auto& p : {Eigen::Vector3f(0.41f, 0.0f, 0.0f), Eigen::Vector3f(0.0f, -0.31f, 0.0f)})
    EXPECT_TRUE(unexmin::sim::checkerboardAlbedo(m, p).isApprox(dark)) << p.transpose();
}

TEST(Checkerboard, InAWorldFileItIsInTheMeshFrameWithTheFacesNormal) {
  const auto w = unexmin::sim::loadWorldConfig(
      plateWorld("b.world",
                 ", xyz: [1, -2, -3], rpy: [1.5708, 0, 0.4], material: {kind: checkerboard, square: 0.05, rows: 4, "
                 "columns: 6, dark: [0.1, 0.2, 0.3], albedo: [0.9, 0.8, 0.7], border: 0.02}"));
  const unexmin::sensors::vision::SurfaceMaterials sm(w);
  const Material& m = w.meshes.at(0).material;
  ASSERT_TRUE(m.checkerboard()) << m.kind;
  EXPECT_EQ(std::make_pair(m.rows, m.columns), std::make_pair(4, 6));
  EXPECT_EQ(std::make_pair(m.square, m.border), std::make_pair(0.05, 0.02));  // as parsed from the same text
  ASSERT_TRUE(sm.textured(0));  // the cameras ask for its albedo at each hit
  const Eigen::Isometry3f pose = w.meshes[0].pose.cast<float>();
  // The first square (dark) and its neighbour along x (light), seen at their world points.
  const Eigen::Vector3f first = pose * Eigen::Vector3f(-0.125f, -0.075f, 0.0f);
  const Eigen::Vector3f next = pose * Eigen::Vector3f(-0.075f, -0.075f, 0.0f);
  EXPECT_TRUE(sm.albedo(0, first).matrix().isApprox(Eigen::Vector3f(0.1f, 0.2f, 0.3f)));
  EXPECT_TRUE(sm.albedo(0, next).matrix().isApprox(Eigen::Vector3f(0.9f, 0.8f, 0.7f)));
  const Eigen::Vector3f n = pose.linear() * Eigen::Vector3f::UnitZ();
  float albedo[3];
  Eigen::Vector3f shading;
  sm.shade(0, next, n, albedo, shading);
  EXPECT_FLOAT_EQ(albedo[2], 0.7f);
  EXPECT_TRUE(shading.isApprox(n));
  // shadeMany, as the camera's tiles call it (points in a camera frame given by its pose in the world): the same
  // albedos, the normals untouched.
  const Eigen::Matrix3f cam_rot = Eigen::AngleAxisf(0.4f, Eigen::Vector3f(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3f cam_pos(0.3f, -0.2f, 1.5f);
  const Eigen::Vector3f a = cam_rot.transpose() * (first - cam_pos), c = cam_rot.transpose() * (next - cam_pos);
  float x[2] = {a.x(), c.x()}, y[2] = {a.y(), c.y()}, z[2] = {a.z(), c.z()};
  float nx[2] = {n.x(), n.x()}, ny[2] = {n.y(), n.y()}, nz[2] = {n.z(), n.z()};
  float r[2], g[2], b[2];
  float* const out[3] = {r, g, b};
  sm.shadeMany(0, cam_rot, cam_pos, 2, x, y, z, nx, ny, nz, out, true);
  EXPECT_FLOAT_EQ(r[0], 0.1f);
  EXPECT_FLOAT_EQ(b[1], 0.7f);
  EXPECT_FLOAT_EQ(nz[1], n.z());
}

TEST(Checkerboard, TheDefaultsAreThe8x6Target) {
  const Material m = unexmin::sim::materialDefaults("checkerboard");
  EXPECT_EQ(m.rows - 1, 6);
  EXPECT_EQ(m.columns - 1, 8);
  EXPECT_DOUBLE_EQ(m.square, 0.08);
  EXPECT_NO_THROW(unexmin::sim::checkMaterial(m));
}

TEST(Checkerboard, BadKeysNameTheFileAndTheKey) {
  const std::pair<const char*, const char*> cases[] = {
      {"{kind: checkerboard, rows: 1.5}", "'meshes[0].material.rows' = 1.5: expected an integer in [2, 1000]"},
      {"{kind: checkerboard, columns: 1}", "'meshes[0].material.columns' = 1"},
      {"{kind: checkerboard, square: 0}", "'meshes[0].material.square' = 0"},
      {"{kind: checkerboard, border: -0.1}", "'meshes[0].material.border' = -0.1"},
      {"{kind: checkerboard, dark: [0.1, 1.2, 0.1]}", "'meshes[0].material.dark' = 1.2"},
      {"{kind: checkerboard, contrast: 0.2}", "'meshes[0].material.contrast' = 0.2: expected 0 on a checkerboard"},
      {"{kind: checkerboard, grain: 0.01}", "'meshes[0].material.grain' = 0.01: expected 0 on a checkerboard"},
      {"{kind: rock, rows: 5}", "'meshes[0].material.rows' is a key of kind checkerboard, not of 'rock'"},
  };
  int k = 0;
  for (const auto& [material, message] : cases) {
    const std::string path = plateWorld("bad" + std::to_string(k++) + ".world", ", material: " + std::string(material));
    const std::string what = loadError(path);
    EXPECT_TRUE(contains(what, path + ": " + message)) << material << " -> " << what;
  }
}

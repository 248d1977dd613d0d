// Image textures and vertex colours of world meshes (docs/worlds.md "Image textures and vertex colours", docs/vision.md
// "Materials"): bilinear sampling in linear light against values written out here, a textured and a coloured plate in
// a camera image with the channel ratios of their colours, and the start-up errors naming the world file and key.
#include <unexmin/raycast/ray_caster_factory.h>
#include <unexmin/sensors/vision/camera_sensor.h>
#include <unexmin/sensors/vision/surface_materials.h>
#include <unexmin/sim/texture_image.h>
#include "expect_error.h"
#include "mesh_fixture.h"
#include "sensor_fixture.h"
#include "temp_dir.h"

#include <gtest/gtest.h>
#include <jpeglib.h>
#include <png.h>

#include <cstdio>
#include <fstream>

namespace unexmin {
namespace test {
namespace {

using sim::TextureImage;

/// sRGB code -> linear light, IEC 61966-2-1, written out here.
double srgb(int code) {
  const double c = code / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

std::string writePng(const std::string& name, int w, int h, const std::vector<std::uint8_t>& rgb) {
  const std::string path = testTempDir() + name + ".png";
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(w);
  image.height = static_cast<png_uint_32>(h);
  image.format = PNG_FORMAT_RGB;
  EXPECT_TRUE(png_image_write_to_file(&image, path.c_str(), 0, rgb.data(), 0, nullptr)) << image.message;
  return path;
}

std::string writeJpeg(const std::string& name, int w, int h, const std::vector<std::uint8_t>& rgb) {
  const std::string path = testTempDir() + name + ".jpg";
  FILE* f = std::fopen(path.c_str(), "wb");
  jpeg_compress_struct info{};
  jpeg_error_mgr err{};
  info.err = jpeg_std_error(&err);
  jpeg_create_compress(&info);
  jpeg_stdio_dest(&info, f);
  info.image_width = static_cast<JDIMENSION>(w);
  info.image_height = static_cast<JDIMENSION>(h);
  info.input_components = 3;
  info.in_color_space = JCS_RGB;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, 100, TRUE);
  jpeg_start_compress(&info, TRUE);
  for (int j = 0; j < h; ++j) {
    JSAMPROW row = const_cast<std::uint8_t*>(&rgb[3 * static_cast<std::size_t>(j) * w]);
    jpeg_write_scanlines(&info, &row, 1);
  }
  jpeg_finish_compress(&info);
  jpeg_destroy_compress(&info);
  std::fclose(f);
  return path;
}

TEST(TextureImage, SamplesTexelCentresExactlyAndInterpolatesInLinearLight) {
  // 2 x 2 texels, top row first: (10, 128, 255) (200, 0, 50) / (0, 0, 0) (255, 255, 255).
  const TextureImage im(2, 2, {10, 128, 255, 200, 0, 50, 0, 0, 0, 255, 255, 255});
  const auto near = [](const Eigen::Array3f& a, double r, double g, double b) {
    EXPECT_NEAR(a[0], r, 1e-6);
    EXPECT_NEAR(a[1], g, 1e-6);
    EXPECT_NEAR(a[2], b, 1e-6);
  };
  near(im.sample(0.25f, 0.75f), srgb(10), srgb(128), srgb(255));  // top-left texel's centre (v = 1 is the top)
  near(im.sample(0.75f, 0.75f), srgb(200), srgb(0), srgb(50));
  near(im.sample(0.25f, 0.25f), 0, 0, 0);
  near(im.sample(0.5f, 0.75f), (srgb(10) + srgb(200)) / 2, srgb(128) / 2, (srgb(255) + srgb(50)) / 2);
  // A quarter of the way from the bottom-right texel to the top-right one, then repeated one tile over.
  near(im.sample(1.75f, -0.625f), 0.75 + 0.25 * srgb(200), 0.75, 0.75 + 0.25 * srgb(50));
  EXPECT_NEAR(TextureImage::linear(128), 0.2158605, 1e-6);
}

TEST(TextureImage, ReadsPngAndJpegAndRefusesOtherFilesNamingThem) {
  std::vector<std::uint8_t> rgb;
  for (int i = 0; i < 16 * 8; ++i)
    rgb.insert(rgb.end(), {200, 100, 50});
  const TextureImage png = TextureImage::load(writePng("flat", 16, 8, rgb));
  EXPECT_EQ(png.width(), 16);
  EXPECT_EQ(png.height(), 8);
  EXPECT_NEAR(png.sample(0.3f, 0.6f)[1], srgb(100), 1e-6);
  const TextureImage jpg = TextureImage::load(writeJpeg("flat", 16, 8, rgb));
  EXPECT_EQ(jpg.width(), 16);
  for (int c = 0; c < 3; ++c)  // quality 100: within two codes
    EXPECT_NEAR(jpg.sample(0.3f, 0.6f)[c], srgb(rgb[c]), srgb(rgb[c]) - srgb(rgb[c] - 2));
  const std::string bad = testTempDir() + "bad.png";
  std::ofstream(bad) << "\x89PNG and then nothing";
  EXPECT_TRUE(contains(thrownMessage<ConfigError>([&] { TextureImage::load(bad); }), bad + ": damaged PNG"));
  const std::string text = testTempDir() + "text.png";
  std::ofstream(text) << "hello";
  EXPECT_TRUE(
      contains(thrownMessage<ConfigError>([&] { TextureImage::load(text); }), text + ": neither a PNG nor a JPEG"));
}

// ---------------------------------------------------------------- plates in a camera image
const Eigen::Vector3d kSpawn(0.0, 0.0, -10.0);  // [m] the sphere robot, open water
constexpr double kPlateX = 1.5, kHalf = 0.3;    // [m] a square plate across +x, 0.6 m wide, centred on the lens axis
constexpr int kSize = 96;                       // [px] square image

/// The plate as a text file: OBJ with texture coordinates (u along -y: left to right in the image; v along +z) or
/// PLY with one colour per vertex.
std::string plateFile(const std::string& name, const std::vector<std::array<int, 3>>& colours = {}) {
  const double y[4] = {kHalf, -kHalf, -kHalf, kHalf}, z[4] = {-kHalf, -kHalf, kHalf, kHalf};
  const double u[4] = {0, 1, 1, 0}, v[4] = {0, 0, 1, 1};
  std::ostringstream o;
  if (colours.empty()) {
    for (int k = 0; k < 4; ++k)
      o << "v " << kPlateX << " " << y[k] << " " << z[k] + kSpawn.z() << "\nvt " << u[k] << " " << v[k] << "\n";
    o << "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
  } else {
    o << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      << "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 2\n"
      << "property list uchar int vertex_indices\nend_header\n";
    for (int k = 0; k < 4; ++k)
      o << kPlateX << " " << y[k] << " " << z[k] + kSpawn.z() << " " << colours[k][0] << " " << colours[k][1] << " "
        << colours[k][2] << "\n";
    o << "3 0 1 2\n3 0 2 3\n";
  }
  const std::string path = testTempDir() + name + (colours.empty() ? ".obj" : ".ply");
  std::ofstream(path) << o.str();
  return path;
}

sim::WorldConfig plateWorld(const std::string& file, const sim::Material& material) {
  sim::WorldConfig config = openWater(SphereSpec(), kSpawn);
  sim::MeshEntry e;
  e.name = "plate";
  e.file = file;
  e.material = material;
  e.albedo = material.albedo;
  config.meshes.push_back(e);
  return config;
}

sim::Material kind(const std::string& name, const std::string& image = "") {
  sim::Material m = sim::materialDefaults(name);
  m.image = image;
  return m;
}

/// Linear radiance (3 per pixel) of a forward camera on the robot held at kSpawn, lit by an LED beside the lens.
std::vector<float> radiance(const sim::WorldConfig& config) {
  const std::map<std::string, std::string> params{
      {"width", num(kSize)}, {"height", num(kSize)},      {"hfov", num(40.0 * M_PI / 180.0)},
      {"noise", "none"},     {"exposure", "1"},           {"clip_far", "10"},
      {"lights", "T/led"},   {"light_intensity", "2 2 2"}};
  const std::string urdf =
      sensorUrdf(SphereSpec(),
                 mountLink("T/cam", Eigen::Vector3d(0.3, 0, 0), Eigen::Vector3d(-M_PI / 2, 0, -M_PI / 2)) +
                     mountLink("T/led", Eigen::Vector3d(0.3, 0, 0.1), Eigen::Vector3d::Zero()),
                 sensorXml("cam", "camera", "T/cam", 10.0, params));
  std::map<std::string, sim::RobotDescription> d;
  d.emplace("T", sim::parseRobotDescription(urdf, "(camera robot)"));
  sim::World world(config, d, 1, 0.002, 1);
  auto caster = raycast::makeRayCaster("embree", world);
  sensors::SensorFactory factory = coreModels();
  factory.add<sensors::vision::CameraSensor>("camera");
  sensors::SensorSuite suite(world, world.robot(0), caster.get(), factory, sensors::SensorSelection(), true);
  const auto& cam = dynamic_cast<const sensors::vision::CameraSensor&>(*suite.find("cam"));
  while (cam.sampleCount() == 0) {
    world.robot(0).setPose(Eigen::Isometry3d(Eigen::Translation3d(kSpawn)));
    world.step();
    caster->update();
    suite.update();
  }
  return cam.last().radiance;
}

/// The albedo each pixel sees on the plate of `file` with material `m` (3 per pixel): its radiance against that of the
/// same plate white and black (radiance is linear in the albedo: backscatter + albedo x the direct light).
std::vector<double> albedoSeen(const std::string& file, const sim::Material& m) {
  const std::vector<float> seen = radiance(plateWorld(file, m));
  sim::Material plain = kind("plain");
  plain.albedo = Eigen::Vector3d::Ones();
  const std::vector<float> white = radiance(plateWorld(file, plain));
  plain.albedo = Eigen::Vector3d::Zero();
  const std::vector<float> black = radiance(plateWorld(file, plain));
  std::vector<double> out(seen.size(), -1.0);
  for (std::size_t i = 0; i < seen.size(); ++i)
    if (white[i] > black[i])
      out[i] = (static_cast<double>(seen[i]) - black[i]) / (static_cast<double>(white[i]) - black[i]);
  return out;
}

/// Pixel (column u, row v) of the plate point at fraction s of its width from its left edge (image left = +y) and
/// fraction t of its height from its bottom.
std::size_t pixelAt(double s, double t) {
  const double f = kSize / 2.0 / std::tan(20.0 * M_PI / 180.0), c = (kSize - 1) / 2.0, depth = kPlateX - 0.3;
  const double y = kHalf - 2 * kHalf * s, z = -kHalf + 2 * kHalf * t;  // world offsets from the lens axis
  const long u = std::lround(c + f * (-y) / depth), v = std::lround(c + f * (-z) / depth);
  return static_cast<std::size_t>(v * kSize + u);
}

TEST(MappedSurfaces, ATexturedPlateHasTheImagesColoursTimesItsAlbedo) {
  // 4 x 1 texels A A B B: the left half of the plate (u < 0.375) is exactly A, the right (u > 0.625) exactly B.
  const std::array<int, 3> a{200, 60, 30}, b{20, 90, 240};
  std::vector<std::uint8_t> rgb;
  for (const auto& t : {a, a, b, b})
    for (int c = 0; c < 3; ++c)
      rgb.push_back(static_cast<std::uint8_t>(t[c]));
  sim::Material image = kind("image", writePng("aabb", 4, 1, rgb));
  image.albedo = Eigen::Vector3d(0.5, 0.8, 1.0);
  const std::vector<double> seen = albedoSeen(plateFile("uv_plate"), image);
  for (const auto& [s, texel] :
       {std::make_pair(0.2, a), std::make_pair(0.3, a), std::make_pair(0.7, b), std::make_pair(0.8, b)})
    for (double t : {0.2, 0.5, 0.8}) {
      const std::size_t p = pixelAt(s, t);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(seen[3 * p + c], image.albedo[c] * srgb(texel[c]), 1e-3) << "s " << s << " t " << t << " ch " << c;
    }
}

TEST(MappedSurfaces, AColouredPlateHasItsVertexColoursInterpolated) {
  // Left edge (vertices 0 and 3, +y) one colour, right edge another: the albedo runs linearly between them.
  const std::array<int, 3> left{200, 100, 50}, right{40, 160, 220};
  const std::string file = plateFile("coloured_plate", {left, right, right, left});
  const std::vector<double> seen = albedoSeen(file, kind("vertex_colours"));
  for (double s : {0.1, 0.5, 0.9}) {
    const std::size_t p = pixelAt(s, 0.5);
    // The pixel's centre is within half a pixel of s: its own fraction across the plate, from its column.
    const double f = kSize / 2.0 / std::tan(20.0 * M_PI / 180.0), c0 = (kSize - 1) / 2.0;
    const double y = -(static_cast<double>(p % kSize) - c0) * (kPlateX - 0.3) / f;
    const double frac = (kHalf - y) / (2 * kHalf);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(seen[3 * p + c], (1 - frac) * srgb(left[c]) + frac * srgb(right[c]), 1e-3)
          << "s " << s << " channel " << c;
  }
}

TEST(MappedSurfaces, MissingOrUnusableSurfacesStopStartUpNamingTheFileAndKey) {
  const std::string dir = testTempDir() + "mapped/";
  std::filesystem::create_directories(dir + "textures");
  std::filesystem::copy_file(plateFile("uv"), dir + "plate.obj", std::filesystem::copy_options::overwrite_existing);
  writeStl("mapped/plain", box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()));
  std::ofstream(dir + "textures/damaged.png") << "\x89PNG";
  const auto start = [&](const std::string& mesh) {
    std::ofstream(dir + "w.world") << "robots: [{name: T}]\nmeshes:\n  - {file: " << mesh << "}\n";
    const sim::WorldConfig config = sim::loadWorldConfig(dir + "w.world");
    std::map<std::string, sim::RobotDescription> d;
    d.emplace("T", sim::parseRobotDescription(sphereUrdf(SphereSpec()), "(sphere)"));
    sim::World world(config, d, 1, 0.002, 1);
  };
  const std::pair<std::string, std::string> cases[] = {
      {"plate.obj, material: {kind: image, image: textures/missing.png}",
       "'meshes[0].material.image' " + dir + "textures/missing.png does not exist"},
      {"plate.obj, material: {kind: image, image: textures/damaged.png}",
       "'meshes[0].material.image': " + dir + "textures/damaged.png: damaged PNG"},
      {"plate.obj, material: {kind: image}", "'meshes[0].material.image' = (none): expected the PNG or JPEG file"},
      {"plate.obj, material: {kind: rock, image: textures/damaged.png}", "'meshes[0].material.kind' = 'rock'"},
      {"plain.stl, material: {kind: image, image: textures/damaged.png}",
       "'meshes[0].material.kind' = 'image': " + dir + "plain.stl has no texture coordinates"},
      {"plain.stl, material: {kind: vertex_colours}",
       "'meshes[0].material.kind' = 'vertex_colours': " + dir + "plain.stl has no vertex colours"},
  };
  for (const auto& [mesh, expected] : cases) {
    const std::string what = thrownMessage<ConfigError>([&] { start(mesh); });
    EXPECT_TRUE(contains(what, dir + "w.world: ")) << what;
    EXPECT_TRUE(contains(what, expected)) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace test
}  // namespace unexmin

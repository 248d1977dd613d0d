// The procedural solid texture of a material (cpp/unexmin/sensors/vision/rock_texture.h) and the world file's
// `material:` key (cpp/unexmin/sim/world_config.cpp): every expected value from the model's documented formulas
// (docs/vision.md "Materials"), over seeded samples of points.
#include <unexmin/sensors/vision/image_formation.h>
#include <unexmin/sensors/vision/rock_texture.h>
#include <unexmin/sensors/vision/surface_materials.h>
#include <unexmin/sim/world_config.h>
#include "expect_error.h"
#include "temp_dir.h"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <vector>

using unexmin::sensors::vision::RockTexture;
using unexmin::sim::Material;
using unexmin::test::contains;
using unexmin::test::thrownMessage;

namespace {

Material rock(std::uint64_t seed, double contrast = 0.2) {
  Material m = unexmin::sim::materialDefaults("rock");
  m.seed = seed;
  m.contrast = contrast;
  return m;
}

/// n seeded points uniform in a cube of side `side` [m] centred on `centre`.
std::vector<Eigen::Vector3f> points(int n, float side, const Eigen::Vector3f& centre = Eigen::Vector3f::Zero(),
                                    unsigned seed = 11) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<float> u(-0.5f * side, 0.5f * side);
  std::vector<Eigen::Vector3f> out;
  for (int i = 0; i < n; ++i)
    out.emplace_back(centre + Eigen::Vector3f(u(gen), u(gen), u(gen)));
  return out;
}

struct Stats {
  Eigen::Array3d mean = Eigen::Array3d::Zero(), sd = Eigen::Array3d::Zero();
};

Stats albedoStats(const RockTexture& t, const std::vector<Eigen::Vector3f>& pts) {
  Stats s;
  Eigen::Array3d s2 = Eigen::Array3d::Zero();
  for (const auto& p : pts) {
    const Eigen::Array3d a = t.albedo(p).cast<double>();
    s.mean += a;
    s2 += a * a;
  }
  s.mean /= pts.size();
  s.sd = (s2 / pts.size() - s.mean * s.mean).sqrt();
  return s;
}

}  // namespace

TEST(RockTexture, SameSeedSameTextureOtherSeedAnother) {
  const RockTexture a(rock(5)), b(rock(5)), c(rock(6));
  double differ = 0.0;
  const auto pts = points(2000, 4.0f);
  for (const auto& p : pts) {
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(a.albedo(p)[k], b.albedo(p)[k]);  // bit for bit: a pure function
    differ += std::abs(a.albedo(p)[1] - c.albedo(p)[1]) / pts.size();
  }
  // Two independent textures of relative sd 0.2 around 0.29: E|x - y| = 2 sd / sqrt(pi) = 0.065.
  const double expected = 2.0 * 0.2 * rock(5).albedo.y() / std::sqrt(M_PI);
  EXPECT_NEAR(differ, expected, 0.25 * expected);
}

TEST(RockTexture, MeanIsTheAlbedoAndContrastIsTheRelativeDeviation) {
  // Over a 30 m cube (about 3000 of the 2 m stains), with the rock kind's four components.
  const auto pts = points(60000, 30.0f);
  for (double contrast : {0.1, 0.2, 0.3}) {
    const Material m = rock(3, contrast);
    const Stats s = albedoStats(RockTexture(m), pts);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(s.mean[k], m.albedo[k], 0.02 * m.albedo[k]) << "contrast " << contrast << " channel " << k;
      EXPECT_NEAR(s.sd[k] / m.albedo[k], contrast, 0.1 * contrast) << "contrast " << contrast << " channel " << k;
    }
  }
  // One component alone is normalised too.
  Material grain = rock(4, 0.25);
  grain.cracks = grain.strata = grain.stains = 0.0;
  const Stats g = albedoStats(RockTexture(grain), points(40000, 2.0f));
  EXPECT_NEAR(g.sd[0] / grain.albedo[0], 0.25, 0.025);
  EXPECT_NEAR(g.mean[0], grain.albedo[0], 0.01 * grain.albedo[0]);
}

TEST(RockTexture, FieldHasZeroMeanUnitDeviationAndItsGradient) {
  const RockTexture t(rock(8));
  double s = 0.0, s2 = 0.0;
  const auto pts = points(40000, 30.0f, Eigen::Vector3f(100, -50, -200));
  for (const auto& p : pts) {
    const double f = t.field(p);
    s += f;
    s2 += f * f;
  }
  EXPECT_NEAR(s / pts.size(), 0.0, 0.03);
  EXPECT_NEAR(std::sqrt(s2 / pts.size()), 1.0, 0.08);
  // The analytic gradients against central differences of the field and of the height. A crack's centre line (where
  // its noise crosses 0) is a kink, across which a central difference averages two slopes: of the 600 comparisons
  // of each, at most 2 may miss (a point within a step of a crack's centre line; with this seed and sample, one).
  const float step = 2e-4f;
  int field_misses = 0, height_misses = 0;
  for (const auto& p : points(200, 3.0f, Eigen::Vector3f(1, 2, 3))) {
    Eigen::Vector3f gf, gh;
    t.field(p, &gf);
    t.height(p, &gh);
    for (int a = 0; a < 3; ++a) {
      Eigen::Vector3f d = Eigen::Vector3f::Zero();
      d[a] = step;
      const double df = (t.field(p + d) - t.field(p - d)) / (2.0 * step);
      const double dh = (t.height(p + d) - t.height(p - d)) / (2.0 * step);
      field_misses += std::abs(gf[a] - df) > 0.03 * gf.norm() + 0.05;
      height_misses += std::abs(gh[a] - dh) > 0.03 * gh.norm() + 0.002;
    }
  }
  EXPECT_LE(field_misses, 2);
  EXPECT_LE(height_misses, 2);
}

TEST(RockTexture, ReliefTiltsTheNormalByTheHeightsSlope) {
  std::mt19937 gen(3);
  std::normal_distribution<float> g;
  for (double relief : {0.0, 0.3, 1.0}) {
    Material m = rock(9);
    m.relief = relief;
    const RockTexture t(m);
    double rms = 0.0;
    const auto pts = points(500, 5.0f);
    for (const auto& p : pts) {
      const Eigen::Vector3f n = Eigen::Vector3f(g(gen), g(gen), g(gen)).normalized();
      const Eigen::Vector3f s = t.normal(p, n);
      EXPECT_NEAR(s.norm(), 1.0, 1e-5);
      Eigen::Vector3f gh;
      t.height(p, &gh);
      const double slope = (gh - gh.dot(n) * n).norm();  // |grad_t h|
      const double tilt = std::atan2(s.cross(n).norm(), s.dot(n));
      EXPECT_NEAR(std::tan(tilt), relief * slope, 1e-3 + 1e-3 * relief * slope);
      rms += std::tan(tilt) * std::tan(tilt) / pts.size();
    }
    // The height field's RMS slope is about 1, its tangential part sqrt(2/3) of it on random planes.
    if (relief == 0.0)
      EXPECT_EQ(rms, 0.0);
    else
      EXPECT_NEAR(std::sqrt(rms), relief * std::sqrt(2.0 / 3.0), 0.25 * relief);
  }
  const RockTexture t(rock(9));
  double slope2 = 0.0;
  const auto pts = points(20000, 20.0f);
  for (const auto& p : pts) {
    Eigen::Vector3f gh;
    t.height(p, &gh);
    slope2 += gh.squaredNorm() / pts.size();
  }
  EXPECT_NEAR(std::sqrt(slope2), 1.0, 0.15);
}

TEST(RockTexture, RegionsOfAnotherHue) {
  // tint: the means of small patches (0.5 m, of a fine grain alone: ~25^3 grains each) at 400 random places 4 km around
  // vary with relative sd tint |d_k|.
  Material m = rock(12, 0.2);
  m.cracks = m.strata = m.stains = 0.0;
  m.region = 20.0;
  m.tint = 0.15;
  const RockTexture t(m);
  std::vector<Eigen::Array3d> means;
  for (const auto& centre : points(400, 4000.0f, Eigen::Vector3f::Zero(), 5))  // at random places in the cells
    means.push_back(albedoStats(t, points(200, 0.5f, centre)).mean);
  Eigen::Array3d mean = Eigen::Array3d::Zero(), m2 = Eigen::Array3d::Zero();
  for (const auto& x : means) {
    mean += x / means.size();
    m2 += x * x / means.size();
  }
  const Eigen::Array3d rel = (m2 - mean * mean).sqrt() / m.albedo.array();
  // One channel has |d_k| = 1: its relative sd is tint (the patches' own grain averages out).
  EXPECT_NEAR(rel.maxCoeff(), m.tint, 0.2 * m.tint);
  // Without tint the patches differ only by their own texture.
  m.tint = 0.0;
  const RockTexture plain(m);
  EXPECT_LT(std::abs(albedoStats(plain, points(200, 0.5f, {0, 0, 0})).mean[0] -
                     albedoStats(plain, points(200, 0.5f, {500, 0, 0})).mean[0]),
            0.02 * m.albedo[0]);
}

TEST(RockTexture, BadParametersNameTheKey) {
  EXPECT_TRUE(contains(thrownMessage([] { unexmin::sim::materialDefaults("marble", "m."); }), "'m.kind' = 'marble'"));
  Material m = rock(1);
  m.grain = -0.1;
  EXPECT_TRUE(
      contains(thrownMessage([&] { RockTexture t(m, "meshes[0].material."); }), "'meshes[0].material.grain' = -0.1"));
  m = rock(1);
  m.contrast = 1.5;
  EXPECT_TRUE(contains(thrownMessage([&] { RockTexture t(m); }), "'contrast' = 1.5: expected a number in [0, 1]"));
  m = rock(1);
  m.contrast = -0.1;
  EXPECT_TRUE(contains(thrownMessage([&] { RockTexture t(m); }), "'contrast' = -0.1"));
  m = rock(1);
  m.stains = NAN;
  EXPECT_TRUE(contains(thrownMessage([&] { RockTexture t(m); }), "'stains' = nan"));
  m = rock(1);
  m.kind = "granite";
  EXPECT_TRUE(
      contains(thrownMessage([&] { RockTexture t(m); }), "'kind' = 'granite': expected plain|rock|painted|rusty"));
}

namespace {

std::string worldWith(const std::string& name, const std::string& mesh_keys) {
  const std::string dir = unexmin::test::testTempDir();
  std::ofstream(dir + "tri.stl") << "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                    "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
  const std::string path = dir + name;
  std::ofstream(path) << "name: w\nmeshes:\n  - {name: wall, file: tri.stl" << mesh_keys
                      << "}\nrobots:\n  - {name: UX_1}\n";
  return path;
}

std::string configError(const std::string& path) {
  return thrownMessage<unexmin::ConfigError>([&] { unexmin::sim::loadWorldConfig(path); });
}

}  // namespace

TEST(WorldFileMaterial, ReadsTheKindsDefaultsAndTheGivenKeys) {
  const auto w = unexmin::sim::loadWorldConfig(
      worldWith("m.world",
                ", material: {kind: rock, albedo: [0.4, 0.3, 0.2], seed: 17, grain: 0.05, tint: 0.1, "
                "region: 25}"));
  const Material& m = w.meshes.at(0).material;
  EXPECT_EQ(m.kind, "rock");
  EXPECT_EQ(m.seed, 17u);
  EXPECT_DOUBLE_EQ(m.grain, 0.05);
  EXPECT_DOUBLE_EQ(m.cracks, unexmin::sim::materialDefaults("rock").cracks);
  EXPECT_DOUBLE_EQ(m.region, 25.0);
  EXPECT_DOUBLE_EQ(w.meshes[0].albedo.z(), 0.2);  // the mesh's albedo is the material's mean
  // Today's per-mesh albedo is the plain material.
  const auto p = unexmin::sim::loadWorldConfig(worldWith("p.world", ", albedo: [0.5, 0.6, 0.7]"));
  EXPECT_EQ(p.meshes[0].material.kind, "plain");
  EXPECT_DOUBLE_EQ(p.meshes[0].material.albedo.y(), 0.6);
  const unexmin::sensors::vision::SurfaceMaterials sm(p);
  EXPECT_FALSE(sm.textured(0));
  EXPECT_FLOAT_EQ(sm.albedo(0, Eigen::Vector3f(0.3f, 0.2f, 0.0f))[1], 0.6f);
}

TEST(WorldFileMaterial, TextureIsInTheMeshFrame) {
  // The same wall placed elsewhere and turned: the same albedo at the same point of its own frame.
  const auto a = unexmin::sim::loadWorldConfig(worldWith("a.world", ", material: {kind: rock, seed: 2}"));
  const auto b = unexmin::sim::loadWorldConfig(
      worldWith("b.world", ", xyz: [10, -3, 2], rpy: [0.3, -0.2, 1.1], material: {kind: rock, seed: 2}"));
  const unexmin::sensors::vision::SurfaceMaterials ma(a), mb(b);
  const Eigen::Isometry3f pose = b.meshes[0].pose.cast<float>();
  for (const auto& p : points(50, 2.0f))
    EXPECT_NEAR(ma.albedo(0, p)[0], mb.albedo(0, pose * p)[0], 1e-5);
}

TEST(WorldFileMaterial, BadMaterialNamesTheFileAndTheKey) {
  const std::string kind = worldWith("k.world", ", material: {kind: marble}");
  EXPECT_TRUE(contains(configError(kind), kind + ": 'meshes[0].material.kind' = 'marble': expected plain|rock"));
  const std::string scale = worldWith("s.world", ", material: {kind: rock, cracks: -1}");
  EXPECT_TRUE(contains(configError(scale), scale + ": 'meshes[0].material.cracks' = -1"));
  const std::string contrast = worldWith("c.world", ", material: {kind: rock, contrast: 2}");
  EXPECT_TRUE(contains(configError(contrast), contrast + ": 'meshes[0].material.contrast' = 2"));
  const std::string typo = worldWith("t.world", ", material: {kind: rock, grian: 0.1}");
  // Unknown keys are refused by the world schema (config/world_schema.yaml) before the material is read.
  EXPECT_TRUE(contains(configError(typo), "unknown key 'meshes[0].material.grian'"));
  EXPECT_TRUE(contains(configError(typo), "did you mean 'grain'?"));
  const std::string both = worldWith("b2.world", ", albedo: [0.1, 0.1, 0.1], material: {kind: rock}");
  EXPECT_TRUE(contains(configError(both), "'meshes[0].albedo' and 'meshes[0].material' both given"));
  const std::string plain = worldWith("p2.world", ", material: {kind: plain, contrast: 0.3}");
  EXPECT_TRUE(contains(configError(plain), "'meshes[0].material.kind' = 'plain'"));
  const std::string seed = worldWith("s2.world", ", material: {kind: rock, seed: -3}");
  EXPECT_TRUE(contains(configError(seed), "'meshes[0].material.seed' = -3"));
}

TEST(RockTexture, EightLanesEqualOne) {
  // shadeMany in AVX2 lanes against one point at a time: every kind, with tint and relief, 203 points (a tail of 3)
  // within 4 m of the mesh origin: albedo within 2e-5, normals within 2e-4 (seen: 7e-5; the relief's gradients
  // amplify the rounding of FMA and of the lanes' sine).
  if (unexmin::sensors::vision::ImageFormation::simdAvailable())
    EXPECT_TRUE(unexmin::sensors::vision::rockAvx2Built()) << "a CPU with AVX2 and FMA must use the eight lanes";
  std::mt19937 gen(21);
  std::normal_distribution<float> g;
  for (const char* kind : {"rock", "painted", "rusty"}) {
    Material m = unexmin::sim::materialDefaults(kind);
    m.seed = 77;
    m.region = 15.0;
    m.tint = 0.2;
    m.relief = 0.8;
    const RockTexture t(m);
    const auto pts = points(203, 4.0f, Eigen::Vector3f(-3, 1, -2), 4);
    const int n = static_cast<int>(pts.size());
    std::vector<float> x(n), y(n), z(n), nx[2], ny[2], nz[2], a[2][3];
    for (int s = 0; s < 2; ++s) {
      nx[s].resize(n), ny[s].resize(n), nz[s].resize(n);
      for (auto& c : a[s])
        c.resize(n);
    }
    for (int i = 0; i < n; ++i) {
      x[i] = pts[i].x(), y[i] = pts[i].y(), z[i] = pts[i].z();
      const Eigen::Vector3f d = Eigen::Vector3f(g(gen), g(gen), g(gen)).normalized();
      for (int s = 0; s < 2; ++s)
        nx[s][i] = d.x(), ny[s][i] = d.y(), nz[s][i] = d.z();
    }
    for (int s = 0; s < 2; ++s) {
      float* const out[3] = {a[s][0].data(), a[s][1].data(), a[s][2].data()};
      t.shadeMany(n, x.data(), y.data(), z.data(), nx[s].data(), ny[s].data(), nz[s].data(), out, s == 1);
    }
    for (int i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(a[1][c][i], a[0][c][i], 2e-5f) << kind << " point " << i;
      EXPECT_NEAR(nx[1][i], nx[0][i], 2e-4f) << kind << " point " << i;
      EXPECT_NEAR(ny[1][i], ny[0][i], 2e-4f) << kind << " point " << i;
      EXPECT_NEAR(nz[1][i], nz[0][i], 2e-4f) << kind << " point " << i;
      // and one point at a time is shade() itself
      float one[3];
      Eigen::Vector3f s;
      t.shade(pts[i], Eigen::Vector3f(nx[0][i], ny[0][i], nz[0][i]), one, s);
      EXPECT_EQ(one[0], a[0][0][i]);
    }
  }
}

TEST(RockTexture, SlowNoisesAreLinearOverASmallBatch) {
  // shadeMany takes the regions' and the stains' noise as linear about the centre of the batch's bounding box when
  // the box is within 0.04 of their scale on every axis (a tile of a frame: 8 x 8 pixels, 2-3 cm at 2 m). The rest
  // of the field is exact, so against shade() the albedo differs by the second-order remainder of those two noises:
  // with |d2n| <= 24 per lattice unit^2 (smoothstep's 6 times the corners' range of 4; rough bound), a distance from
  // the centre of at most sqrt(3) / 2 x 0.04 scales and the unit noise's 1 / value_sd ~ 3.5:
  // < 0.5 * 24 * 3 * 0.02^2 * 3.5 = 0.05 in the noise, times (tint + contrast weight) in the albedo. Normals: the
  // stains have no relief, but they warp the strata, whose slope then takes the stains' slope as constant over the
  // batch: off by relief * strata height * 2 pi value_sd/2 * (the stains' slope change over half the batch)
  // < 0.34 * 0.04 * 0.9 * 0.5 = 6e-3 rad. A batch spread wider is exact.
  Material m = unexmin::sim::materialDefaults("rock");
  m.seed = 5;
  m.region = 20.0;
  m.tint = 0.2;
  const RockTexture t(m);
  const float side = 0.04f * static_cast<float>(std::min(m.stains, m.region));  // 8 cm: within the guard
  double worst_albedo = 0.0, worst_tilt = 0.0;
  for (int batch = 0; batch < 50; ++batch) {
    const auto pts = points(64, side, Eigen::Vector3f(3.0f * batch, -1.0f, 0.5f * batch), 100 + batch);
    const int n = static_cast<int>(pts.size());
    std::vector<float> x(n), y(n), z(n), nx(n, 0.0f), ny(n, 0.0f), nz(n, 1.0f), a[3];
    for (auto& c : a)
      c.resize(n);
    for (int i = 0; i < n; ++i)
      x[i] = pts[i].x(), y[i] = pts[i].y(), z[i] = pts[i].z();
    float* const out[3] = {a[0].data(), a[1].data(), a[2].data()};
    t.shadeMany(n, x.data(), y.data(), z.data(), nx.data(), ny.data(), nz.data(), out, batch % 2 == 0);
    for (int i = 0; i < n; ++i) {
      float exact[3];
      Eigen::Vector3f s;
      t.shade(pts[i], Eigen::Vector3f::UnitZ(), exact, s);
      for (int c = 0; c < 3; ++c)
        worst_albedo = std::max(worst_albedo, std::abs(a[c][i] - exact[c]) / m.albedo[c]);
      worst_tilt = std::max(
          worst_tilt, static_cast<double>(std::acos(std::min(1.0f, s.dot(Eigen::Vector3f(nx[i], ny[i], nz[i]))))));
    }
  }
  EXPECT_GT(worst_albedo, 0.0);  // the linear path was taken
  EXPECT_LT(worst_albedo, 0.005);
  EXPECT_LT(worst_tilt, 0.006);
  std::printf("slow noises linear over a batch of 8 cm: albedo off by <= %.2g (relative), normal by <= %.2g rad\n",
              worst_albedo, worst_tilt);
}

TEST(RockTexture, ATileGivenInAnotherFrameIsTheMeshFramesTexture) {
  // shadeManyFrom (the camera's path: points and normals in the camera frame, moved into the mesh frame in lanes)
  // against shadeMany one point at a time on the same points in the mesh frame: tiles of 64 points 3 cm across (the
  // cracks' lattice cell is then shared by most groups of eight, which reuse its corners), 4-9 m from the mesh
  // origin. Within the rounding of the transforms (~1e-6 m, times the albedo's slope of < 20 per m) and of the lanes
  // (EightLanesEqualOne): albedo 1e-4, normals 1e-3.
  Material m = unexmin::sim::materialDefaults("rock");
  m.seed = 9;
  m.region = 20.0;
  m.tint = 0.2;
  m.relief = 0.5;
  const RockTexture t(m);
  const Eigen::Matrix3f rotation =
      Eigen::AngleAxisf(0.7f, Eigen::Vector3f(0.3f, -0.5f, 0.8f).normalized()).toRotationMatrix();
  const Eigen::Vector3f translation(2.5f, -4.0f, 6.0f);
  std::mt19937 gen(5);
  std::normal_distribution<float> g;
  double worst_albedo = 0.0, worst_normal = 0.0;
  for (int tile = 0; tile < 40; ++tile) {
    const auto pts = points(64, 0.03f, Eigen::Vector3f(0.13f * tile, -1.0f, 0.071f * tile - 2.0f), 300 + tile);
    constexpr int n = 64;
    float x[3][n], a[3][n], d[3][n], ref[3][n], dref[3][n];
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3f normal = Eigen::Vector3f(g(gen), g(gen), g(gen)).normalized();
      const Eigen::Vector3f pa = rotation.transpose() * (pts[i] - translation), na = rotation.transpose() * normal;
      for (int c = 0; c < 3; ++c) {
        x[c][i] = pa[c], d[c][i] = na[c];
        dref[c][i] = normal[c];
      }
    }
    std::vector<float> mx(n), my(n), mz(n);
    for (int i = 0; i < n; ++i)
      mx[i] = pts[i].x(), my[i] = pts[i].y(), mz[i] = pts[i].z();
    float* const out_ref[3] = {ref[0], ref[1], ref[2]};
    t.shadeMany(n, mx.data(), my.data(), mz.data(), dref[0], dref[1], dref[2], out_ref, false);
    float* const out[3] = {a[0], a[1], a[2]};
    t.shadeManyFrom(rotation, translation, n, x[0], x[1], x[2], d[0], d[1], d[2], out, tile % 4 != 3);
    for (int i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c)
        worst_albedo = std::max(worst_albedo, static_cast<double>(std::abs(a[c][i] - ref[c][i])));
      const Eigen::Vector3f back = rotation * Eigen::Vector3f(d[0][i], d[1][i], d[2][i]);
      worst_normal = std::max(worst_normal,
                              static_cast<double>((back - Eigen::Vector3f(dref[0][i], dref[1][i], dref[2][i])).norm()));
      EXPECT_NEAR(Eigen::Vector3f(d[0][i], d[1][i], d[2][i]).norm(), 1.0f, 1e-5f);
    }
  }
  EXPECT_LT(worst_albedo, 1e-4);
  EXPECT_LT(worst_normal, 1e-3);
  std::printf("a tile in another frame: albedo off by <= %.2g, normal by <= %.2g\n", worst_albedo, worst_normal);
}

TEST(WorldFileMaterial, RockMeshTakesItsColourFromTheGeology) {
  // The same rock wall with and without a geology (a granite host, a malachite-quartz box at x > 1): at every point
  // the albedo with it is the one without times the rock's albedo over the material's, per channel (clamped at 1),
  // through albedo(), shade() and shadeMany(); a plain mesh stays plain.
  const std::string dir = unexmin::test::testTempDir();
  std::ofstream(dir + "tri.stl") << "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                    "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
  const std::string mesh =
      "  - {name: wall, file: tri.stl, material: {kind: rock, albedo: [0.3, 0.25, 0.2], seed: 4}}\n"
      "  - {name: sign, file: tri.stl, albedo: [0.5, 0.5, 0.5]}\n";
  std::ofstream(dir + "plain.world") << "name: w\nmeshes:\n" << mesh << "robots:\n  - {name: UX_1}\n";
  std::ofstream(dir + "geo.world") << "name: w\nmeshes:\n"
                                   << mesh
                                   << "geology:\n  host: [{mineral: granite, fraction: 1.0}]\n  bodies:\n"
                                      "    - {name: stain, kind: box, xyz: [3, 0, 0], size: [4, 10, 10],\n"
                                      "       minerals: [{mineral: malachite, fraction: 0.5}, {mineral: quartz, "
                                      "fraction: 0.5}]}\nrobots:\n  - {name: UX_1}\n";
  const auto plain = unexmin::sim::loadWorldConfig(dir + "plain.world");
  const auto geo = unexmin::sim::loadWorldConfig(dir + "geo.world");
  ASSERT_TRUE(geo.geology);
  const unexmin::sensors::vision::SurfaceMaterials a(plain), b(geo);
  EXPECT_FALSE(a.geological(0));
  EXPECT_TRUE(b.geological(0));
  EXPECT_FALSE(b.geological(1));
  const Eigen::Vector3d material(0.3, 0.25, 0.2);
  const Eigen::Vector3d host = geo.geology->host().albedo, stain = geo.geology->rock(1).albedo;
  EXPECT_GT(stain.y(), stain.x());  // malachite's green
  EXPECT_GT(stain.y(), stain.z());
  const auto pts = points(400, 4.0f, Eigen::Vector3f(1, 0, 0));
  std::vector<float> px, py, pz, nx, ny, nz, out[3];
  int inside = 0;
  for (const auto& p : pts) {
    const Eigen::Vector3d rock = p.x() >= 1.0f ? stain : host;
    inside += p.x() >= 1.0f;
    const Eigen::Array3f without = a.albedo(0, p), with = b.albedo(0, p);
    float shaded[3];
    Eigen::Vector3f normal;
    b.shade(0, p, Eigen::Vector3f::UnitZ(), shaded, normal);
    for (int k = 0; k < 3; ++k) {
      const double expected = std::min(1.0, without[k] * rock[k] / material[k]);
      EXPECT_NEAR(with[k], expected, 1e-5 * std::max(1.0, expected));
      EXPECT_NEAR(shaded[k], expected, 1e-5 * std::max(1.0, expected));
    }
    EXPECT_FLOAT_EQ(b.albedo(1, p)[1], 0.5f);
    px.push_back(p.x() - 2.0f);  // in a frame A at (2, 0, 0) turned by a half turn about z
    py.push_back(p.y());
    pz.push_back(p.z());
    nx.push_back(0.0f);
    ny.push_back(0.0f);
    nz.push_back(1.0f);
  }
  EXPECT_GT(inside, 50);
  EXPECT_LT(inside, 350);
  // shadeMany from a frame A: world = R p_A + t with R a half turn about z and t = (2, 0, 0) gives p = (2 - x_A, -y_A).
  const int n = static_cast<int>(pts.size());
  for (auto& x : px)
    x = -x;
  for (auto& y : py)
    y = -y;
  for (auto& o : out)
    o.resize(pts.size());
  float* const albedo[3] = {out[0].data(), out[1].data(), out[2].data()};
  const Eigen::Matrix3f half = Eigen::AngleAxisf(static_cast<float>(M_PI), Eigen::Vector3f::UnitZ()).toRotationMatrix();
  b.shadeMany(0, half, Eigen::Vector3f(2, 0, 0), n, px.data(), py.data(), pz.data(), nx.data(), ny.data(), nz.data(),
              albedo, false);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3f& p = pts[static_cast<std::size_t>(i)];
    if (std::abs(p.x() - 1.0f) < 1e-3f)
      continue;  // on the face: float rounding of the frame change may put it either side
    float shaded[3];
    Eigen::Vector3f normal;
    b.shade(0, p, Eigen::Vector3f::UnitZ(), shaded, normal);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(out[k][static_cast<std::size_t>(i)], shaded[k], 2e-3f) << "point " << i << " channel " << k;
  }
}

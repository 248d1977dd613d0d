// The camera's shading kernels (cpp/unexmin/sensors/vision/shading_kernels.h): eight AVX2 lanes against one lane
// on the same pixels (random tiles of surfaces around five lights in turbid water, tiles of every size 1..64, so
// that the padding and the lights that reach no pixel of a group are exercised), and one lane against the closed
// form of the direct term for a single LED.
#include <unexmin/sensors/vision/image_formation.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace unexmin {
namespace test {
namespace {

using sensors::vision::CameraModel;
using sensors::vision::ImageFormation;
using sensors::vision::LedLight;
using sensors::vision::PixelBatch;
using sensors::vision::WaterOptics;

constexpr double kDeg = M_PI / 180.0;

CameraModel camera() {
  return CameraModel(160, 120, 100.0, 100.0, 79.5, 59.5, {-0.2, 0.05, 0.001, -0.002, 0.0});
}

/// Five LEDs around the lens, each lighting part of the view: four spread across it and one down-forward, each
/// beam different.
std::vector<LedLight> fiveLights() {
  std::vector<LedLight> lights;
  const double yaw[] = {-60.0, -20.0, 20.0, 60.0};
  for (int k = 0; k < 4; ++k) {
    LedLight l;
    const double a = yaw[k] * kDeg;
    l.position = Eigen::Vector3d(0.25 * std::sin(a), 0.05, 0.25 * std::cos(a));
    l.axis = Eigen::Vector3d(0.6 * std::sin(a), 0.1, std::cos(a) + 0.3).normalized();
    l.intensity = Eigen::Vector3d(1.5 + 0.2 * k, 2.0, 2.5 - 0.1 * k);
    l.cone = (70.0 + 15.0 * k) * kDeg;
    l.exponent = 1.0 + k;
    lights.push_back(l);
  }
  LedLight down;
  down.position = Eigen::Vector3d(0.0, 0.2, 0.1);
  down.axis = Eigen::Vector3d(0.0, 0.8, 0.6).normalized();
  down.cone = 100.0 * kDeg;
  down.exponent = 4.0;
  lights.push_back(down);
  return lights;
}

/// n pixels in groups of 8 around random surface patches (some behind or beside every beam), random normals
/// (some facing away), albedo, shadow masks and a few pixels of open water.
void randomTile(PixelBatch& b, int n, double max_range, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  b.n = n;
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();
  for (int i = 0; i < n; ++i) {
    if (i % 8 == 0) {
      const Eigen::Vector3d d(u01(rng) * 2 - 1, u01(rng) * 2 - 1, u01(rng) * 1.5 - 0.2);
      centre = (d.normalized() * (0.2 + u01(rng) * 0.8 * max_range)).cast<float>();
    }
    const Eigen::Vector3f p = centre + Eigen::Vector3f(u01(rng) - 0.5, u01(rng) - 0.5, u01(rng) - 0.5) * 0.3f;
    const Eigen::Vector3f normal =
        (Eigen::Vector3f(u01(rng) - 0.5, u01(rng) - 0.5, u01(rng) - 0.5) - 0.5f * p.normalized()).normalized();
    const float albedo[3] = {static_cast<float>(u01(rng)), static_cast<float>(u01(rng)), static_cast<float>(u01(rng))};
    const float pu = static_cast<float>(u01(rng) * 170 - 5), pv = static_cast<float>(u01(rng) * 130 - 5);
    if (u01(rng) < 0.05)
      b.setWater(i, pu, pv, static_cast<float>(max_range));
    else
      b.set(i, pu, pv, p.norm(), p, normal, albedo, static_cast<std::uint32_t>(rng()) | 0x3u);
  }
}

TEST(Shading, EightLanesGiveWhatOneLaneGivesForEveryTileSize) {
  if (!ImageFormation::simdAvailable())
    GTEST_SKIP() << "this CPU (or build) has no AVX2 and FMA: one lane only";
  std::mt19937_64 rng(11);
  int compared = 0, lit = 0;
  float worst = 0.0f;
  for (const char* level : {"none", "medium", "high"}) {
    const ImageFormation f(camera(), fiveLights(), WaterOptics::fromVisibility(level, Eigen::Vector3d::Ones()), 6.0);
    ASSERT_EQ(f.activeLights().size(), 5u) << level;
    for (int n = 1; n <= static_cast<int>(raycast::kBlock); ++n) {
      PixelBatch eight, one;
      randomTile(eight, n, f.maxRange(), rng);
      one = eight;
      f.radiance(eight, true);
      f.radiance(one, false);
      for (int i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
          const float a = eight.out[c][i], b = one.out[c][i];
          ASSERT_TRUE(std::isfinite(a)) << level << " n " << n << " pixel " << i;
          // FMA rounds once where one lane rounds twice: 1e-7 relative, up to a few 1e-5 near a beam's edge, where
          // the profile falls to 0 steeply. A wrong lane, node or bin is off by percents.
          ASSERT_NEAR(a, b, 1e-4f * std::abs(b) + 1e-12f) << level << " n " << n << " pixel " << i << " channel " << c;
          worst = std::max(worst, std::abs(a - b) / std::max(std::abs(b), 1e-30f));
          ++compared;
          lit += b > 2.0f * f.backscatter(one.u[i], one.v[i], one.range[i])[c] ? 1 : 0;
        }
    }
  }
  EXPECT_EQ(compared, 3 * 3 * 64 * 65 / 2);
  EXPECT_GT(lit, compared / 10);  // the direct term, not the water alone, is what was compared
  RecordProperty("worst_relative_difference", std::to_string(worst));
  std::printf("worst relative difference, eight lanes vs one: %.3g\n", worst);
}

TEST(Shading, ANonFiniteInputSpoilsItsOwnPixelOnlyAndReadsNothingOutOfBounds) {
  // Every table index is clamped NaN included: a NaN or infinite range, point or coordinate must not make a lane
  // read outside a table (it would crash or read garbage), nor change the other pixels.
  const ImageFormation f(camera(), fiveLights(), WaterOptics::fromVisibility("medium", Eigen::Vector3d::Ones()), 6.0);
  std::mt19937_64 rng(5);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (bool simd : {false, true}) {
    if (simd && !ImageFormation::simdAvailable())
      continue;
    PixelBatch clean;
    randomTile(clean, 24, f.maxRange(), rng);
    for (int bad = 0; bad < 6; ++bad) {
      PixelBatch b = clean, ref = clean;
      const int i = 3 + bad;
      switch (bad) {
        case 0:
          b.range[i] = nan;
          break;
        case 1:
          b.range[i] = inf;
          break;
        case 2:
          b.px[i] = nan;
          break;
        case 3:
          b.u[i] = nan;
          break;
        case 4:
          b.v[i] = -inf;
          break;
        case 5:
          b.nz[i] = nan;
          break;
      }
      f.radiance(b, simd);
      f.radiance(ref, simd);
      for (int k = 0; k < b.n; ++k)
        for (int c = 0; c < 3; ++c)
          if (k != i) {
            EXPECT_EQ(b.out[c][k], ref.out[c][k]) << "simd " << simd << " bad input " << bad << " pixel " << k;
          }
    }
  }
}

TEST(Shading, EightLanesAreBuiltAndUsedWhereTheCpuHasAvx2AndFma) {
  // A build that silently lost shading_avx2.cpp's -mavx2 -mfma would shade one pixel at a time (and the tests
  // comparing the two would skip): on a CPU with both, the eight lanes must be there.
#if defined(__x86_64__) && defined(__GNUC__)
  const bool cpu = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  EXPECT_EQ(ImageFormation::simdAvailable(), cpu) << "CPU has AVX2 and FMA: " << cpu;
#else
  EXPECT_FALSE(ImageFormation::simdAvailable());
#endif
}

TEST(Shading, BackscatterGrowsWithRangeAndIsContinuousAcrossEveryBinEdge) {
  // The table's range bins end at s_j = max_range (j / 64)^2; the lookup finds a range's bin from a rounded square
  // root and steps one bin if that landed wrong. Just below, at and just above every edge, at pixels inside and
  // outside the image, in both lane widths: the glow never decreases with range, and across an edge it changes by
  // no more than a float's rounding of the whole sweep (near a light the glow rises by 1e4 per metre: the steps
  // of one ulp of range are compared with the sweep's largest value, not with their own).
  const double max_range = 6.0;
  const ImageFormation f(camera(), fiveLights(), WaterOptics::fromVisibility("high", Eigen::Vector3d::Ones()),
                         max_range);
  for (bool simd : {false, true}) {
    if (simd && !ImageFormation::simdAvailable())
      continue;
    for (const Eigen::Vector2f& uv :
         {Eigen::Vector2f(80.0f, 60.0f), Eigen::Vector2f(3.3f, 117.9f), Eigen::Vector2f(-20.0f, 200.0f)}) {
      std::vector<std::array<float, 3>> at_edge;  // (below, at, above) per edge
      std::vector<float> sweep;
      for (int j = 1; j <= 64; ++j) {
        const float edge = static_cast<float>(max_range * (j / 64.0) * (j / 64.0));
        PixelBatch b;
        b.n = 3;
        b.setWater(0, uv.x(), uv.y(), std::nextafter(edge, 0.0f));
        b.setWater(1, uv.x(), uv.y(), edge);
        b.setWater(2, uv.x(), uv.y(), std::nextafter(edge, 100.0f));
        f.radiance(b, simd);
        at_edge.push_back({b.out[1][0], b.out[1][1], b.out[1][2]});
        for (int i = 0; i < 3; ++i)
          sweep.push_back(b.out[1][i]);
      }
      const float top = *std::max_element(sweep.begin(), sweep.end());
      ASSERT_GT(top, 0.0f) << "the lights must light the water along this ray";
      for (std::size_t i = 1; i < sweep.size(); ++i)
        ASSERT_GE(sweep[i], sweep[i - 1]) << "simd " << simd << " sample " << i << " (edge " << i / 3 + 1 << ")";
      for (std::size_t e = 0; e < at_edge.size(); ++e) {
        EXPECT_LE(at_edge[e][2] - at_edge[e][0], 1e-6f * top) << "simd " << simd << " edge " << e + 1;
      }
      // Beyond max_range the ray sees open water up to max_range: the same glow.
      EXPECT_EQ(f.backscatter(uv.x(), uv.y(), 50.0f)[1],
                f.backscatter(uv.x(), uv.y(), static_cast<float>(max_range))[1]);
    }
  }
}

TEST(Shading, OneLaneDirectTermMatchesTheClosedFormOfOneLed) {
  LedLight l;
  l.position = Eigen::Vector3d(0.1, -0.05, 0.0);
  l.axis = Eigen::Vector3d(0.0, 0.0, 1.0);
  l.intensity = Eigen::Vector3d(1.0, 2.0, 3.0);
  l.cone = 120.0 * kDeg;
  l.exponent = 3.0;
  const WaterOptics water = WaterOptics::fromVisibility("medium", Eigen::Vector3d::Ones());
  const ImageFormation f(camera(), {l}, water, 10.0);
  const Eigen::Array3f albedo(0.3f, 0.5f, 0.7f);
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0.0, 0.0, 1.5), Eigen::Vector3d(0.4, 0.3, 2.5), Eigen::Vector3d(-0.6, 0.2, 3.0)}) {
    const Eigen::Vector3d n = Eigen::Vector3d(0.2, -0.1, -1.0).normalized();
    const Eigen::Vector3d v = p - l.position;
    const double r = v.norm(), cos_theta = v.z() / r, cos_phi = -n.dot(v) / r;
    const Eigen::Array3f got = f.direct(p.cast<float>(), static_cast<float>(p.norm()), n.cast<float>(), albedo);
    for (int c = 0; c < 3; ++c) {
      const double want = albedo[c] / M_PI * l.intensity[c] * l.profile(cos_theta) * cos_phi *
                          std::exp(-water.c()[c] * (r + p.norm())) / (r * r);
      EXPECT_NEAR(got[c], want, 2e-3 * want) << "point " << p.transpose() << " channel " << c;
    }
    // The light's bit cleared (a shadow): nothing.
    EXPECT_EQ(f.direct(p.cast<float>(), static_cast<float>(p.norm()), n.cast<float>(), albedo, ~1u).matrix().norm(),
              0.0f);
  }
}

}  // namespace
}  // namespace test
}  // namespace unexmin

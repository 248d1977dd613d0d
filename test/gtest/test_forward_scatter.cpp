// Forward scattering (cpp/unexmin/sensors/vision/forward_scatter.h) against closed forms computed here: the forward
// lobe's share of Henyey-Greenstein scattering, the PSF's width sqrt(eta b R <theta^2> / 6) and its zero at b = 0,
// the halo's weight exp(eta b R) - 1, and the blurred image of one bright tile (its power and its spread); the pass
// run on a ray caster's worker threads gives the image it gives on one thread, bit for bit.
#include <unexmin/core/error.h>
#include <unexmin/raycast/ray_caster.h>
#include <unexmin/raycast/ray_caster_factory.h>
#include <unexmin/sensors/vision/forward_scatter.h>
#include "sensor_fixture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace unexmin {
namespace test {
namespace {

using sensors::vision::ForwardScatter;
using sensors::vision::WaterOptics;

const Eigen::Vector3d kColour(0.25, 0.3, 0.2);

/// Share of Henyey-Greenstein scattering (asymmetry g) within angle `lobe` of the forward direction: the phase
/// function's integral over the cap, (1 - g^2) / (2 g) (1 / (1 - g) - 1 / sqrt(1 + g^2 - 2 g cos(lobe))).
double capShare(double g, double lobe) {
  return (1 - g * g) / (2 * g) * (1 / (1 - g) - 1 / std::sqrt(1 + g * g - 2 * g * std::cos(lobe)));
}

/// <theta^2> over the cap by the midpoint rule on a fine grid (independent of the class's Simpson rule).
double capMeanSquare(double g, double lobe) {
  const int n = 200000;
  double s0 = 0, s2 = 0;
  for (int i = 0; i < n; ++i) {
    const double t = (i + 0.5) * lobe / n;
    const double p = (1 - g * g) / (4 * M_PI * std::pow(1 + g * g - 2 * g * std::cos(t), 1.5)) * 2 * M_PI * std::sin(t);
    s0 += p;
    s2 += p * t * t;
  }
  return s2 / s0;
}

TEST(ForwardScatter, TheLobeIsTheHenyeyGreensteinCap) {
  for (const double g : {0.5, 0.8, 0.924}) {
    double eta = 0, m2 = 0;
    ForwardScatter::lobe(g, ForwardScatter::kLobe, eta, m2);
    EXPECT_NEAR(eta, capShare(g, ForwardScatter::kLobe), 1e-6) << "g " << g;
    EXPECT_NEAR(m2, capMeanSquare(g, ForwardScatter::kLobe), 1e-6) << "g " << g;
    EXPECT_LT(m2, ForwardScatter::kLobe * ForwardScatter::kLobe);
  }
  // Petzold's water (g = 0.924): about 61 % of the scattering within 10 degrees.
  double eta = 0, m2 = 0;
  ForwardScatter::lobe(0.924, 10 * M_PI / 180, eta, m2);
  EXPECT_NEAR(eta, 0.611, 0.002);
}

TEST(ForwardScatter, ThePsfWidthFollowsItsFormulaAndVanishesInClearWater) {
  for (const std::string level : {"low", "medium", "high"}) {
    SCOPED_TRACE(level);
    const WaterOptics water = WaterOptics::fromVisibility(level, kColour);
    ASSERT_TRUE(ForwardScatter::needed(water));
    const ForwardScatter fs(water, 10.0, 400.0, 64, 48, 8);
    const double eta = capShare(water.g, ForwardScatter::kLobe), m2 = capMeanSquare(water.g, ForwardScatter::kLobe);
    for (const double r : {0.5, 1.0, 2.0, 4.0}) {
      const double lambda = eta * water.b.y() * r;
      EXPECT_NEAR(fs.scatterings(r)[1], lambda, 1e-6 * lambda);
      EXPECT_NEAR(fs.psfSigma(r), std::sqrt(lambda * m2 / 6), 1e-6);
      EXPECT_NEAR(fs.haloWeight(r)[1], std::exp(lambda) - 1, 1e-6 * std::exp(lambda));
      // The whole PSF's variance is the halo's weight in it times the halo's variance.
      const double h = fs.haloSigma(r);
      EXPECT_NEAR((1 - std::exp(-lambda)) * h * h, fs.psfSigma(r) * fs.psfSigma(r), 1e-9);
    }
    EXPECT_GT(fs.psfSigma(4.0), fs.psfSigma(1.0));  // wider with range
  }
  EXPECT_GT(ForwardScatter(WaterOptics::fromVisibility("high", kColour), 10, 400, 64, 48, 8).psfSigma(2.0),
            ForwardScatter(WaterOptics::fromVisibility("low", kColour), 10, 400, 64, 48, 8).psfSigma(2.0));
  // b -> 0: no scattering, no width, no halo.
  WaterOptics clear = WaterOptics::fromVisibility("none", kColour);
  EXPECT_FALSE(ForwardScatter::needed(clear));
  clear.b.setZero();
  const ForwardScatter none(clear, 10.0, 400.0, 64, 48, 8);
  EXPECT_EQ(none.psfSigma(3.0), 0.0);
  EXPECT_EQ(none.haloWeight(3.0).maxCoeff(), 0.0);
  clear.b.setConstant(1e-4);  // sigma ~ sqrt(b): 0.4 mrad at 3 m
  EXPECT_LT(ForwardScatter(clear, 10.0, 400.0, 64, 48, 8).psfSigma(3.0), 1e-3);
}

TEST(ForwardScatter, OneBrightTileSpreadsItsHaloWithTheBandsWidthAndKeepsItsPower) {
  // A 256 x 256 image, one 8 x 8 tile in the middle with direct light 1 at range r; the rest open water.
  const int size = 256, cell = 8;
  const WaterOptics water = WaterOptics::fromVisibility("medium", kColour);
  const double focal = 400.0, r = 1.5;
  ForwardScatter fs(water, 10.0, focal, size, size, cell);
  fs.clear();
  const int cu = 16, cv = 16;  // the tile's pixels are [128, 136)
  std::vector<float> ones(64, 1.0f), range(64, static_cast<float>(r));
  const float* direct[3] = {ones.data(), ones.data(), ones.data()};
  fs.accumulate(cu, cv, 64, direct, range.data());
  std::vector<float> radiance(3 * size * size, 0.0f);
  fs.apply(radiance);
  double power = 0, mu = 0, mu2 = 0;
  const double centre = cu * cell + 0.5 * (cell - 1);
  for (int v = 0; v < size; ++v)
    for (int u = 0; u < size; ++u) {
      const double x = radiance[3 * (v * size + u) + 1];
      power += x;
      mu += x * (u - centre);
      mu2 += x * (u - centre) * (u - centre);
    }
  // The halo holds exp(lambda) - 1 of the tile's 64 pixels of direct light (table interpolation: 1e-3).
  const double weight = fs.haloWeight(r)[1];
  EXPECT_NEAR(power, 64 * weight, 1e-3 * 64 * weight);
  EXPECT_NEAR(mu / power, 0.0, 0.05);
  // Its spread per axis: the band's Gaussian (sampled at tile centres) plus the tile-to-pixel interpolation (a
  // triangle of half width one cell: variance cell^2 / 6).
  const int band = static_cast<int>(ForwardScatter::kBands * std::sqrt(r / 10.0));
  const double sigma = fs.bandSigmaPixels(band);
  EXPECT_GT(sigma, 8.0);  // the test means something: wider than a cell
  EXPECT_NEAR(std::sqrt(mu2 / power), std::sqrt(sigma * sigma + cell * cell / 6.0), 0.05 * sigma);
  // That width is the formula's at the band's middle range.
  const double mid = 10.0 * std::pow((band + 0.5) / ForwardScatter::kBands, 2);
  EXPECT_NEAR(sigma, fs.haloSigma(mid) * focal, 1e-9);
}

TEST(ForwardScatter, OnTheCastersThreadsTheImageIsTheOneThreadsBitForBit) {
  // An image whose size is a multiple of neither the cell nor the strip, direct light and ranges drawn at random in
  // every tile; the pass applied on the calling thread alone and on a caster's pool of 2 and 3 threads.
  const int width = 203, height = 157, cell = 8;
  const WaterOptics water = WaterOptics::fromVisibility("medium", kColour);
  ForwardScatter fs(water, 20.0, 150.0, width, height, cell);
  fs.clear();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<float> light(0.0f, 0.05f), far(0.3f, 25.0f);
  for (int cv = 0; cv < (height + cell - 1) / cell; ++cv)
    for (int cu = 0; cu < (width + cell - 1) / cell; ++cu) {
      std::vector<float> d[3], range(64);
      for (auto& c : d)
        for (int i = 0; i < 64; ++i)
          c.push_back(light(rng));
      for (auto& r : range)
        r = far(rng);  // some beyond max_range: open water
      const float* direct[3] = {d[0].data(), d[1].data(), d[2].data()};
      fs.accumulate(cu, cv, 64, direct, range.data());
    }
  std::vector<float> base(3 * width * height);
  for (auto& x : base)
    x = light(rng);
  std::vector<float> alone = base;
  fs.apply(alone);
  sim::WorldConfig config = sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/test_box.world");
  std::map<std::string, sim::RobotDescription> d;
  d.emplace(config.robots.at(0).name, sim::parseRobotDescription(sensorUrdf(SphereSpec(), "", ""), "(test robot)"));
  sim::World world(config, d, 1, 0.002, 1);
  for (int threads : {2, 3}) {
    raycast::RayCasterOptions options;
    options.threads = threads;
    const auto pool = raycast::makeRayCaster("embree", world, options);
    std::vector<float> shared = base;
    fs.apply(shared, pool.get());
    EXPECT_EQ(shared, alone) << threads << " threads";
  }
  EXPECT_NE(alone, base);  // the pass added a halo
}

TEST(ForwardScatter, SiltOnTheCameraLegAddsItsForwardScatteringsToTheHalo) {
  // One tile of direct light 1 at range r with x more forward scatterings per pixel (the silt's eta tau): its halo
  // holds exp(lambda + x) - 1 of the direct light, also in water too clear for the pass alone; x = 0 is the water's.
  const int size = 256, cell = 8;  // the tile in the middle, its halo well inside the frame
  const double r = 1.2;
  for (const char* level : {"none", "medium"}) {
    const WaterOptics water = WaterOptics::fromVisibility(level, kColour);
    ForwardScatter fs(water, 10.0, 400.0, size, size, cell);
    for (const float x : {0.0f, 0.3f, 1.5f}) {
      fs.clear();
      std::vector<float> ones(64, 1.0f), range(64, static_cast<float>(r)), extra(64, x);
      const float* direct[3] = {ones.data(), ones.data(), ones.data()};
      fs.accumulate(16, 16, 64, direct, range.data(), extra.data());
      std::vector<float> radiance(3 * size * size, 0.0f);
      fs.apply(radiance);
      double power = 0;
      for (int i = 0; i < size * size; ++i)
        power += radiance[3 * i + 1];
      const double expected = 64 * (std::exp(fs.scatterings(r)[1] + x) - 1.0);
      EXPECT_NEAR(power, expected, 2e-3 * expected + 1e-9) << level << ", x = " << x;
    }
  }
}

TEST(ForwardScatter, BadGeometryIsRefused) {
  const WaterOptics water = WaterOptics::fromVisibility("medium", kColour);
  EXPECT_THROW(ForwardScatter(water, 0.0, 400, 64, 48, 8), ParameterError);
  EXPECT_THROW(ForwardScatter(water, 10.0, -1, 64, 48, 8), ParameterError);
  EXPECT_THROW(ForwardScatter(water, 10.0, 400, 64, 48, 0), ParameterError);
}

}  // namespace
}  // namespace test
}  // namespace unexmin

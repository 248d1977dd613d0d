// mapping::scanPoints against closed forms: beams placed at angle_min + k * angle_increment, the beams without an
// echo (+-inf, NaN, below range_min, above range_max) left out with the limits themselves kept, and coordinates
// rounded to float from double arithmetic.
#include <unexmin/mapping/scan_points.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace unexmin {
namespace mapping {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(ScanPoints, PlacesEachBeamAtItsAngle) {
  const ScanGeometry g{static_cast<float>(-kPi / 2), static_cast<float>(kPi / 4), 0.1f, 30.0f};
  const std::vector<octomap::point3d> p = scanPoints(g, {1.0f, 2.0f, 3.0f, 4.0f, 5.0f});
  ASSERT_EQ(p.size(), 5u);
  const double expected[5][2] = {
      {0, -1}, {std::sqrt(2.0), -std::sqrt(2.0)}, {3, 0}, {2 * std::sqrt(2.0), 2 * std::sqrt(2.0)}, {0, 5}};
  for (int k = 0; k < 5; ++k) {
    EXPECT_NEAR(p[k].x(), expected[k][0], 1e-6) << k;
    EXPECT_NEAR(p[k].y(), expected[k][1], 1e-6) << k;
    EXPECT_EQ(p[k].z(), 0.0f);
  }
}

TEST(ScanPoints, LeavesOutTheBeamsWithoutAnEcho) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const ScanGeometry g{0.0f, 0.5f, 0.5f, 10.0f};
  const std::vector<float> ranges = {inf, -inf, nan, 0.49f, 0.5f, 10.0f, 10.01f, 2.0f};
  const std::vector<octomap::point3d> p = scanPoints(g, ranges);
  ASSERT_EQ(p.size(), 3u);  // beams 4 (range_min), 5 (range_max) and 7
  EXPECT_NEAR(p[0].norm(), 0.5, 1e-6);
  EXPECT_NEAR(std::atan2(p[0].y(), p[0].x()), 2.0, 1e-6);
  EXPECT_NEAR(p[1].norm(), 10.0, 1e-5);
  EXPECT_NEAR(std::atan2(p[1].y(), p[1].x()), 2.5, 1e-6);
  EXPECT_NEAR(std::atan2(p[2].y(), p[2].x()), 3.5 - 2 * kPi, 1e-6);
  EXPECT_TRUE(scanPoints(g, {}).empty());
}

TEST(ScanPoints, ComputesTheAngleInDoubleFromTheFloatFields) {
  // 1000 beams of a fine increment: the angle of beam k is angle_min + k * increment in double, not in float.
  const ScanGeometry g{-2.0f, 0.00123f, 0.0f, 100.0f};
  const std::vector<float> ranges(1000, 50.0f);
  const std::vector<octomap::point3d> p = scanPoints(g, ranges);
  ASSERT_EQ(p.size(), 1000u);
  for (std::size_t k = 0; k < p.size(); k += 37) {
    const double a = static_cast<double>(g.angle_min) + static_cast<double>(k) * static_cast<double>(g.angle_increment);
    EXPECT_EQ(p[k].x(), static_cast<float>(50.0 * std::cos(a))) << k;
    EXPECT_EQ(p[k].y(), static_cast<float>(50.0 * std::sin(a))) << k;
  }
}

}  // namespace
}  // namespace mapping
}  // namespace unexmin

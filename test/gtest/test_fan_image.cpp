// The Cartesian fan image (cpp/unexmin/sensors/sonar/fan_image.h): its size, and every pixel showing the polar
// image's bin and beam of its centre's range and azimuth, computed here from the documented geometry.
#include "expect_error.h"

#include <unexmin/sensors/sonar/fan_image.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace unexmin {
namespace test {
namespace {

using sensors::sonar::FanImage;

TEST(FanImage, EveryPixelShowsTheBinAndBeamOfItsCentre) {
  const std::size_t beams = 64, bins = 50;
  const double fov = 130.0 * M_PI / 180.0, r0 = 0.5, r1 = 10.0;
  const FanImage fan(beams, fov, bins, r0, r1, 40);
  const double s = r1 / 40.0;
  EXPECT_DOUBLE_EQ(fan.pixelSize(), s);
  EXPECT_EQ(fan.width(), 2 * static_cast<int>(std::ceil(r1 * std::sin(fov / 2.0) / s)));  // 2 x 37
  int inside = 0;
  for (int row = 0; row < fan.height(); ++row) {
    for (int col = 0; col < fan.width(); ++col) {
      const double x = (fan.height() - row - 0.5) * s, y = (fan.width() / 2.0 - col - 0.5) * s;
      const double r = std::hypot(x, y), a = std::atan2(y, x);
      const double k = std::floor((fov / 2.0 - a) / (fov / beams)), i = std::floor((r - r0) / ((r1 - r0) / bins));
      const bool in = k >= 0 && k < beams && i >= 0 && i < bins;
      inside += in;
      EXPECT_EQ(fan.source(row, col), in ? static_cast<long>(i * beams + k) : -1L) << row << ", " << col;
    }
  }
  // About the fan's area over a pixel's: (fov / 2) (r1^2 - r0^2) / s^2.
  EXPECT_NEAR(inside, fov / 2.0 * (r1 * r1 - r0 * r0) / (s * s), 0.05 * inside);
  // Port is on the left: the top-left pixel inside the fan shows beam 0's side.
  std::vector<std::uint8_t> polar(bins * beams, 0), out;
  for (std::size_t i = 0; i < bins; ++i)
    polar[i * beams] = 200;  // beam 0 lit
  fan.render(polar, out);
  ASSERT_EQ(out.size(), static_cast<std::size_t>(fan.width() * fan.height()));
  int left = 0, right = 0;
  for (int row = 0; row < fan.height(); ++row)
    for (int col = 0; col < fan.width(); ++col)
      if (out[row * fan.width() + col] == 200)
        (col < fan.width() / 2 ? left : right)++;
  EXPECT_GT(left, 0);
  EXPECT_EQ(right, 0);
}

TEST(FanImage, BadFiguresAreNamed) {
  EXPECT_TRUE(contains(thrownMessage([] { FanImage(64, 4.0, 10, 0.0, 1.0, 10); }), "fov_h"));
  EXPECT_TRUE(contains(thrownMessage([] { FanImage(64, 1.0, 10, 2.0, 1.0, 10); }), "range_max"));
  EXPECT_TRUE(contains(thrownMessage([] { FanImage(0, 1.0, 10, 0.0, 1.0, 10); }), "beams"));
}

}  // namespace
}  // namespace test
}  // namespace unexmin

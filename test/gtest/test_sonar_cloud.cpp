// The imaging sonar's point cloud (cpp/unexmin/sensors/sonar/sonar_cloud.h): on a polar image written by the test,
// the noise floor is each row's median and each beam's point is its first bin at the threshold, at the beam's
// bearing and elevation 0; on a ping of a wall across the fan at a known distance, the points lie on the wall.
#include "expect_error.h"
#include "sonar_image_fixture.h"

#include <unexmin/sensors/sonar/sonar_cloud.h>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace unexmin {
namespace test {
namespace {

using sensors::sonar::PolarImage;
using sensors::sonar::SonarCloud;

/// 8 beams from +35 to -35 deg, 20 bins at 1 + 0.5 i m; step 0.5 dB, threshold 6 dB = 12 codes.
struct Small {
  std::vector<double> azimuths, ranges;
  PolarImage image;
  Small() {
    for (int k = 0; k < 8; ++k)
      azimuths.push_back((35.0 - 10.0 * k) * kDegree);
    for (int i = 0; i < 20; ++i)
      ranges.push_back(1.0 + 0.5 * i);
    image.beams = 8;
    image.bins = 20;
    image.codes.assign(160, 0);
    // the noise floor rising with range as the time-varied gain raises the noise: row i at code 2 i, three of the
    // eight beams one code above it (the median is still 2 i)
    for (std::size_t i = 0; i < 20; ++i)
      for (std::size_t k = 0; k < 8; ++k)
        image.codes[i * 8 + k] = static_cast<std::uint8_t>(2 * i + (k % 3 == 0 ? 1 : 0));
  }
  void set(std::size_t bin, std::size_t beam, int code) {
    image.codes[bin * 8 + beam] = static_cast<std::uint8_t>(code);
  }
};

TEST(SonarCloud, EachBeamGivesItsFirstBinAtTheThresholdAboveItsRowsMedianAtItsBearing) {
  Small s;
  s.set(7, 3, 14 + 12);  // exactly at the threshold: detected
  s.set(5, 5, 10 + 11);  // one code short: not detected ...
  s.set(9, 5, 18 + 40);  // ... so beam 5's point is this later bin
  s.set(4, 6, 8 + 30);   // two echoes in beam 6: the first one
  s.set(12, 6, 24 + 60);
  SonarCloud cloud(s.azimuths, s.ranges, 0.5, 6.0);
  EXPECT_EQ(cloud.thresholdCodes(), 12);
  const auto& points = cloud.build(s.image);
  for (std::size_t i = 0; i < 20; ++i)
    EXPECT_EQ(cloud.floor()[i], 2 * i) << "row " << i;
  ASSERT_EQ(points.size(), 3u);
  const std::size_t beams[] = {3, 5, 6}, bins[] = {7, 9, 4};
  for (std::size_t n = 0; n < 3; ++n) {
    EXPECT_EQ(points[n].beam, beams[n]);
    EXPECT_EQ(points[n].bin, bins[n]);
    const double r = 1.0 + 0.5 * bins[n], a = (35.0 - 10.0 * beams[n]) * kDegree;
    EXPECT_NEAR(points[n].xyz.x(), r * std::cos(a), 1e-5);
    EXPECT_NEAR(points[n].xyz.y(), r * std::sin(a), 1e-5);
    EXPECT_EQ(points[n].xyz.z(), 0.0f);
  }
  EXPECT_EQ(points[1].code, 58);
}

TEST(SonarCloud, BadGeometryThresholdOrImageSizeAreRefusedNamingThem) {
  Small s;
  EXPECT_TRUE(contains(thrownMessage([&] { SonarCloud(s.azimuths, s.ranges, 0.5, 0.0); }), "threshold 0 dB"));
  EXPECT_TRUE(contains(thrownMessage([&] { SonarCloud(s.azimuths, s.ranges, 0.0, 6.0); }), "code step 0 dB"));
  EXPECT_TRUE(contains(thrownMessage([&] { SonarCloud({}, s.ranges, 0.5, 6.0); }), "0 beams x 20 bins"));
  SonarCloud cloud(s.azimuths, s.ranges, 0.5, 6.0);
  s.image.bins = 19;
  EXPECT_TRUE(contains(thrownMessage([&] { cloud.build(s.image); }), "image of 19 bins x 8 beams: expected 20 x 8"));
}

TEST(SonarCloud, APingOfAWallAcrossTheFanPutsEveryBeamsPointOnTheWall) {
  // A wall 6 m ahead (x = 6 m from the sonar), 40 m wide and high; receiver noise, speckle and noise floor on.
  const double D = 6.0;
  const Eigen::Vector3d at(0, 0, -50);
  auto w = sonarRig({{"wall", box(at + Eigen::Vector3d(D, -20, -20), at + Eigen::Vector3d(D + 1, 20, 20))}}, at,
                    Eigen::Vector3d::Zero(), "imaging_sonar", 10.0, {}, 7);
  auto& sonar = w->sensor<sensors::sonar::ImagingSonarSensor>("sonar");
  w->samples(sonar, 1);
  SonarCloud cloud(sonar, 15.0);
  const auto& points = cloud.build(sonar.last());
  // The wall fills every beam within atan(20 / 6) = 73 deg; the beam's first echo comes from its side nearest the
  // wall's normal, at D / cos(|a| - w/2) (w = 130/512 deg the beam width), within one bin and the spread of one
  // ray's footprint.
  const double half_width = 0.5 * 130.0 / 512.0 * kDegree;
  std::size_t on_wall = 0, inside = 0;
  for (std::size_t k = 0; k < sonar.beams(); ++k)
    inside += std::abs(sonar.azimuth(k)) < 60.0 * kDegree;
  for (const auto& p : points) {
    const double a = sonar.azimuth(p.beam);
    EXPECT_EQ(p.xyz.z(), 0.0f);
    EXPECT_NEAR(std::atan2(p.xyz.y(), p.xyz.x()), a, 1e-6);
    if (std::abs(a) >= 60.0 * kDegree)
      continue;
    const double expected = D / std::cos(std::max(0.0, std::abs(a) - half_width));
    const double r = p.xyz.cast<double>().norm();
    on_wall += std::abs(r - expected) <= 2.0 * sonar.rangeResolution() + expected * std::tan(half_width);
  }
  EXPECT_GE(on_wall, static_cast<std::size_t>(0.97 * static_cast<double>(inside))) << points.size() << " points";
}

}  // namespace
}  // namespace test
}  // namespace unexmin

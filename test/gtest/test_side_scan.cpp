// The side-scan sonar (cpp/unexmin/sensors/sonar/side_scan_sensor.h) against closed forms: the nadir gap at the
// slant range of the fan's steepest ray over a flat floor (the altitude itself for a fan reaching the vertical), the
// acoustic shadow of a box on the floor by similar triangles, the walls of a box of cold fresh water 1500 / c farther
// (the echoes timed at its sound speed), the waterfall's layout, seeded lines, pings built only on
// demand, parameter errors.
#include "expect_error.h"
#include "sonar_image_fixture.h"

#include <unexmin/sensors/sonar/waterfall.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

namespace unexmin {
namespace test {
namespace {

using sensors::sonar::SideScanSensor;

const Eigen::Vector3d kAt(0, 0, -50);

SideScanSensor& sonar(SonarWorld& w) {
  return w.sensor<SideScanSensor>("sonar");
}

int firstEcho(const std::vector<std::uint8_t>& line) {
  return static_cast<int>(std::find_if(line.begin(), line.end(), [](std::uint8_t q) { return q > 0; }) - line.begin());
}

TEST(SideScan, TheNadirGapIsTheSlantRangeOfTheSteepestRayAndTheAltitudeForAFanReachingTheVertical) {
  const double H = 5.0;
  // tilt 60 deg + fov_v / 2 = 30 deg: the steepest ray (half a ray spacing from it) points straight down.
  for (const double tilt : {60.0, 30.0}) {
    const double steepest = (tilt + 30.0 - 0.5 * 60.0 / 256.0) * kDegree;
    auto w = sonarRig({{"floor", floorBelow(kAt, H)}}, kAt, Eigen::Vector3d::Zero(), "side_scan", 10.0,
                      {{"noise", "none"}, {"tilt", std::to_string(tilt * kDegree)}});
    const SideScanSensor& s = sonar(*w);
    w->samples(s, 1);
    const double gap = H / std::sin(steepest);
    if (tilt == 60.0) {
      EXPECT_NEAR(gap, H, 1e-4);
    }
    for (const auto* line : {&s.last().port, &s.last().starboard}) {
      ASSERT_EQ(line->size(), 1000u);
      const int first = firstEcho(*line);
      ASSERT_LT(first, 1000) << "tilt " << tilt << ": no echo";
      // The first echo's bin holds the gap; half the steepest ray's footprint (r dphi / tan(steepest)) may reach
      // before it.
      const double footprint = gap * (60.0 * kDegree / 256.0) / std::tan(steepest);
      EXPECT_NEAR(s.binCenter(first), gap, 0.5 * footprint + s.rangeResolution()) << "tilt " << tilt;
      // The floor from there on to where the shallowest ray meets it.
      const double farthest = H / std::sin((tilt - 30.0 + 0.5 * 60.0 / 256.0) * kDegree);
      for (int i = first; i < 1000 && s.binCenter(i) < std::min(farthest, s.rangeMax()) - 0.5; ++i)
        EXPECT_GT((*line)[i], 0) << "tilt " << tilt << " bin " << i;
    }
  }
}

TEST(SideScan, AnObjectOnTheFloorCastsTheShadowOfSimilarTriangles) {
  // 5 m above the floor; a box 1 m high, 0.5 m wide across-track, 40 m long, 12 m to port.
  const double H = 5.0, d = 12.0, t = 0.5, h = 1.0;
  const double floor_z = kAt.z() - H;
  const Geometry object = box(Eigen::Vector3d(-20.0, d, floor_z), Eigen::Vector3d(20.0, d + t, floor_z + h));
  auto w = sonarRig({{"floor", floorBelow(kAt, H)}, {"object", object}}, kAt, Eigen::Vector3d::Zero(), "side_scan",
                    10.0, {{"noise", "none"}, {"rays", "1024"}});
  const SideScanSensor& s = sonar(*w);
  w->samples(s, 1);
  const Shadow expected = boxShadow(H, d, t, h);
  const auto gap = longestGap(s.last().port);
  ASSERT_GE(gap.first, 0);
  const double grazing = std::asin(H / expected.end);
  const double footprint = expected.end * (60.0 * kDegree / 1024.0) / std::tan(grazing);
  EXPECT_NEAR(s.binCenter(gap.first - 1), expected.start, 1.5 * s.rangeResolution());
  EXPECT_NEAR(s.binCenter(gap.second + 1), expected.end, 0.5 * footprint + 1.5 * s.rangeResolution());
  // Starboard: the bare floor, no gap after the nadir gap up to where the shallowest ray meets it.
  const auto other = longestGap(s.last().starboard);
  EXPECT_EQ(other.first, -1) << "a gap to starboard at " << s.binCenter(other.first) << " m";
}

TEST(SideScan, TheWaterfallStacksThePingsNewestFirstPortReversed) {
  auto w = sonarRig({{"floor", floorBelow(kAt, 5.0)}}, kAt, Eigen::Vector3d::Zero(), "side_scan", 10.0,
                    {{"nbins", "200"}, {"waterfall_lines", "3"}});
  const SideScanSensor& s = sonar(*w);
  std::vector<std::vector<std::uint8_t>> port, starboard;
  for (int n = 0; n < 4; ++n) {
    w->samples(s, 1);
    port.push_back(s.last().port);
    starboard.push_back(s.last().starboard);
  }
  std::vector<std::uint8_t> image;
  s.waterfall().image(image);
  ASSERT_EQ(image.size(), 3u * 400u);
  for (std::size_t row = 0; row < 3; ++row) {
    const std::size_t n = 3 - row;  // row 0: the latest ping
    for (std::size_t i = 0; i < 200; ++i) {
      ASSERT_EQ(image[row * 400 + 199 - i], port[n][i]) << "row " << row << " port bin " << i;
      ASSERT_EQ(image[row * 400 + 200 + i], starboard[n][i]) << "row " << row << " starboard bin " << i;
    }
  }
  EXPECT_FALSE(port[3] == port[2]);  // speckle and noise differ from ping to ping
  sensors::sonar::Waterfall fresh(2, 3);
  fresh.image(image);
  EXPECT_EQ(image, std::vector<std::uint8_t>(12, 0));  // nothing yet: zeros
}

TEST(SideScan, LinesRepeatWithTheSeed) {
  const auto lines = [](std::uint64_t seed) {
    auto w = sonarRig({{"floor", floorBelow(kAt, 5.0)}}, kAt, Eigen::Vector3d::Zero(), "side_scan", 10.0, {}, seed);
    w->samples(sonar(*w), 2);
    return std::make_pair(sonar(*w).last().port, sonar(*w).last().starboard);
  };
  EXPECT_TRUE(lines(3) == lines(3));
  EXPECT_FALSE(lines(3) == lines(4));
}

TEST(SideScan, APingNotWantedIsNotBuiltLeavesABlankWaterfallRowAndTheNextDoesNotDependOnIt) {
  // Three pings, the second wanted or not: the third's lines are the same either way; the waterfall's middle row is
  // the second ping's lines when it was built and zeros when it was not.
  const auto run = [](bool second_wanted) {
    auto w = sonarRig({{"floor", floorBelow(kAt, 5.0)}}, kAt, Eigen::Vector3d::Zero(), "side_scan", 10.0,
                      {{"nbins", "200"}, {"waterfall_lines", "3"}}, 5);
    SideScanSensor& s = sonar(*w);
    bool wanted = true;
    s.setDemand([&wanted] { return wanted; });
    w->samples(s, 1);
    EXPECT_TRUE(s.last().built);
    wanted = second_wanted;
    w->samples(s, 1);
    EXPECT_EQ(s.last().built, second_wanted);
    wanted = true;
    w->samples(s, 1);
    EXPECT_TRUE(s.last().built);
    std::vector<std::uint8_t> image;
    s.waterfall().image(image);
    return std::make_pair(s.last().port, image);
  };
  const auto built = run(true), skipped = run(false);
  EXPECT_TRUE(built.first == skipped.first);
  ASSERT_EQ(built.second.size(), 3u * 400u);
  const auto row = [](const std::vector<std::uint8_t>& image, std::size_t r) {
    return std::vector<std::uint8_t>(image.begin() + r * 400, image.begin() + (r + 1) * 400);
  };
  EXPECT_TRUE(row(built.second, 0) == row(skipped.second, 0));  // the third ping
  EXPECT_TRUE(row(built.second, 2) == row(skipped.second, 2));  // the first
  EXPECT_EQ(row(skipped.second, 1), std::vector<std::uint8_t>(400, 0));
  EXPECT_GT(std::count_if(built.second.begin() + 400, built.second.begin() + 800, [](std::uint8_t q) { return q > 0; }),
            100);  // the floor's echoes
}

TEST(SideScan, InColdFreshWaterASonarSetToFifteenHundredPlacesTheWallsLong) {
  // The 4 m box (walls at +-2 m, floor at -2 m) filled with fresh water at 8 degC (sound at ~1441 m/s there), the
  // sonar level at its centre, 300 bins over 0.1..3 m (9.7 mm): a sonar that turns echo times into ranges at 1500 m/s
  // puts each side's first echo at 1500 / c times the nearest wall of its rays (about 4 %: 8 bins farther); set to the
  // water's own speed, at the wall. Ray j of a side at depression tilt + fov_v/2 - (j + 1/2) fov_v / rays below the
  // horizontal, across the track: port (0, cos, -sin), starboard (0, -cos, -sin) (the defaults 30 deg, 60 deg, 256).
  sim::WorldConfig box = sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/test_box.world");
  fillWithFreshWater(box, 8.0);
  const double c = freshWaterSoundSpeed(box, 8.0, box.robots.at(0).pose.translation());
  ASSERT_NEAR(c, 1439.1 + 0.0163 * 100.0, 0.3);  // Chen & Millero's pure water plus ~0.016 m/s per dbar
  for (const double assumed : {1500.0, c}) {
    std::map<std::string, std::string> params = {{"noise", "none"}, {"range_max", "3"}, {"nbins", "300"}};
    if (assumed != 1500.0)
      params["sound_speed"] = num(assumed);  // else the default
    SonarWorld w(box,
                 sensorUrdf(SphereSpec(), mountLink("T/sonar_link", Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()),
                            sensorXml("sonar", "side_scan", "T/sonar_link", 10.0, params)));
    const SideScanSensor& s = sonar(w);
    w.samples(s, 1);
    const Eigen::Isometry3d pose = w.robot().state().pose;  // the sonar link's
    ASSERT_NEAR(freshWaterSoundSpeed(box, 8.0, pose.translation()), c, 0.01);
    ASSERT_NEAR(s.rangeResolution(), 2.9 / 300, 1e-12);
    for (const double side : {1.0, -1.0}) {  // port, starboard
      double truth = INFINITY;
      for (int j = 0; j < 256; ++j) {
        const double depression = (30.0 + 30.0 - (j + 0.5) * 60.0 / 256.0) * kDegree;
        const Eigen::Vector3d d =
            pose.linear() * Eigen::Vector3d(0.0, side * std::cos(depression), -std::sin(depression));
        for (int axis = 0; axis < 3; ++axis)
          if (std::abs(d[axis]) > 1e-12)
            truth = std::min(truth, ((d[axis] > 0 ? 2.0 : -2.0) - pose.translation()[axis]) / d[axis]);
      }
      const auto& line = side > 0 ? s.last().port : s.last().starboard;
      const int first = firstEcho(line);
      ASSERT_LT(first, 300) << "side " << side << ": no echo";
      EXPECT_NEAR(s.binCenter(first), truth * assumed / c, s.rangeResolution())
          << "sound_speed " << assumed << " side " << side << " truth " << truth << " m";
      if (assumed == 1500.0) {
        EXPECT_GT(s.binCenter(first) - truth, 5.0 * s.rangeResolution());  // a model that ignores it fails
      }
    }
  }
}

TEST(SideScan, BadParametersNameTheSensorAndTheParameter) {
  const auto build = [](double rate, const std::map<std::string, std::string>& params) {
    sonarRig({}, kAt, Eigen::Vector3d::Zero(), "side_scan", rate, params);
  };
  std::string m = thrownMessage<ConfigError>([&] { build(10.0, {{"range_max", "100"}}); });  // 7.5 Hz at most
  EXPECT_TRUE(contains(m, "sensor 'sonar'") && contains(m, "'rate'") && contains(m, "7.5")) << m;
  m = thrownMessage<ConfigError>([&] { build(10.0, {{"tilt", "2"}}); });
  EXPECT_TRUE(contains(m, "'tilt'")) << m;
  m = thrownMessage<ConfigError>([&] { build(10.0, {{"rays", "0"}}); });
  EXPECT_TRUE(contains(m, "'rays'")) << m;
}

}  // namespace
}  // namespace test
}  // namespace unexmin

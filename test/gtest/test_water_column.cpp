// The water column (water/water_column.h) and its world-file keys (docs/worlds.md, "Water column"): interpolation
// between rows, layers and steps, regions, the heaving boundary, the derived density and sound speed, and every
// refusal naming the file and the key.
#include <unexmin/sim/world_config.h>
#include <unexmin/water/seawater.h>
#include <unexmin/water/water_column.h>
#include "expect_error.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

using unexmin::ConfigError;
namespace sim = unexmin::sim;
namespace water = unexmin::water;

namespace {

const std::string kSchema = std::string(UNEXMIN_SOURCE_DIR) + "/config/world_schema.yaml";

/// A world file whose `water:` map is `water` (and `extra` at the top level), written to <temp>/`name`.
std::string writeWorld(const std::string& name, const std::string& water, const std::string& extra = "") {
  const std::string path = unexmin::test::testTempDir() + name;
  std::ofstream(path) << "name: w\n" << extra << "water:\n" << water << "robots:\n  - {name: UX_1, xyz: [0, 0, -1]}\n";
  return path;
}

std::string refusal(const std::string& water, const std::string& extra = "") {
  const std::string path = writeWorld("bad.world", water, extra);
  return unexmin::test::thrownMessage<ConfigError>([&] { sim::loadWorldConfig(path, kSchema); });
}

const std::string kTwoLayers =
    "  surface_z: 2.0\n"
    "  profile:\n"
    "    - {depth: 0, temperature: 12, conductivity: 400, ph: 7.5, redox: 300, oxygen: 9, turbidity: 1}\n"
    "    - {depth: 20, temperature: 10, conductivity: 600, ph: 6.5, redox: 100, oxygen: 5, turbidity: 3}\n"
    "    - {depth: 20, temperature: 16, conductivity: 9000, ph: 4.0, redox: -50, oxygen: 0.5, turbidity: 20}\n"
    "    - {depth: 60, temperature: 18, conductivity: 9500, ph: 3.5, redox: -100, oxygen: 0, turbidity: 30}\n";

water::Profile rows(std::initializer_list<std::pair<double, double>> depth_temperature) {
  water::Profile p;
  for (const auto& dt : depth_temperature) {
    water::WaterRow r;
    r.depth = dt.first;
    r.temperature = dt.second;
    p.rows.push_back(r);
  }
  return p;
}

}  // namespace

TEST(WaterColumn, InterpolatesLinearlyBetweenRowsAndStepsAtARepeatedDepth) {
  const sim::WorldConfig w = sim::loadWorldConfig(writeWorld("two.world", kTwoLayers), kSchema);
  ASSERT_TRUE(w.water_column);
  const water::WaterColumn& c = *w.water_column;
  // depth 5 below the surface at z = 2: a quarter of the way from row 0 to row 1
  const water::WaterSample s = c.at(Eigen::Vector3d(3, -4, 2.0 - 5.0), 0.0);
  EXPECT_NEAR(s.depth, 5.0, 1e-12);
  EXPECT_NEAR(s.temperature, 11.5, 1e-12);
  EXPECT_NEAR(s.conductivity, 450.0, 1e-9);
  EXPECT_NEAR(s.ph, 7.25, 1e-12);
  EXPECT_NEAR(s.redox, 250.0, 1e-9);
  EXPECT_NEAR(s.oxygen, 8.0, 1e-12);
  EXPECT_NEAR(s.turbidity, 1.5, 1e-12);
  // derived from the same water by the equations
  EXPECT_NEAR(s.salinity, water::practicalSalinity(450.0, 11.5, s.pressure), 1e-12);
  EXPECT_NEAR(s.density, water::density(s.salinity, 11.5, s.pressure), 1e-12);
  EXPECT_NEAR(s.sound_speed, water::soundSpeed(s.salinity, 11.5, s.pressure), 1e-12);
  EXPECT_NEAR(s.pressure, 1e-4 * 1000.0 * 9.81 * 5.0, 1e-12);
  // the chemocline at 20 m is a step: just above it the upper water, just below it the lower
  const water::WaterSample above = c.at(Eigen::Vector3d(0, 0, 2.0 - 19.999), 0.0);
  const water::WaterSample below = c.at(Eigen::Vector3d(0, 0, 2.0 - 20.001), 0.0);
  EXPECT_NEAR(above.ph, 6.5, 1e-3);
  EXPECT_NEAR(below.ph, 4.0, 1e-3);
  EXPECT_GT(below.density - above.density, 3.0);  // ~9000 uS/cm of salt outweighs 6 degC of warmth
  // above the surface the first row, below the last row the last
  EXPECT_NEAR(c.at(Eigen::Vector3d(0, 0, 10.0), 0.0).temperature, 12.0, 1e-12);
  EXPECT_NEAR(c.at(Eigen::Vector3d(0, 0, -500.0), 0.0).temperature, 18.0, 1e-12);
  // the density the rest of the world reads is the surface's
  EXPECT_NEAR(w.water_density, c.at(Eigen::Vector3d(0, 0, 2.0), 0.0).density, 1e-12);
  EXPECT_NEAR(c.densityAt(Eigen::Vector3d(0, 0, -30), 0.0), c.at(Eigen::Vector3d(0, 0, -30), 0.0).density, 1e-12);
  EXPECT_NEAR(c.soundSpeedAt(Eigen::Vector3d(0, 0, -30), 0.0), c.at(Eigen::Vector3d(0, 0, -30), 0.0).sound_speed,
              1e-12);
}

TEST(WaterColumn, LayersHoldEachRowDownToTheNext) {
  water::Profile p = rows({{0, 12}, {10, 8}, {30, 6}});
  p.layers = true;
  water::checkProfile(p, "water.profile");
  const water::WaterColumn c(p, {}, 0.0, 9.81);
  EXPECT_EQ(c.at(Eigen::Vector3d(0, 0, -9.99), 0).temperature, 12.0);
  EXPECT_EQ(c.at(Eigen::Vector3d(0, 0, -10.0), 0).temperature, 8.0);
  EXPECT_EQ(c.at(Eigen::Vector3d(0, 0, -29.0), 0).temperature, 8.0);
  EXPECT_EQ(c.at(Eigen::Vector3d(0, 0, -31.0), 0).temperature, 6.0);
  // salinity given (default 0): conductivity derived, back to the same salinity
  const water::WaterSample s = c.at(Eigen::Vector3d(0, 0, -5), 0);
  EXPECT_EQ(s.salinity, 0.0);
  EXPECT_EQ(s.conductivity, 0.0);
}

TEST(WaterColumn, TheLastRegionContainingThePointWins) {
  water::Region a, b;
  a.box = Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, -50), Eigen::Vector3d(10, 10, 0));
  a.profile = rows({{0, 20}});
  b.box = Eigen::AlignedBox3d(Eigen::Vector3d(5, 5, -50), Eigen::Vector3d(20, 20, 0));
  b.profile = rows({{0, 30}});
  const water::WaterColumn c(rows({{0, 4}}), {a, b}, 0.0, 9.81);
  EXPECT_EQ(c.at(Eigen::Vector3d(-1, -1, -1), 0).temperature, 4.0);
  EXPECT_EQ(c.at(Eigen::Vector3d(1, 1, -1), 0).temperature, 20.0);
  EXPECT_EQ(c.at(Eigen::Vector3d(7, 7, -1), 0).temperature, 30.0);  // in both: the later
  EXPECT_EQ(c.at(Eigen::Vector3d(15, 15, -1), 0).temperature, 30.0);
}

TEST(WaterColumn, TheBoundaryHeavesAndTheLayersStretch) {
  // a linear temperature profile 10 -> 20 degC over 0..100 m, its boundary at 40 m heaving by 5 m every 600 s
  water::Profile p = rows({{0, 10}, {100, 20}});
  p.boundary.enabled = true;
  p.boundary.depth = 40.0;
  p.boundary.amplitude = 5.0;
  p.boundary.period = 600.0;
  water::checkProfile(p, "water.profile");
  const water::WaterColumn c(p, {}, 0.0, 9.81);
  const double t_down = 150.0;  // a quarter period: the boundary at 45 m
  // the rest-depth-40 water (14 degC) is at 45 m; the mapping is linear on either side of it
  EXPECT_NEAR(c.at(Eigen::Vector3d(0, 0, -45.0), t_down).temperature, 14.0, 1e-12);
  EXPECT_NEAR(water::WaterColumn::restDepth(p, 22.5, t_down), 20.0, 1e-12);
  EXPECT_NEAR(water::WaterColumn::restDepth(p, 45.0 + 27.5, t_down), 70.0, 1e-12);
  // fixed at the surface and at the last row; half a period later the boundary is at 35 m
  EXPECT_NEAR(c.at(Eigen::Vector3d(0, 0, 0.0), t_down).temperature, 10.0, 1e-12);
  EXPECT_NEAR(c.at(Eigen::Vector3d(0, 0, -100.0), t_down).temperature, 20.0, 1e-12);
  EXPECT_NEAR(c.at(Eigen::Vector3d(0, 0, -35.0), 450.0).temperature, 14.0, 1e-12);
  EXPECT_NEAR(c.at(Eigen::Vector3d(0, 0, -40.0), 0.0).temperature, 14.0, 1e-12);  // at rest at t = 0 (phase 0)
  // a probe held at 42 m sees the temperature swing as the boundary passes it
  double lo = 1e9, hi = -1e9;
  for (double t = 0.0; t < 600.0; t += 5.0) {
    const double x = c.at(Eigen::Vector3d(0, 0, -42.0), t).temperature;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  EXPECT_NEAR(lo, 10.0 + 0.1 * (42.0 * 40.0 / 45.0), 1e-3);                  // boundary down: shallower water
  EXPECT_NEAR(hi, 10.0 + 0.1 * (40.0 + (42.0 - 35.0) * 60.0 / 65.0), 1e-3);  // boundary up: deeper water
}

TEST(WaterColumn, AWorldWithoutAProfileHasNoColumn) {
  const sim::WorldConfig w =
      sim::loadWorldConfig(writeWorld("plain.world", "  {density: 1010.0, surface_z: 0.0}\n"), kSchema);
  EXPECT_FALSE(w.water_column);
  EXPECT_EQ(w.water_density, 1010.0);
}

TEST(WaterColumn, BadInputStopsWithTheFileAndTheKey) {
  const std::string file = unexmin::test::testTempDir() + "bad.world";
  struct Case {
    std::string water, message;
  };
  const std::vector<Case> cases = {
      {"  profile:\n    - {depth: 10, temperature: 8}\n    - {depth: 5, temperature: 9}\n",
       "'water.profile[1].depth' = 5: expected rows sorted by depth: it is above the row before it (10 m)"},
      {"  profile:\n    - {depth: 0}\n    - {depth: 5}\n    - {depth: 5}\n    - {depth: 5}\n",
       "'water.profile[3].depth' = 5: expected at most two rows at one depth (a step)"},
      {"  profile:\n    - {depth: 0, conductivity: -3}\n",
       "'water.profile[0].conductivity' = -3: expected [0, 120000] uS/cm (not negative)"},
      {"  profile:\n    - {depth: 0, oxygen: -1}\n",
       "'water.profile[0].oxygen' = -1: expected [0, 100] mg/L (not negative)"},
      {"  profile:\n    - {depth: 0, temperature: 45}\n",
       "'water.profile[0].temperature' = 45: expected [0, 40] degC (the range of EOS-80 and Chen & Millero)"},
      {"  profile:\n    - {depth: 0, ph: 7}\n    - {depth: 5}\n",
       "'water.profile[1].ph' missing: a field is given in every row of 'water.profile' or in none (row 0 gives it)"},
      {"  profile:\n    - {depth: 0, salinity: 1, conductivity: 3}\n",
       "'water.profile[0].salinity' and 'water.profile[0].conductivity' both given"},
      {"  density: 1000\n  profile:\n    - {depth: 0}\n", "'water.density' and 'water.profile' both given"},
      {"  profile:\n    - {depth: 0}\n    - {depth: 50}\n  boundary: {depth: 10, amplitude: 12, period: 60}\n",
       "'water.boundary.amplitude' = 12: expected |amplitude| < 10 m"},
      {"  profile:\n    - {depth: 0}\n  regions:\n    - {min: [0, 0, -5], max: [1, 1, -9], profile: [{depth: 0}]}\n",
       "'water.regions[0].max' must exceed 'water.regions[0].min' on every axis"},
      {"  profile:\n    - {depth: 0}\n  regions:\n    - {min: [0, 0, -9], max: [1, 1, 0], profile: [{depth: 3}, "
       "{depth: 1}]}\n",
       "'water.regions[0].profile[1].depth' = 1: expected rows sorted by depth"},
      {"  boundary: {depth: 10, amplitude: 1, period: 60}\n", "'water.boundary' given without 'water.profile'"},
      {"  profile:\n    - {depth: 0, temprature: 8}\n", "unknown key 'water.profile[0].temprature'"},
  };
  for (const Case& c : cases) {
    const std::string msg = refusal(c.water);
    EXPECT_EQ(msg.rfind(file + ": " + c.message, 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

// The geology (geo/) and its world-file key (docs/worlds.md, "Geology"): the shipped mineral table loads and every
// value has a source; rocks mix their minerals' properties by the rules of docs/minerals.md; a point inside each
// kind of body finds it, the later of two overlapping bodies wins; bad input stops with the file and the key.
#include <unexmin/geo/geology.h>
#include <unexmin/geo/mineral_table.h>
#include <unexmin/sim/world_config.h>
#include "expect_error.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

using unexmin::ConfigError;
namespace geo = unexmin::geo;
namespace sim = unexmin::sim;

namespace {

const std::string kSchema = std::string(UNEXMIN_SOURCE_DIR) + "/config/world_schema.yaml";
const std::string kMinerals = std::string(UNEXMIN_SOURCE_DIR) + "/config/minerals.yaml";

const geo::MineralTable& table() {
  static const geo::MineralTable t = geo::MineralTable::load(kMinerals);
  return t;
}

std::string writeFile(const std::string& name, const std::string& text) {
  const std::string path = unexmin::test::testTempDir() + name;
  std::ofstream(path) << text;
  return path;
}

/// A world whose `geology:` map is `geology`.
std::string writeWorld(const std::string& name, const std::string& geology) {
  return writeFile(name, "name: w\ngeology:\n" + geology + "robots:\n  - {name: UX_1, xyz: [0, 0, -1]}\n");
}

const std::string kMine =
    "  host: [{mineral: granite, fraction: 1.0}]\n"
    "  bodies:\n"
    "    - {name: beds, kind: stratum, xyz: [0, 0, -30], normal: [0, 0, 1], thickness: 5,\n"
    "       minerals: [{mineral: calcite, fraction: 1.0}]}\n"
    "    - {name: lens, kind: ellipsoid, xyz: [10, 0, -20], radii: [4, 2, 1], rpy: [0, 0, 1.5707963267948966],\n"
    "       minerals: [{mineral: magnetite, fraction: 0.6}, {mineral: quartz, fraction: 0.4}]}\n"
    "    - {name: stope, kind: box, xyz: [-10, 0, -20], size: [2, 4, 6], rpy: [0.5235987755982988, 0, 0],\n"
    "       minerals: [{mineral: hematite, fraction: 0.5}, {mineral: goethite, fraction: 0.5}]}\n"
    "    - {name: vein, kind: vein, xyz: [0, 0, -20], normal: [1, 1, 0], thickness: 0.4, extent: 15,\n"
    "       minerals: [{mineral: chalcopyrite, fraction: 0.3}, {mineral: pyrite, fraction: 0.2},\n"
    "                  {mineral: quartz, fraction: 0.5}]}\n";

}  // namespace

TEST(MineralTable, TheShippedTableHasTheMineralsAndEveryValueASource) {
  for (const char* name : {"quartz", "calcite", "chalcopyrite", "pyrite", "malachite", "magnetite", "hematite",
                           "goethite", "autunite", "k_feldspar", "granite", "sludge"})
    EXPECT_NE(table().find(name), nullptr) << name;
  EXPECT_EQ(table().find("unobtainium"), nullptr);
  // calcite's Mn2+ glows orange-red under 365 nm, the uranyl mineral green; quartz not at all
  const geo::Mineral& calcite = *table().find("calcite");
  const geo::Mineral& autunite = *table().find("autunite");
  EXPECT_TRUE(calcite.fluorescence.excitedBy(365.0));
  EXPECT_GT(calcite.fluorescence.emission.x(), calcite.fluorescence.emission.y());
  EXPECT_TRUE(autunite.fluorescence.excitedBy(365.0));
  EXPECT_GT(autunite.fluorescence.emission.y(), autunite.fluorescence.emission.x());
  EXPECT_FALSE(table().find("quartz")->fluorescence.excitedBy(365.0));
  // the spectra's features (docs/minerals.md): malachite green, hematite red and dark below 550 nm
  const Eigen::Vector3d malachite = table().find("malachite")->reflectance.rgb();
  EXPECT_GT(malachite.y(), malachite.x());
  EXPECT_GT(malachite.y(), malachite.z());
  const geo::Spectrum& hematite = table().find("hematite")->reflectance;
  EXPECT_LT(hematite.at(500.0), 0.5 * hematite.at(700.0));
  EXPECT_LT(hematite.at(880.0), hematite.at(750.0));  // the 880 nm band
}

TEST(MineralTable, AValueWithoutASourceOrABadValueNamesTheFileAndKey) {
  struct Case {
    std::string text, message;
  };
  const std::string head = "references: {book: \"a book\"}\nminerals:\n  m:\n";
  const std::string body =
      "    density: 2650\n    susceptibility: 0\n    potassium: 0\n    uranium: 0\n    thorium: 0\n"
      "    reflectance: {nm: [400, 1000], value: [0.5, 0.5]}\n";
  const std::string all = "density: book, susceptibility: book, potassium: book, uranium: book, thorium: book";
  const std::vector<Case> cases = {
      {head + body + "    sources: {" + all + "}\n", "missing 'minerals.m.sources.reflectance'"},
      {head + body + "    sources: {" + all + ", reflectance: hearsay}\n",
       "'minerals.m.sources.reflectance' = 'hearsay': not a key of 'references' nor 'assumed'"},
      {head + "    density: -5\n", "'minerals.m.density' = -5: expected [500, 25000] kg/m^3"},
      {head + body + "    colour: red\n", "unknown key 'minerals.m.colour'"},
      {head + "    density: 2650\n    susceptibility: 0\n    potassium: 0\n    uranium: 0\n    thorium: 0\n"
              "    reflectance: {nm: [400, 300], value: [0.5, 0.5]}\n",
       "'minerals.m.reflectance.nm[1]' must be a number in [400, 1000]"},
  };
  for (const Case& c : cases) {
    const std::string path = writeFile("table.yaml", c.text);
    const std::string msg = unexmin::test::thrownMessage<ConfigError>([&] { geo::MineralTable::load(path); });
    EXPECT_EQ(msg.rfind(path + ": " + c.message, 0), 0u) << msg;
  }
}

TEST(Rock, MixesByVolumeAndConcentrationsByMass) {
  const geo::Rock r = geo::mixRock(table(), {{"k_feldspar", 0.25}, {"magnetite", 0.75}}, "x");
  const geo::Mineral& f = *table().find("k_feldspar");
  const geo::Mineral& m = *table().find("magnetite");
  EXPECT_NEAR(r.density, 0.25 * f.density + 0.75 * m.density, 1e-9);
  EXPECT_NEAR(r.susceptibility, 0.25 * f.susceptibility + 0.75 * m.susceptibility, 1e-12);
  // K by weight: the feldspar's potassium diluted by the mass of the magnetite (not by its volume)
  EXPECT_NEAR(r.potassium, 0.25 * f.density * f.potassium / (0.25 * f.density + 0.75 * m.density), 1e-12);
  EXPECT_LT(r.potassium, 0.25 * f.potassium - 0.5);
  EXPECT_NEAR(r.reflectanceAt(633.0), 0.25 * f.reflectance.at(633.0) + 0.75 * m.reflectance.at(633.0), 1e-12);
  EXPECT_NEAR(r.albedo.y(), 0.25 * f.reflectance.rgb().y() + 0.75 * m.reflectance.rgb().y(), 1e-12);
  // a calcite vein with quartz fluoresces at 365 nm in proportion to its calcite, not at 450 nm
  const geo::Rock v = geo::mixRock(table(), {{"calcite", 0.4}, {"quartz", 0.6}}, "x");
  const geo::Fluorescence& c = table().find("calcite")->fluorescence;
  EXPECT_NEAR((v.fluorescenceAt(365.0) - 0.4 * c.yield * c.emission).norm(), 0.0, 1e-12);
  EXPECT_EQ(v.fluorescenceAt(450.0).norm(), 0.0);
}

TEST(Spectrum, InterpolatesTheKnotsAndAveragesTheBands) {
  const geo::Spectrum s = geo::Spectrum::fromKnots({450, 650}, {0.2, 0.6});
  EXPECT_NEAR(s.at(400.0), 0.2, 1e-12);  // flat before the first knot
  EXPECT_NEAR(s.at(550.0), 0.4, 1e-12);
  EXPECT_NEAR(s.at(555.0), 0.41, 1e-12);
  EXPECT_NEAR(s.at(1000.0), 0.6, 1e-12);
  // blue 400-500: 0.2 up to 450, then the ramp to 0.3 at 500: mean 0.2125
  const Eigen::Vector3d rgb = s.rgb();
  EXPECT_NEAR(rgb.z(), (50 * 0.2 + 50 * 0.25) / 100.0, 1e-12);
  EXPECT_NEAR(rgb.y(), 0.4, 1e-12);
  EXPECT_NEAR(rgb.x(), (50 * 0.55 + 50 * 0.6) / 100.0, 1e-12);
}

TEST(Geology, APointInsideEachKindFindsItsBodyAndTheLaterWins) {
  const sim::WorldConfig w = sim::loadWorldConfig(writeWorld("mine.world", kMine), kSchema);
  ASSERT_TRUE(w.geology);
  const geo::Geology& g = *w.geology;
  ASSERT_EQ(g.bodies().size(), 4u);
  auto at = [&](double x, double y, double z) { return g.name(g.bodyAt(Eigen::Vector3d(x, y, z))); };
  EXPECT_EQ(at(0, 0, 0), "host");
  // stratum: base at z = -30, 5 m up
  EXPECT_EQ(at(100, -80, -29.9), "beds");
  EXPECT_EQ(at(100, -80, -25.1), "beds");
  EXPECT_EQ(at(100, -80, -24.9), "host");
  EXPECT_EQ(at(100, -80, -30.1), "host");
  // ellipsoid turned 90 deg in yaw: its 4 m semi-axis lies along world y
  EXPECT_EQ(at(10, 3.9, -20), "lens");
  EXPECT_EQ(at(13.9, 0, -20), "host");
  EXPECT_EQ(at(10, 0, -20.99), "lens");
  EXPECT_EQ(at(10, 2.9, -20.7), "host");  // (2.9/4)^2 + (0.7/1)^2 = 1.016: inside its bounds, outside the ellipsoid
  EXPECT_EQ(at(10, 2.7, -20.7), "lens");  // (2.7/4)^2 + 0.49 = 0.946
  // box rolled 30 deg: its 6 m edge along (0, -sin 30, cos 30)
  const Eigen::Vector3d axis(0, -0.5, std::sqrt(3.0) / 2);
  const Eigen::Vector3d c(-10, 0, -20);
  EXPECT_EQ(g.name(g.bodyAt(c + 2.9 * axis)), "stope");
  EXPECT_EQ(g.name(g.bodyAt(c + 3.1 * axis)), "host");
  EXPECT_EQ(at(-10, 0, -17.1), "stope");  // 2.9 m up world z: in the box's frame (0, 1.45, 2.51), inside
  EXPECT_EQ(at(-10, 0, -16.4), "host");   // 3.6 m up: (0, 1.8, 3.12), beyond the half edge of 3
  // vein: 0.4 m thick across (1, 1, 0)/sqrt 2 through (0, 0, -20), a disc of radius 15; listed after the stratum,
  // it wins where it crosses it
  const Eigen::Vector3d n = Eigen::Vector3d(1, 1, 0).normalized();
  const Eigen::Vector3d o(0, 0, -20);
  EXPECT_EQ(g.name(g.bodyAt(o + 0.19 * n)), "vein");
  EXPECT_EQ(g.name(g.bodyAt(o + 0.21 * n)), "host");
  EXPECT_EQ(g.name(g.bodyAt(o + Eigen::Vector3d(0, 0, -9.0))), "vein");   // z = -29: inside the stratum too
  EXPECT_EQ(g.name(g.bodyAt(o + Eigen::Vector3d(0, 0, -16.0))), "host");  // beyond its 15 m radius
  EXPECT_EQ(g.name(g.bodyAt(o + 14.0 * Eigen::Vector3d(1, -1, 0).normalized())), "vein");
  EXPECT_EQ(g.name(g.bodyAt(o + 15.5 * Eigen::Vector3d(1, -1, 0).normalized())), "host");
  // the rocks are the bodies' mixes
  EXPECT_NEAR(g.rockAt(Eigen::Vector3d(10, 0, -20)).density, 0.6 * 5175 + 0.4 * 2650, 1e-9);
  EXPECT_EQ(g.rockAt(Eigen::Vector3d(0, 0, 0)).potassium, table().find("granite")->potassium);
}

TEST(Geology, OverlapOrderIsTheListsOrder) {
  const geo::Rock a = geo::mixRock(table(), {{"quartz", 1.0}}, "a");
  const geo::Rock b = geo::mixRock(table(), {{"pyrite", 1.0}}, "b");
  geo::Body first, second;
  first.name = "first";
  first.kind = geo::BodyKind::box;
  first.size = Eigen::Vector3d(2, 2, 2);
  first.rock = a;
  second = first;
  second.name = "second";
  second.pose.translation() = Eigen::Vector3d(1, 0, 0);
  second.rock = b;
  const geo::Geology g(a, {first, second});
  EXPECT_EQ(g.name(g.bodyAt(Eigen::Vector3d(-0.5, 0, 0))), "first");
  EXPECT_EQ(g.name(g.bodyAt(Eigen::Vector3d(0.5, 0, 0))), "second");
  const geo::Geology h(a, {second, first});
  EXPECT_EQ(h.name(h.bodyAt(Eigen::Vector3d(0.5, 0, 0))), "first");
}

TEST(Geology, BadInputStopsWithTheFileAndTheKey) {
  const std::string file = unexmin::test::testTempDir() + "bad.world";
  const std::string host = "  host: [{mineral: granite, fraction: 1.0}]\n";
  struct Case {
    std::string geology, message;
  };
  const std::vector<Case> cases = {
      {"  host: [{mineral: kryptonite, fraction: 1.0}]\n",
       "'geology.host[0].mineral' = 'kryptonite': not in the mineral table"},
      {"  host: [{mineral: quartz, fraction: 0.5}, {mineral: calcite, fraction: 0.4999}]\n",
       "'geology.host' fractions sum to 0.9999: expected 1 (within 1e-6)"},
      {"  host: [{mineral: quartz, fraction: 0.5}, {mineral: quartz, fraction: 0.5}]\n",
       "'geology.host[1].mineral' = 'quartz' is listed twice in 'geology.host'"},
      {host + "  bodies:\n    - {name: a, kind: sphere, minerals: [{mineral: quartz, fraction: 1}]}\n",
       "'geology.bodies[0].kind' is 'sphere', expected ellipsoid|box|vein|stratum"},
      {host + "  bodies:\n    - {name: a, kind: box, radii: [1, 1, 1], minerals: [{mineral: quartz, fraction: 1}]}\n",
       "'geology.bodies[0].radii' is not a key of kind box"},
      {host + "  bodies:\n    - {name: a, kind: vein, normal: [0, 0, 0], thickness: 1, minerals: [{mineral: quartz, "
              "fraction: 1}]}\n",
       "'geology.bodies[0].normal' must be a non-zero vector"},
      {host + "  bodies:\n    - {name: a, kind: stratum, normal: [0, 0, 1], thickness: -1, minerals: [{mineral: "
              "quartz, fraction: 1}]}\n",
       "'geology.bodies[0].thickness' = -1: expected > 0 m"},
      {host + "  bodies:\n    - {name: a, kind: ellipsoid, radii: [1, 1, 1], minerals: [{mineral: quartz, fraction: "
              "1}]}\n    - {name: a, kind: ellipsoid, radii: [1, 1, 1], minerals: [{mineral: quartz, fraction: 1}]}\n",
       "'geology.bodies[1].name' = 'a': another body has it"},
      {host + "  bodies:\n    - {name: a, kind: box, size: [1, 1, 1], minerals: [{mineral: quartz, fraction: 1.2}]}\n",
       "'geology.bodies[0].minerals[0].fraction' = 1.2: expected a volume fraction in (0, 1]"},
      {host + "  bodys: []\n", "unknown key 'geology.bodys'"},
  };
  for (const Case& c : cases) {
    const std::string path = writeWorld("bad.world", c.geology);
    const std::string msg = unexmin::test::thrownMessage<ConfigError>([&] { sim::loadWorldConfig(path, kSchema); });
    EXPECT_EQ(msg.rfind(file + ": " + c.message, 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

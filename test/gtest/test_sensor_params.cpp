// Sensor parameter checks (cpp/unexmin/sensors/sensor_params.h): typed reads of a <sensor>'s <param>s with
// fallbacks, and every failure (missing value, out of range, not a number, wrong count, not one of the allowed
// words, unknown name) a ConfigError naming the robot, the sensor, the parameter, the value and the accepted
// range; then the same through a robot description for every core sensor family.
#include <unexmin/sensors/sensor_params.h>
#include "expect_error.h"
#include "sonar_fixture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

namespace unexmin {
namespace test {
namespace {

using sensors::SensorParams;

/// A DVL-like sensor spec with the given numeric and text parameters, as the description parser fills it.
sim::SensorSpec spec(const hydro::ParamMap& params, const std::map<std::string, std::string>& text = {}) {
  sim::SensorSpec s;
  s.name = "nav_dvl";
  s.type = "dvl";
  s.link = "T/dvl_link";
  s.rate = 8.0;
  s.params = params;
  s.text = text;
  return s;
}

/// The message names the robot and the sensor (with its type) and holds every one of `parts`.
void expectNames(const std::string& m, const std::string& robot, const std::string& sensor, const std::string& type,
                 const std::vector<std::string>& parts) {
  EXPECT_TRUE(contains(m, robot + ": sensor '" + sensor + "' (type " + type + ")")) << m;
  for (const auto& p : parts)
    EXPECT_TRUE(contains(m, p)) << "'" << p << "' not in: " << m;
}

TEST(SensorParams, NumbersInRangeAreReadAndAbsentOnesFallBack) {
  const sim::SensorSpec s = spec({{"altitude_max", {30.0}}, {"low", {0.0}}, {"high", {10.0}}});
  SensorParams p(s, "UX_1");
  EXPECT_EQ(p.number("altitude_max", 75.0, 0.0, 1e4, "m"), 30.0);
  EXPECT_EQ(p.number("altitude_min", 0.1, 0.0, 1e4, "m"), 0.1);  // absent: the fallback
  EXPECT_EQ(p.number("low", 5.0, 0.0, 10.0, "m"), 0.0);          // both ends of a closed range
  EXPECT_EQ(p.number("high", 5.0, 0.0, 10.0, "m"), 10.0);
  EXPECT_NO_THROW(p.finish());
  EXPECT_EQ(p.where(), "UX_1: sensor 'nav_dvl' (type dvl)");
}

TEST(SensorParams, AValueOutOfRangeNamesRobotSensorParameterValueAndRange) {
  const sim::SensorSpec s = spec({{"beam_angle", {2.0}}, {"altitude_min", {-0.5}}, {"rate_ok", {10.0}}});
  SensorParams p(s, "UX_1");
  expectNames(thrownMessage<ConfigError>([&] { p.number("beam_angle", 0.4, 0.0, 1.5, "rad"); }), "UX_1", "nav_dvl",
              "dvl", {"parameter 'beam_angle' = 2", "expected a number in [0, 1.5] rad"});
  expectNames(thrownMessage<ConfigError>([&] { p.number("altitude_min", 0.1, 0.0, 10000.0, "m"); }), "UX_1", "nav_dvl",
              "dvl", {"parameter 'altitude_min' = -0.5", "[0, 10000] m"});
  // An open upper end excludes the end itself and says so.
  expectNames(thrownMessage<ConfigError>([&] { p.number("rate_ok", 1.0, 0.0, 10.0, "Hz", true); }), "UX_1", "nav_dvl",
              "dvl", {"parameter 'rate_ok' = 10", "[0, 10) Hz"});
}

TEST(SensorParams, NonNumbersMissingValuesAndWrongCountsAreNamedWithTheirText) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const sim::SensorSpec s = spec({{"pair", {1.0, 2.0}}, {"not_finite", {nan}}, {"three", {1.0, 2.0}}},
                                 {{"beam_angle", "steep"}, {"empty", ""}, {"vector_text", "up"}});
  SensorParams p(s, "UX_2");
  expectNames(thrownMessage<ConfigError>([&] { p.number("beam_angle", 0.4, 0.0, 1.5, "rad"); }), "UX_2", "nav_dvl",
              "dvl", {"parameter 'beam_angle' = 'steep'", "expected a number in [0, 1.5] rad"});
  // value='' (no value given): the empty text, quoted.
  expectNames(thrownMessage<ConfigError>([&] { p.number("empty", 1.0, 0.0, 2.0, "m"); }), "UX_2", "nav_dvl", "dvl",
              {"parameter 'empty' = ''", "[0, 2] m"});
  expectNames(thrownMessage<ConfigError>([&] { p.number("pair", 1.0, 0.0, 5.0, "m"); }), "UX_2", "nav_dvl", "dvl",
              {"parameter 'pair' = 1 2", "one number", "[0, 5] m"});
  expectNames(thrownMessage<ConfigError>([&] { p.number("not_finite", 1.0, 0.0, 5.0, "m"); }), "UX_2", "nav_dvl", "dvl",
              {"parameter 'not_finite' = nan", "[0, 5] m"});
  expectNames(thrownMessage<ConfigError>([&] { p.vec3("three", Eigen::Vector3d::Zero()); }), "UX_2", "nav_dvl", "dvl",
              {"parameter 'three' = 1 2", "three numbers"});
  expectNames(thrownMessage<ConfigError>([&] { p.vec3("vector_text", Eigen::Vector3d::Zero()); }), "UX_2", "nav_dvl",
              "dvl", {"parameter 'vector_text' = 'up'", "three numbers"});
}

TEST(SensorParams, VectorsTextsAndWordsAreReadWithTheirFallbacks) {
  const sim::SensorSpec s = spec({{"offset", {1.0, -2.0, 0.5}}, {"numeric_word", {3.0}}},
                                 {{"noise", "none"}, {"frames", "a_link  b_link\tc_link"}});
  SensorParams p(s, "UX_1");
  EXPECT_EQ(p.vec3("offset", Eigen::Vector3d::Zero()), Eigen::Vector3d(1.0, -2.0, 0.5));
  EXPECT_EQ(p.vec3("absent", Eigen::Vector3d(7, 8, 9)), Eigen::Vector3d(7, 8, 9));
  EXPECT_EQ(p.text("noise", "gaussian", {"gaussian", "none"}), "none");
  EXPECT_EQ(p.text("model", "gaussian", {"gaussian", "none"}), "gaussian");
  EXPECT_EQ(p.text("numeric_word", ""), "3");  // a number read as text
  EXPECT_EQ(p.words("frames"), (std::vector<std::string>{"a_link", "b_link", "c_link"}));
  EXPECT_TRUE(p.words("no_frames").empty());
  EXPECT_NO_THROW(p.finish());
}

TEST(SensorParams, AWordNotAllowedNamesTheAllowedOnes) {
  const sim::SensorSpec s = spec({{"noise", {1.0}}}, {{"mode", "brown"}});
  SensorParams p(s, "UX_3");
  expectNames(thrownMessage<ConfigError>([&] { p.text("mode", "gaussian", {"gaussian", "none"}); }), "UX_3", "nav_dvl",
              "dvl", {"parameter 'mode' = 'brown'", "one of gaussian|none"});
  expectNames(thrownMessage<ConfigError>([&] { p.text("noise", "gaussian", {"gaussian", "none"}); }), "UX_3", "nav_dvl",
              "dvl", {"parameter 'noise' = '1'", "one of gaussian|none"});
}

TEST(SensorParams, AFlagIsTrueOrFalseAsWrittenByHandOrByXacro) {
  const sim::SensorSpec s = spec({{"one", {1.0}}, {"zero", {0.0}}},
                                 {{"a", "true"}, {"b", "True"}, {"c", "false"}, {"d", "False"}, {"e", "yes"}});
  SensorParams p(s, "UX_2");
  EXPECT_TRUE(p.flag("a", false));
  EXPECT_TRUE(p.flag("b", false));
  EXPECT_FALSE(p.flag("c", true));
  EXPECT_FALSE(p.flag("d", true));
  EXPECT_TRUE(p.flag("one", false));
  EXPECT_FALSE(p.flag("zero", true));
  EXPECT_TRUE(p.flag("absent", true));  // the fallback
  EXPECT_FALSE(p.flag("absent_too", false));
  expectNames(thrownMessage<ConfigError>([&] { p.flag("e", false); }), "UX_2", "nav_dvl", "dvl",
              {"parameter 'e' = 'yes'", "one of true|false|True|False|1|0"});
}

TEST(SensorParams, AnUnreadParameterIsATypoExceptTopicNames) {
  const sim::SensorSpec s =
      spec({{"beam_angle", {0.4}}, {"altitud_max", {30.0}}}, {{"topic", "dvl/data"}, {"range_topic", "dvl/range"}});
  SensorParams p(s, "UX_1");
  p.number("beam_angle", 0.4, 0.0, 1.5, "rad");
  p.number("altitude_max", 75.0, 0.0, 1e4, "m");
  expectNames(thrownMessage<ConfigError>([&] { p.finish(); }), "UX_1", "nav_dvl", "dvl",
              {"unknown parameter 'altitud_max'", "altitude_max", "beam_angle"});

  const sim::SensorSpec topics_only = spec({}, {{"topic", "dvl/data"}, {"range_topic", "dvl/range"}});
  EXPECT_NO_THROW(SensorParams(topics_only, "UX_1").finish());
}

TEST(SensorParams, FailIsAConfigErrorUnderTheOneErrorRoot) {
  static_assert(std::is_base_of<Error, ConfigError>::value, "ConfigError is an unexmin::Error");
  const sim::SensorSpec s = spec({});
  SensorParams p(s, "UX_1");
  expectNames(thrownMessage<ConfigError>([&] { p.fail("beam_frames", "'x'", "4 link names"); }), "UX_1", "nav_dvl",
              "dvl", {"parameter 'beam_frames' = 'x': expected 4 link names"});
}

// ---- Through a robot description, for every core family (the checks every model's constructor makes) ----

/// Start-up of the robot "T" (test_fixture's sphere) in open water with one sensor; the ConfigError's what().
std::string startup(const std::string& links, const std::string& sensor) {
  return thrownMessage<ConfigError>(
      [&] { SonarWorld w(meshWorld({}, Eigen::Vector3d(0, 0, -50)), sensorUrdf(SphereSpec(), links, sensor)); });
}

TEST(SensorParams, EveryFamilyNamesRobotSensorParameterValueAndRangeAtStartUp) {
  struct Case {
    std::string type, link, links, key, value;
    std::vector<std::string> parts;
    std::map<std::string, std::string> extra;
  };
  const std::string imu = mountLink("T/imu_link", Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  const std::string pressure = mountLink("T/p_link", Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  const std::string dvl = dvlLinks(25.0 * M_PI / 180, 0.0);
  const std::string m3 = mountLink("T/m3_link", Eigen::Vector3d(0.3, 0, 0), Eigen::Vector3d::Zero());
  const std::map<std::string, std::string> head = {{"joint", "T/msis_head_joint"}};
  const std::vector<Case> cases = {
      {"imu", "T/imu_link", imu, "temperature", "200", {"= 200", "[-50, 150] degC"}, {}},
      {"imu", "T/imu_link", imu, "gyro_range", "fast", {"= 'fast'", "rad/s"}, {}},
      {"pressure", "T/p_link", pressure, "pressure_noise", "-3", {"= -3", "Pa"}, {}},
      {"pressure", "T/p_link", pressure, "pressure_bias", "", {"= ''", "Pa"}, {}},
      {"dvl", "T/dvl_link", dvl, "altitude_min", "-1", {"= -1", "[0, 10000] m"}, {}},
      {"dvl", "T/dvl_link", dvl, "beam_angle", "steep", {"= 'steep'", "rad"}, {}},
      {"dvl", "T/dvl_link", dvl, "water_temperature", "1 2", {"= 1 2", "one number", "[-5, 100] degC"}, {}},
      {"m3", "T/m3_link", m3, "range_resolution", "20", {"= 20", "[1e-06, 10] m"}, {}},
      {"msis", "T/msis_head_link", msisLinks(), "gain", "2", {"= 2", "[0, 1]"}, head},
      {"msis", "T/msis_head_link", msisLinks(), "absorption", "strong", {"= 'strong'", "[0, 10] dB/m"}, head},
  };
  for (const Case& c : cases) {
    std::map<std::string, std::string> params = c.extra;
    params[c.key] = c.value;
    const std::string m = startup(c.links, sensorXml("my_" + c.type, c.type, c.link, 5.0, params));
    std::vector<std::string> parts = c.parts;
    parts.push_back("parameter '" + c.key + "' ");
    expectNames(m, "T", "my_" + c.type, c.type, parts);
  }
}

TEST(SensorParams, AParamWithoutValueOrWithANonFiniteOneStopsTheDescriptionNamingSensorAndParameter) {
  const std::string links = mountLink("T/p_link", Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  const auto urdf = [&](const std::string& param) {
    return sensorUrdf(SphereSpec(), links,
                      "<sensor name='depth' type='pressure' link='T/p_link' rate='5'>" + param + "</sensor>\n");
  };
  std::string m = thrownMessage<ConfigError>(
      [&] { sim::parseRobotDescription(urdf("<param name='pressure_noise'/>"), "UX_1 description"); });
  EXPECT_TRUE(contains(m, "UX_1 description")) << m;
  EXPECT_TRUE(contains(m, "sensor name='depth'")) << m;
  EXPECT_TRUE(contains(m, "pressure_noise")) << m;
  EXPECT_TRUE(contains(m, "'value'")) << m;

  m = thrownMessage<ConfigError>(
      [&] { sim::parseRobotDescription(urdf("<param name='pressure_noise' value='nan'/>"), "UX_1 description"); });
  EXPECT_TRUE(contains(m, "UX_1 description")) << m;
  EXPECT_TRUE(contains(m, "sensor name='depth'")) << m;
  EXPECT_TRUE(contains(m, "pressure_noise")) << m;
  EXPECT_TRUE(contains(m, "'nan' is not finite")) << m;
}

}  // namespace
}  // namespace test
}  // namespace unexmin

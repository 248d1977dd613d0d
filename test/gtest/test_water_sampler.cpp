// Water sampler (cpp/unexmin/sensors/science/water_sampler_sensor.h, docs/water_sampler.md): the lab result is the
// true water at the intake averaged over the fill (a robot driven at a known speed across a linear temperature
// gradient: the mean of the linear function over the path); depth, time and channel-jump triggers fire at the first
// check that meets them; a full sampler refuses; the water taken weighs on the robot (a neutral robot sinks with
// (dm g) / (m + m_added + dm)); bad parameters stop start-up naming the parameter.
#include <unexmin/sensors/science/water_sampler_sensor.h>
#include <unexmin/water/water_column.h>
#include "sensor_fixture.h"

#include <gtest/gtest.h>

#include <cmath>

namespace unexmin {
namespace test {
namespace {

using sensors::science::SampleTrigger;
using sensors::science::WaterSamplerSensor;

const Eigen::Vector3d kMount(0.0, 0.0, -0.2);  // intake 0.2 m below the hull centre

std::string samplerUrdf(const SphereSpec& s, double rate, const std::map<std::string, std::string>& params,
                        const std::string& extra = "") {
  return sensorUrdf(s, mountLink("T/sampler_link", kMount, Eigen::Vector3d::Zero()),
                    sensorXml("sampler", "water_sampler", "T/sampler_link", rate, params) + extra);
}

/// A profile of rows (depth [m], temperature [degC], pH), salinity 0.5, linear between rows.
std::shared_ptr<const water::WaterColumn> column(const std::vector<std::array<double, 3>>& rows) {
  water::Profile p;
  for (const auto& r : rows) {
    water::WaterRow w;
    w.depth = r[0];
    w.temperature = r[1];
    w.ph = r[2];
    w.salinity = 0.5;
    p.rows.push_back(w);
  }
  water::checkProfile(p, "water.profile");
  return std::make_shared<const water::WaterColumn>(p, std::vector<water::Region>{}, 0.0, 9.81);
}

/// Moves the robot along the straight path spawn + v t (world velocity `v` [m/s]) for `steps` steps: before each
/// step it is placed, at rest, where the path is at the step's end, so the sensors see the path whatever the forces
/// (within the a dt^2 < 1e-6 m one step's forces move it).
void drive(SensorWorld& w, const Eigen::Vector3d& v, int steps) {
  const Eigen::Vector3d spawn = w.world->config().robots.at(0).pose.translation();
  for (int i = 0; i < steps; ++i) {
    const double t = static_cast<double>(w.world->stepCount() + 1) * w.world->dt();
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = spawn + v * t;
    w.place(pose);
    w.step();
  }
}

TEST(WaterSampler, TheLabResultIsTheMeanOfTheWaterAlongThePathFlownDuringTheFill) {
  const SphereSpec s = undampedSphere();
  // 10 degC at the surface, 30 degC at 10 m: 2 degC/m; pH 8 to 6.
  const double gradient = 2.0, ph_gradient = -0.2;
  sim::WorldConfig config = openWater(s, Eigen::Vector3d(0, 0, -3.0));
  config.water_column = column({{{0.0, 10.0, 8.0}}, {{10.0, 30.0, 6.0}}});
  const double fill_time = 2.0, volume = 0.5;
  SensorWorld w(config, samplerUrdf(s, 10.0, {{"fill_time", num(fill_time)}, {"bottle_volume", num(volume)}}));
  auto& sampler = w.sensor<WaterSamplerSensor>("sampler");
  const double speed = 0.5;  // [m/s] straight down
  const Eigen::Vector3d v(0, 0, -speed);
  drive(w, v, 250);  // 0.5 s
  const double t0 = w.world->time();
  const double depth0 = -(w.robot().state().pose * kMount).z();  // the intake when fired
  EXPECT_EQ(sampler.fire(), "filling bottle 1 of 4");
  const int fill_steps = static_cast<int>(std::lround(fill_time / w.world->dt()));
  drive(w, v, fill_steps - 1);
  EXPECT_TRUE(sampler.filling());
  EXPECT_TRUE(sampler.results().empty());
  drive(w, v, 1);
  ASSERT_EQ(sampler.results().size(), 1u);
  EXPECT_FALSE(sampler.filling());
  const auto& r = sampler.results()[0];
  // The path: depth0 + speed t over (0, fill_time]; its mean is the depth at the middle of the fill, and the mean
  // of the linear profile along it the profile at that depth. The fill is sampled at the end of each step: the mean
  // of the steps' depths is deeper by speed dt / 2 (the tolerance).
  const double mean_depth = depth0 + speed * fill_time / 2.0;
  const double step_bias = speed * w.world->dt() / 2.0;
  EXPECT_NEAR(r.depth, mean_depth, 1.01 * step_bias);
  EXPECT_NEAR(r.temperature, 10.0 + gradient * mean_depth, 1.01 * gradient * step_bias);
  EXPECT_NEAR(r.ph, 8.0 + ph_gradient * mean_depth, 1.01 * std::abs(ph_gradient) * step_bias);
  EXPECT_NEAR(r.salinity, 0.5, 1e-9);
  EXPECT_NEAR(r.position.z(), -mean_depth, 1.01 * step_bias);
  EXPECT_NEAR(r.position.x(), 0.0, 1e-9);
  // The ends of the path differ by 2 degC: a sample of either end instead of the mean is 1 degC off.
  EXPECT_GT(std::abs(r.temperature - (10.0 + gradient * depth0)), 0.9);
  EXPECT_DOUBLE_EQ(r.start_time, t0);
  EXPECT_NEAR(r.end_time, t0 + fill_time, 1e-9);
  EXPECT_EQ(r.trigger, SampleTrigger::manual);
  EXPECT_EQ(r.bottle, 0u);
  EXPECT_DOUBLE_EQ(r.volume, volume);
  // The density: EOS-80 is not linear in temperature, so its mean along the path (Simpson's rule, 200 intervals)
  // is not the density at the mean depth; the steps' bias as above.
  double rho_sum = 0.0;
  const int n = 200;
  for (int i = 0; i <= n; ++i) {
    const double z = -(depth0 + speed * fill_time * i / n);
    rho_sum +=
        (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0)) * config.water_column->densityAt(Eigen::Vector3d(0, 0, z), 0.0);
  }
  const double rho_mean = rho_sum / (3.0 * n);
  const double rho_slope = std::abs(config.water_column->densityAt(Eigen::Vector3d(0, 0, -depth0 - 1.0), 0.0) -
                                    config.water_column->densityAt(Eigen::Vector3d(0, 0, -depth0), 0.0));  // [kg/m^3/m]
  EXPECT_NEAR(r.density, rho_mean, 2.0 * rho_slope * step_bias);
  EXPECT_NEAR(r.mass, r.density * volume * 1e-3, 1e-12);
  EXPECT_NEAR(sampler.carriedMass(), r.mass, 1e-12);
  EXPECT_EQ(sampler.bottlesLeft(), 3);
}

TEST(WaterSampler, ADepthTriggerFiresAtTheFirstCheckAtOrBelowItsDepth) {
  const SphereSpec s = undampedSphere();
  // [m], [m], [m/s]; the start is off the step grid, so that no step ends exactly at the trigger depth
  const double start = 4.0003, trigger = 5.0, speed = 0.5;
  const sim::WorldConfig config = openWater(s, Eigen::Vector3d(0, 0, -start));  // no water column
  SensorWorld w(config, samplerUrdf(s, 500.0, {{"depth_triggers", "5 1000"}, {"fill_time", "0.5"}}));
  auto& sampler = w.sensor<WaterSamplerSensor>("sampler");
  const double dt = w.world->dt();
  // The intake's depth after step k is start - mount.z + speed k dt: the first k at or below the trigger.
  const double first = std::ceil((trigger - (start - kMount.z())) / (speed * dt) - 1e-9) * dt;
  while (w.world->time() + dt < first - 0.5 * dt) {
    drive(w, Eigen::Vector3d(0, 0, -speed), 1);
    ASSERT_FALSE(sampler.filling()) << "fired at t = " << w.world->time() << " s, before the depth";
  }
  drive(w, Eigen::Vector3d(0, 0, -speed), 1);
  EXPECT_TRUE(sampler.filling());
  drive(w, Eigen::Vector3d(0, 0, -speed), 300);
  ASSERT_EQ(sampler.results().size(), 1u);  // the 1000 m trigger is never reached
  const auto& r = sampler.results()[0];
  EXPECT_EQ(r.trigger, SampleTrigger::depth);
  EXPECT_NEAR(r.start_time, first, 1e-9);  // checked at the end of that step; filled from the next one
  // No water column: the world's uniform water, its chemistry unknown.
  EXPECT_DOUBLE_EQ(r.density, config.water_density);
  EXPECT_TRUE(std::isnan(r.temperature));
  EXPECT_TRUE(std::isnan(r.ph));
}

TEST(WaterSampler, ATimeTriggerFiresAtTheFirstCheckAtOrAfterItsTime) {
  const SphereSpec s = undampedSphere();
  SensorWorld w(openWater(s), samplerUrdf(s, 4.0, {{"time_triggers", "1.1"}, {"fill_time", "0.5"}}));
  auto& sampler = w.sensor<WaterSamplerSensor>("sampler");
  while (w.world->time() < 3.0)
    w.step();
  ASSERT_EQ(sampler.results().size(), 1u);
  EXPECT_EQ(sampler.results()[0].trigger, SampleTrigger::time);
  EXPECT_NEAR(sampler.results()[0].start_time, 1.25, 1e-9);  // checks at k / 4 Hz: the first at or after 1.1 s
  EXPECT_NEAR(sampler.results()[0].end_time, 1.75, 1e-9);
}

TEST(WaterSampler, AChannelJumpFiresAtTheChemocline) {
  const SphereSpec s = undampedSphere();
  const double chemocline = 20.0, start = 15.0003, speed = 0.5;
  sim::WorldConfig config = openWater(s, Eigen::Vector3d(0, 0, -start));
  // pH 7.5 down to 20 m, 4.5 below it (a sharp step); temperature uniform.
  config.water_column =
      column({{{0.0, 12.0, 7.5}}, {{chemocline, 12.0, 7.5}}, {{chemocline, 12.0, 4.5}}, {{100.0, 12.0, 4.5}}});
  SensorWorld w(config,
                samplerUrdf(s, 500.0, {{"trigger_channel", "ph"}, {"trigger_jump", "0.5"}, {"fill_time", "0.5"}}));
  auto& sampler = w.sensor<WaterSamplerSensor>("sampler");
  const double dt = w.world->dt();
  const double first = std::ceil((chemocline - (start - kMount.z())) / (speed * dt) - 1e-9) * dt;
  while (w.world->time() < first + 1.0)
    drive(w, Eigen::Vector3d(0, 0, -speed), 1);
  ASSERT_EQ(sampler.results().size(), 1u) << "one bottle at the step, none in the uniform water either side";
  const auto& r = sampler.results()[0];
  EXPECT_EQ(r.trigger, SampleTrigger::channel);
  EXPECT_NEAR(r.start_time, first, 1e-9);
  EXPECT_NEAR(r.ph, 4.5, 1e-9);  // the bottle filled below the step
}

TEST(WaterSampler, AFullSamplerAndAFillingOneRefuse) {
  const SphereSpec s = undampedSphere();
  SensorWorld w(openWater(s), samplerUrdf(s, 10.0, {{"bottles", "2"}, {"fill_time", "0.1"}}));
  auto& sampler = w.sensor<WaterSamplerSensor>("sampler");
  for (int bottle = 1; bottle <= 2; ++bottle) {
    EXPECT_EQ(sampler.fire(), "filling bottle " + std::to_string(bottle) + " of 2");
    try {
      sampler.fire();
      FAIL() << "a second fire while filling was accepted";
    } catch (const ParameterError& e) {
      EXPECT_NE(std::string(e.what()).find("T/sampler: bottle " + std::to_string(bottle) + " of 2 is filling"),
                std::string::npos)
          << e.what();
    }
    for (int i = 0; i < 60; ++i)
      w.step();
  }
  ASSERT_EQ(sampler.results().size(), 2u);
  EXPECT_EQ(sampler.bottlesLeft(), 0);
  try {
    sampler.fire();
    FAIL() << "a full sampler fired";
  } catch (const ParameterError& e) {
    EXPECT_EQ(std::string(e.what()), "T/sampler: all 2 bottles are full");
  }
  EXPECT_EQ(sampler.results().size(), 2u);
}

TEST(WaterSampler, AFamilyWithoutAnActionRefusesToFireNamingIt) {
  const SphereSpec s;
  SensorWorld w(openWater(s), sensorUrdf(s, mountLink("T/p_link", Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()),
                                         sensorXml("depth", "pressure", "T/p_link", 10.0, {})));
  try {
    w.suite->find("depth")->fire();
    FAIL() << "a pressure sensor fired";
  } catch (const ParameterError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("T/depth (family pressure)"), std::string::npos) << m;
  }
}

TEST(WaterSampler, ANeutralRobotThatFillsTwoLitresSinksWithTheirWeight) {
  const SphereSpec s = undampedSphere();  // neutral in fresh water, no damping: a constant force, a constant rate
  SensorWorld w(openWater(s, Eigen::Vector3d(0, 0, -100.0)),
                samplerUrdf(s, 10.0, {{"bottle_volume", "2"}, {"fill_time", "2"}}));
  auto& sampler = w.sensor<WaterSamplerSensor>("sampler");
  const double m0 = w.robot().totalMass();
  for (int i = 0; i < 500; ++i)  // 1 s at rest: neutral
    w.step();
  EXPECT_NEAR(w.robot().state().linear_velocity.z(), 0.0, 1e-9);
  sampler.fire();
  for (int i = 0; i < 500; ++i)
    w.step();
  const double dm = s.rho * 2e-3;  // [kg] of 2 L of the world's water
  EXPECT_NEAR(sampler.carriedMass(), dm / 2.0, 1e-9) << "half the fill time, half the water";
  EXPECT_NEAR(w.robot().totalMass(), m0 + dm / 2.0, 1e-9);
  for (int i = 0; i < 500; ++i)
    w.step();
  ASSERT_EQ(sampler.results().size(), 1u);
  EXPECT_NEAR(w.robot().totalMass(), m0 + dm, 1e-9);
  // Full: weight (m + dm) g against buoyancy m g, inertia m + m_added + dm.
  const double g = 9.81;
  const double expected = -dm * g / (s.mass + s.added_mass + dm);
  w.step();  // the full mass acts from this step on
  const double v0 = w.robot().state().linear_velocity.z();
  EXPECT_LT(v0, 0.0) << "the robot did not start sinking during the fill";
  for (int i = 0; i < 500; ++i)
    w.step();
  const double accel = (w.robot().state().linear_velocity.z() - v0) / 1.0;
  EXPECT_NEAR(accel, expected, 0.01 * std::abs(expected));
  // After the fill the sinking is the full bottle's alone: half the water (a fill still half done) is 2x off.
  EXPECT_LT(std::abs(expected), 0.2);
}

TEST(WaterSampler, BadParametersStopStartUpNamingTheParameter) {
  const SphereSpec s;
  const std::vector<std::pair<std::map<std::string, std::string>, std::string>> cases = {
      {{{"bottles", "2.5"}}, "'bottles' = 2.5"},
      {{{"bottles", "0"}}, "'bottles' = 0"},
      {{{"bottle_volume", "0"}}, "'bottle_volume' = 0"},
      {{{"bottle_volume", "-1"}}, "'bottle_volume' = -1"},
      {{{"fill_time", "0.0001"}}, "'fill_time' = 0.0001"},
      {{{"depth_triggers", "5 -1"}}, "'depth_triggers' = -1"},
      {{{"depth_triggers", "five"}}, "'depth_triggers' = 'five'"},
      {{{"time_triggers", "1e9"}}, "'time_triggers' = "},
      {{{"trigger_channel", "salt"}}, "'trigger_channel' = 'salt'"},
      {{{"trigger_channel", "ph"}}, "'trigger_jump' = (unset)"},
      {{{"trigger_jump", "0.2"}}, "'trigger_jump' = (set)"},
      {{{"trigger_channel", "redox"}, {"trigger_jump", "0"}}, "'trigger_jump' = 0"},
      {{{"bottle_volum", "1"}}, "bottle_volum"},
  };
  for (const auto& c : cases) {
    try {
      SensorWorld w(openWater(s), samplerUrdf(s, 10.0, c.first));
      ADD_FAILURE() << "accepted " << c.second;
    } catch (const ConfigError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("sensor 'sampler'"), std::string::npos) << m;
      EXPECT_NE(m.find(c.second), std::string::npos) << m;
    }
  }
}

}  // namespace
}  // namespace test
}  // namespace unexmin

// The engine (cpp/unexmin/engine/engine.h) that both front ends run, in the 4 m test box (worlds/test_box.world) with
// the sphere robot carrying a noisy IMU and an M3: each step is the world's, the caster's and the sensors' step in
// that order (the same numbers as the three stepped by hand, bit for bit: the same code in the same order), a reset
// replays the same samples for the same seed, `hold` keeps a thrust command past its 1 s watchdog, no sensor family
// builds no caster, and a bad ray caster name stops construction naming the world file.
#include <unexmin/engine/engine.h>
#include "expect_error.h"
#include "sensor_fixture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace unexmin {
namespace test {
namespace {

const std::string kWorldFile = std::string(UNEXMIN_SOURCE_DIR) + "/worlds/test_box.world";
constexpr double kDt = 0.002;     // [s]
constexpr double kThrust = 30.0;  // [N] along +x (thruster 0 of the sphere robot)

std::string robotUrdf() {
  const std::map<std::string, std::string> imu = {
      {"noise", "gaussian"}, {"gyro_noise_density", "0.001"}, {"accel_noise_density", "0.01"}};
  return sensorUrdf(SphereSpec(),
                    mountLink("T/imu_link", Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()) +
                        mountLink("T/m3_link", Eigen::Vector3d(0.3, 0.0, 0.0), Eigen::Vector3d::Zero()),
                    sensorXml("imu", "imu", "T/imu_link", 500.0, imu) +
                        sensorXml("m3", "m3", "T/m3_link", 40.0, {{"noise", "none"}}));
}

engine::EngineOptions options(std::uint64_t seed, const std::string& sensors = "all") {
  engine::EngineOptions o;
  o.dt = kDt;
  o.seed = seed;
  o.selection = sensors::SensorSelection::parse(sensors, coreModels().types(), "sensors");
  return o;
}

std::unique_ptr<engine::Engine> makeEngine(const sim::WorldConfig& config, std::uint64_t seed,
                                           const std::string& sensors = "all", const std::string& urdf = robotUrdf()) {
  std::map<std::string, sim::RobotDescription> d;
  d.emplace(config.robots.at(0).name, sim::parseRobotDescription(urdf, "(test robot)"));
  return std::make_unique<engine::Engine>(config, d, 1, coreModels(), options(seed, sensors), kWorldFile);
}

/// What a run leaves behind: the robot's position [m] and its sensors' newest samples.
struct Outcome {
  Eigen::Vector3d position;
  Eigen::Vector3d specific_force;
  std::uint64_t imu_count;
  std::vector<float> m3_ranges;
  std::uint64_t m3_count;
};

Outcome outcome(sim::Robot& robot, sensors::SensorSuite& suite) {
  const auto& imu = dynamic_cast<sensors::ImuSensor&>(*suite.find("imu"));
  const auto& m3 = dynamic_cast<sensors::sonar::M3Sensor&>(*suite.find("m3"));
  return {robot.state().pose.translation(), imu.last().specific_force, imu.sampleCount(), m3.last().ranges,
          m3.sampleCount()};
}

void expectSame(const Outcome& a, const Outcome& b) {
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.specific_force, b.specific_force);
  EXPECT_EQ(a.imu_count, b.imu_count);
  EXPECT_EQ(a.m3_ranges, b.m3_ranges);
  EXPECT_EQ(a.m3_count, b.m3_count);
}

/// 0.6 s under thrust, the command held by the engine.
Outcome fly(engine::Engine& e) {
  sim::Robot& r = e.world().robot(0);
  EXPECT_TRUE(r.thruster(0).setCommand(kThrust, e.world().time()));
  for (int i = 0; i < 300; ++i)
    e.step(true);
  return outcome(r, e.suite(0));
}

TEST(Engine, StepsAsTheWorldTheCasterAndTheSensorsSteppedByHand) {
  const sim::WorldConfig config = sim::loadWorldConfig(kWorldFile);
  auto e = makeEngine(config, 5);
  ASSERT_NE(e->caster(), nullptr);
  ASSERT_EQ(e->suite(0).size(), 2u);
  const Outcome engine = fly(*e);

  SensorWorld hand(config, robotUrdf(), 5, kDt);
  ASSERT_TRUE(hand.robot().thruster(0).setCommand(kThrust, 0.0));
  for (int i = 0; i < 300; ++i) {
    hand.robot().thruster(0).holdCommand(hand.world->time());
    hand.step();  // the world, the caster, the suite
  }
  expectSame(engine, outcome(hand.robot(), *hand.suite));
  EXPECT_EQ(engine.imu_count, 300u);      // every step at 500 Hz
  EXPECT_EQ(engine.m3_count, 24u);        // 40 Hz over 0.6 s
  EXPECT_GT(engine.position.x(), 0.005);  // it moved: the samples depend on the pose of each step
}

TEST(Engine, AResetReplaysTheSameSamplesForTheSameSeed) {
  auto e = makeEngine(sim::loadWorldConfig(kWorldFile), 5);
  const Outcome first = fly(*e);
  e->reset(5);
  EXPECT_EQ(e->world().stepCount(), 0u);
  EXPECT_EQ(e->suite(0).find("imu")->sampleCount(), 0u);
  expectSame(fly(*e), first);
  e->reset(6);
  EXPECT_NE(fly(*e).specific_force, first.specific_force);  // another seed, other noise
}

TEST(Engine, HoldKeepsACommandPastItsWatchdog) {
  constexpr double kTimeout = 0.5;  // [s] the thrusters' watchdog (the sphere fixture's is off)
  std::string urdf = robotUrdf();
  for (std::size_t at; (at = urdf.find("<timeout value='0'/>")) != std::string::npos;)
    urdf.replace(at, 20, "<timeout value='" + num(kTimeout) + "'/>");
  auto e = makeEngine(sim::loadWorldConfig(kWorldFile), 1, "none", urdf);
  hydro::Thruster& t = e->world().robot(0).thruster(0);
  ASSERT_DOUBLE_EQ(t.params().timeout, kTimeout);
  const int steps = static_cast<int>(std::ceil(1.5 * kTimeout / kDt));
  ASSERT_TRUE(t.setCommand(kThrust, e->world().time()));
  for (int i = 0; i < steps; ++i)
    e->step(true);
  EXPECT_DOUBLE_EQ(t.thrust(), kThrust);  // zero-order dynamics, identity conversion
  for (int i = 0; i < steps; ++i)
    e->step();
  EXPECT_DOUBLE_EQ(t.thrust(), 0.0);  // not held: the watchdog set it to zero
}

TEST(Engine, NoSensorFamilyBuildsNoCasterAndNoSensor) {
  auto e = makeEngine(sim::loadWorldConfig(kWorldFile), 1, "none");
  EXPECT_EQ(e->caster(), nullptr);
  EXPECT_EQ(e->suite(0).size(), 0u);
  EXPECT_EQ(e->suite(0).skipped(), (std::vector<std::string>{"imu", "m3"}));
  EXPECT_EQ(e->selection().text(), "none");
  e->step();
  EXPECT_EQ(e->world().stepCount(), 1u);
}

TEST(Engine, AnUnknownRayCasterNamesTheWorldFile) {
  sim::WorldConfig config = sim::loadWorldConfig(kWorldFile);
  config.ray_caster = "optix";
  const std::string message = thrownMessage<ConfigError>([&] { makeEngine(config, 1); });
  EXPECT_TRUE(contains(message, kWorldFile + ": 'ray_caster': ")) << message;
  EXPECT_TRUE(contains(message, "optix")) << message;
}

}  // namespace
}  // namespace test
}  // namespace unexmin

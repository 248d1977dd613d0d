// docs/adding_a_thruster.md through ROS: a thruster dynamics family and a conversion family that exist only in the
// tests (test/gtest/thruster_family_fixture.h) are registered on a copy of ThrusterFactory::builtin(), named in
// thruster 0 of the UX-1's description, built by SimulatorRos in the test process, commanded on
// /UX_1/thrusters/0/input and stepped through /sim/step; the thrust published on /UX_1/thrusters/0/thrust equals
// the families' closed form. And: the same description on a simulator that does not know the families stops
// start-up with one ConfigError naming the thruster, the unknown type and the known ones.
#include "../gtest/thruster_family_fixture.h"

#include <unexmin/ros_layer/simulator_ros.h>

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_msgs/Float64.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <thread>
#include <vector>

namespace unexmin {
namespace {

/// UX_1's description (loaded by the .test file) with thruster 0's <dynamics> and <conversion> replaced by the
/// test families.
std::string describedWithTestFamilies(const std::string& urdf) {
  const std::size_t thruster = urdf.find("<thruster id=\"0\"");
  const std::size_t from = urdf.find("<dynamics", thruster);
  const std::size_t to = urdf.find("<thrust ", thruster);
  EXPECT_NE(thruster, std::string::npos);
  EXPECT_LT(from, to);
  const std::string families = "<dynamics type='slew'>" + test::slewParams() +
                               "</dynamics><conversion type='deadband'>" + test::deadbandParams() + "</conversion>";
  return urdf.substr(0, from) + families + urdf.substr(to);
}

class ThrusterFamily : public testing::Test {
protected:
  void SetUp() override {
    ASSERT_TRUE(ros::param::get("/UX_1/robot_description", original_));
    ros::param::set("/UX_1/robot_description", describedWithTestFamilies(original_));
    ros::param::set("~world_file", std::string(UNEXMIN_SOURCE_DIR) + "/worlds/test_box.world");
    ros::param::set("~paused", true);
    ros::param::set("~sensors", std::string("none"));
  }
  void TearDown() override { ros::param::set("/UX_1/robot_description", original_); }

  std::string original_;
};

TEST_F(ThrusterFamily, AnUnknownTypeStopsStartUpNamingThrusterTypeAndKnownTypes) {
  try {
    ros_layer::SimulatorRos sim(ros::NodeHandle(), ros::NodeHandle("~"));
    ADD_FAILURE() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              "/UX_1/robot_description: <thruster id=0>: thruster dynamics: unknown type 'slew'; expected one of: "
              "first_order, zero_order");
  }
}

TEST_F(ThrusterFamily, ARegisteredFamilyIsBuiltCommandedAndSteppedThroughRos) {
  const hydro::ThrusterFactory thrusters = test::withTestFamilies();  // built-in + slew + deadband
  auto sim = std::make_unique<ros_layer::SimulatorRos>(ros::NodeHandle(), ros::NodeHandle("~"),
                                                       ros_layer::SensorRegistry::builtin(), thrusters);

  ros::NodeHandle nh;
  std::mutex mutex;
  std::vector<double> thrust;
  ros::Subscriber sub =
      nh.subscribe<std_msgs::Float64>("/UX_1/thrusters/0/thrust", 1000, [&](const std_msgs::Float64ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        thrust.push_back(m->data);
      });
  ros::Publisher input = nh.advertise<std_msgs::Float64>("/UX_1/thrusters/0/input", 10);
  std::thread spin([&] { sim->spin(); });  // serves /sim/step and runs our callbacks (global queue)

  ros::ServiceClient step = nh.serviceClient<unexmin::Step>("/sim/step");
  ASSERT_TRUE(step.waitForExistence(ros::Duration(30.0)));
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(30.0);
  while ((sub.getNumPublishers() == 0 || input.getNumSubscribers() == 0) && ros::WallTime::now() < deadline)
    ros::WallDuration(0.01).sleep();
  ASSERT_GT(sub.getNumPublishers(), 0u);
  ASSERT_GT(input.getNumSubscribers(), 0u);

  const double command = 30.0;  // [unit], within the description's command range [-40, 40]
  std_msgs::Float64 m;
  m.data = command;
  input.publish(m);
  // The thrust at the end of each /sim/step (the simulator publishes the state it stopped at), waited for.
  const auto stepTo = [&](double duration, std::uint64_t commands, double expected) {
    unexmin::Step srv;
    srv.request.duration = duration;
    srv.request.client = ros::this_node::getName();
    srv.request.commands = commands;  // the step waits until our command is applied
    srv.request.hold = true;
    EXPECT_TRUE(step.call(srv));
    const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(30.0);
    auto last = [&] {
      std::lock_guard<std::mutex> lock(mutex);
      return thrust.empty() ? NAN : thrust.back();
    };
    while (!(std::abs(last() - expected) < 1e-9) && ros::WallTime::now() < until)
      ros::WallDuration(0.01).sleep();
    EXPECT_NEAR(last(), expected, 1e-9) << "thrust at t = " << srv.response.time << " s";
    return srv.response.time;
  };
  const auto closedForm = [](double u, double t) { return test::deadbandThrust(test::slewState(u, t)); };
  const double t1 = stepTo(0.5, 1, closedForm(command, 0.5));  // ramp: x = 10, T = 0.5 (10 - 2) = 4 N
  EXPECT_NEAR(t1, 0.5, 1e-9);
  const double t2 = stepTo(1.0, 1, closedForm(command, 1.5));  // plateau: x = 30, T = 14 N
  EXPECT_NEAR(t2, 1.5, 1e-9);
  ros::shutdown();  // ends sim->spin()
  spin.join();

  std::lock_guard<std::mutex> lock(mutex);
  ASSERT_GE(thrust.size(), 2u);
  EXPECT_TRUE(std::is_sorted(thrust.begin(), thrust.end())) << "the slew ramps up, never down";
  EXPECT_GE(thrust.front(), 0.0);
}

}  // namespace
}  // namespace unexmin

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "thruster_family_test");
  ros::NodeHandle keep;  // keeps roscpp up between the tests
  return RUN_ALL_TESTS();
}

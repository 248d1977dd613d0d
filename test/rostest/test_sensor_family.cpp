// The worked example of docs/adding_a_sensor.md: a sensor family defined only here (a single-beam altimeter:
// one ray along its link's -z, published as sensor_msgs/Range) is registered with its publisher in one call,
// created from a <sensor type="altimeter"> element of the UX-1's description, stepped by the simulator and
// published through ROS; its ranges equal the closed-form distance to the test box's floor. And: the same
// description on a simulator that does not know the family stops start-up with one ConfigError naming the
// robot, the sensor and the known types.
#include <unexmin/ros_layer/simulator_ros.h>
#include <unexmin/sensors/sensor_params.h>

#include "ros_test_main.h"

#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/Range.h>

#include <Eigen/Geometry>

#include <cmath>
#include <mutex>
#include <thread>
#include <vector>

namespace unexmin {
namespace {

// ---------------------------------------------------------------- the family: model (ROS-free) ...
/// Range [m] along the link's -z to the first surface, up to `max_range` [m] (default 10); +inf beyond.
class Altimeter : public sensors::Sensor {
public:
  Altimeter(const sim::SensorSpec& spec, const sensors::SensorSetup& setup) : Sensor(spec, setup) {
    sensors::SensorParams p(spec, setup.robot);
    max_range_ = p.number("max_range", 10.0, 0.01, 1000.0, "m");
    p.finish();  // a misspelt <param> stops start-up
    rays_.resize(1);
  }
  double range() const { return range_; }
  double maxRange() const { return max_range_; }

protected:
  void sample(const sensors::SensorContext& ctx) override {
    const Eigen::Isometry3d link = ctx.state.pose * spec().pose;
    rays_[0].origin = link.translation().cast<float>();
    rays_[0].direction = (-link.linear().col(2)).cast<float>();
    rays_[0].max_range = static_cast<float>(max_range_);
    castRays(ctx, rays_, hits_);
    range_ = hits_[0].range;
  }

private:
  double max_range_ = 10.0;
  double range_ = INFINITY;
  std::vector<raycast::Ray> rays_;
  std::vector<raycast::Hit> hits_;
};

// ---------------------------------------------------------------- ... and its publisher
class AltimeterPublisher : public ros_layer::SensorPublisher {
public:
  AltimeterPublisher(const Altimeter& sensor, const ros_layer::PublisherContext& ctx) : sensor_(sensor) {
    pub_ = ctx.nh.advertise<sensor_msgs::Range>(resolve(ctx.ns, topicParam(sensor, "topic", sensor.name())),
                                                ros_layer::queueSize(sensor.rate()));
  }
  void publish() override {
    sensor_msgs::Range m;
    m.header.stamp.fromSec(sensor_.sampleTime());
    m.header.frame_id = sensor_.frame();
    m.radiation_type = sensor_msgs::Range::ULTRASOUND;
    m.field_of_view = 0.0f;
    m.min_range = 0.0f;
    m.max_range = static_cast<float>(sensor_.maxRange());
    m.range = static_cast<float>(sensor_.range());
    pub_.publish(m);
  }

private:
  const Altimeter& sensor_;
  ros::Publisher pub_;
};

/// UX_1's description (loaded by the .test file) with an altimeter on its base link at `rate` Hz.
std::string describedWithAltimeter(double rate) {
  std::string urdf;
  EXPECT_TRUE(ros::param::get("/UX_1/robot_description", urdf));
  const std::string sensor = "<sensor name='altimeter' type='altimeter' link='UX_1/base_link' rate='" +
                             formatNumber(rate) + "'><param name='max_range' value='5'/></sensor>";
  urdf.insert(urdf.find("</unexmin>"), sensor);
  return urdf;
}

void configure(const std::string& urdf) {
  ros::param::set("/UX_1/robot_description", urdf);
  ros::param::set("~world_file", std::string(UNEXMIN_SOURCE_DIR) + "/worlds/test_box.world");
  ros::param::set("~paused", true);
  ros::param::set("~sensors", std::string("altimeter,imu"));
}

TEST(SensorFamily, AnUnknownTypeStopsStartUpNamingRobotSensorAndKnownTypes) {
  const std::string original = [] {
    std::string u;
    ros::param::get("/UX_1/robot_description", u);
    return u;
  }();
  configure(describedWithAltimeter(10.0));
  ros::param::set("~sensors", std::string("all"));
  try {
    ros_layer::SimulatorRos sim(ros::NodeHandle(), ros::NodeHandle("~"));
    ADD_FAILURE() << "expected ConfigError";
  } catch (const ConfigError& e) {
    std::string known;
    for (const auto& t : ros_layer::SensorRegistry::builtin().types())
      known += (known.empty() ? "" : ", ") + t;
    EXPECT_NE(known.find("imu, m3, magnetometer, msis, pressure"), std::string::npos) << known;
    EXPECT_EQ(std::string(e.what()), "UX_1: sensor 'altimeter': unknown type 'altimeter' (known: " + known + ")");
  }
  ros::param::set("/UX_1/robot_description", original);
}

TEST(SensorFamily, ARegisteredFamilyIsBuiltSteppedAndPublished) {
  const std::string original = [] {
    std::string u;
    ros::param::get("/UX_1/robot_description", u);
    return u;
  }();
  const double rate = 20.0;  // [Hz]
  configure(describedWithAltimeter(rate));

  ros_layer::SensorRegistry registry = ros_layer::SensorRegistry::builtin();
  registry.add<Altimeter, AltimeterPublisher>("altimeter");  // the one registration line
  auto sim = std::make_unique<ros_layer::SimulatorRos>(ros::NodeHandle(), ros::NodeHandle("~"), registry);

  ros::NodeHandle nh;
  std::mutex mutex;
  std::vector<sensor_msgs::Range> ranges;
  nav_msgs::Odometry odom;
  ros::Subscriber sub =
      nh.subscribe<sensor_msgs::Range>("/UX_1/altimeter", 1000, [&](const sensor_msgs::RangeConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        ranges.push_back(*m);
      });
  ros::Subscriber odom_sub =
      nh.subscribe<nav_msgs::Odometry>("/UX_1/odom", 10, [&](const nav_msgs::OdometryConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        odom = *m;
      });
  std::thread spin([&] { sim->spin(); });  // serves /sim/step and runs our callbacks (global queue)

  ros::ServiceClient step = nh.serviceClient<unexmin::Step>("/sim/step");
  ASSERT_TRUE(step.waitForExistence(ros::Duration(30.0)));
  // Wait until the simulator's publisher is connected (it builds messages only for subscribed topics).
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(30.0);
  while (sub.getNumPublishers() == 0 && ros::WallTime::now() < deadline)
    ros::WallDuration(0.01).sleep();
  ASSERT_GT(sub.getNumPublishers(), 0u);

  unexmin::Step srv;
  srv.request.duration = 1.0;  // [s] of sim time: 20 samples at 20 Hz
  ASSERT_TRUE(step.call(srv));
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(30.0);
  auto count = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    return ranges.size();
  };
  while (count() < 20 && ros::WallTime::now() < until)
    ros::WallDuration(0.01).sleep();
  ros::shutdown();  // ends sim->spin()
  spin.join();

  std::lock_guard<std::mutex> lock(mutex);
  ASSERT_EQ(ranges.size(), 20u) << "one Range per 1/20 s of sim time";
  for (std::size_t k = 0; k < ranges.size(); ++k) {
    EXPECT_NEAR(ranges[k].header.stamp.toSec(), (k + 1) / rate, 1e-6);
    EXPECT_EQ(ranges[k].header.frame_id, "UX_1/base_link");
  }
  // Closed form at the last sample (odometry of the same instant, end of the step): the ray from the
  // hull's centre along body -z meets the box floor z = -2 at (z + 2) / -d_z (own hull invisible).
  const auto& p = srv.response.odometry.at(0).pose.pose;
  const Eigen::Quaterniond q(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z);
  const Eigen::Vector3d d = q * Eigen::Vector3d(0, 0, -1);
  EXPECT_NEAR(ranges.back().range, (p.position.z + 2.0) / -d.z(), 2e-3);
  EXPECT_GT(ranges.back().range, 1.5);
  ros::param::set("/UX_1/robot_description", original);
}

}  // namespace
}  // namespace unexmin

int main(int argc, char** argv) {
  return unexmin::test::runRosTests(argc, argv, "sensor_family_test");
}

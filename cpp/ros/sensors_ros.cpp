#include "ros/sensors_ros.h"

#include "ros/dvl_publisher.h"
#include "ros/imu_publisher.h"
#include "ros/m3_publisher.h"    // [sonar]
#include "ros/msis_publisher.h"  // [sonar]
#include "ros/pressure_publisher.h"
#include "sonar/sensor_rays.h"   // [sonar]

#include <functional>
#include <map>

namespace unexmin {
namespace ros_layer {
namespace {

struct PublisherArgs
{
  ros::NodeHandle& nh;
  std::string ns;     ///< "/<robot>/"
  bool kvh_direct;
  bool raw;
};

using PublisherCreator = std::function<std::unique_ptr<SensorPublisher>(sensors::Sensor&, PublisherArgs&)>;

/// Publisher families by sensor type name (the same names as sensors::SensorFactory's).
const std::map<std::string, PublisherCreator>& publisherFamilies()
{
  static const std::map<std::string, PublisherCreator> families{
      {"imu",
       [](sensors::Sensor& s, PublisherArgs& a) -> std::unique_ptr<SensorPublisher> {
         return std::make_unique<ImuPublisher>(dynamic_cast<sensors::ImuSensor&>(s), a.nh, a.ns, a.kvh_direct,
                                               a.raw);
       }},
      {"dvl",
       [](sensors::Sensor& s, PublisherArgs& a) -> std::unique_ptr<SensorPublisher> {
         return std::make_unique<DvlPublisher>(dynamic_cast<sensors::DvlSensor&>(s), a.nh, a.ns);
       }},
      {"pressure",
       [](sensors::Sensor& s, PublisherArgs& a) -> std::unique_ptr<SensorPublisher> {
         return std::make_unique<PressurePublisher>(dynamic_cast<sensors::PressureSensor&>(s), a.nh, a.ns);
       }},
      {"msis",  // [sonar]
       [](sensors::Sensor& s, PublisherArgs& a) -> std::unique_ptr<SensorPublisher> {
         return std::make_unique<MsisPublisher>(dynamic_cast<sonar::MsisSensor&>(s), a.nh, a.ns);
       }},
      {"m3",  // [sonar]
       [](sensors::Sensor& s, PublisherArgs& a) -> std::unique_ptr<SensorPublisher> {
         return std::make_unique<M3Publisher>(dynamic_cast<sonar::M3Sensor&>(s), a.nh, a.ns);
       }},
  };
  return families;
}

}  // namespace

SensorsRos::SensorsRos(sim::World& world, sim::Robot& robot, ros::NodeHandle& nh) : world_(world)
{
  // [sonar] Every ray sensor (DVL, MSIS, M3) casts through the world's shared Embree caster (docs/sonars.md).
  auto rays = sonar::SensorRays::forRobot(world, robot, "embree");
  suite_ = std::make_unique<sensors::SensorSuite>(world, robot, rays);
  PublisherArgs args{nh, "/" + robot.name() + "/", true, false};
  nh.param(args.ns + "kvh_from_simulator", args.kvh_direct, true);
  nh.param(args.ns + "kvh_raw", args.raw, !args.kvh_direct);
  for (std::size_t i = 0; i < suite_->size(); ++i) {
    sensors::Sensor& s = suite_->sensor(i);
    const auto it = publisherFamilies().find(s.type());
    publishers_.push_back(it == publisherFamilies().end() ? nullptr : it->second(s, args));
    if (!publishers_.back())
      ROS_WARN_STREAM(robot.name() << ": sensor '" << s.name() << "' of type " << s.type() << " has no publisher");
    ROS_DEBUG_STREAM(robot.name() << ": sensor '" << s.name() << "' (" << s.type() << ", " << s.rate() << " Hz)");
  }
  for (const auto& name : suite_->skipped())
    ROS_DEBUG_STREAM(robot.name() << ": sensor '" << name << "' is not a navigation sensor; simulated elsewhere");
  last_step_ = world.stepCount();
}

void SensorsRos::publish(std::uint64_t step)
{
  if (step == last_step_) return;
  last_step_ = step;
  suite_->update();
  for (std::size_t i = 0; i < publishers_.size(); ++i)
    if (suite_->fresh(i) && publishers_[i]) publishers_[i]->publish();
}

bool SensorsRos::jointState(const std::string& joint, double& position, double& velocity) const  // [sonar]
{
  for (std::size_t i = 0; i < suite_->size(); ++i) {
    const auto* msis = dynamic_cast<const sonar::MsisSensor*>(&suite_->sensor(i));
    if (!msis || msis->joint() != joint) continue;
    position = msis->headAngle();
    velocity = 0.0;  // a stepper: at rest between steps
    return true;
  }
  return false;
}

void SensorsRos::restart()
{
  suite_->reset(world_.seed());
  last_step_ = world_.stepCount();
}

}  // namespace ros_layer
}  // namespace unexmin

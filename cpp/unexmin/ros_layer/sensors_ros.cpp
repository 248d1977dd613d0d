#include <unexmin/ros_layer/sensors_ros.h>

namespace unexmin {
namespace ros_layer {

SensorsRos::SensorsRos(const sim::World& world, const sim::Robot& robot, sensors::SensorSuite& suite,
                       const SensorRegistry& registry, const sensors::SensorSelection& selection, ros::NodeHandle& nh)
    : world_(world), suite_(suite) {
  const PublisherContext ctx{nh, "/" + robot.name() + "/"};
  for (std::size_t i = 0; i < suite_.size(); ++i) {
    sensors::Sensor& s = suite_.sensor(i);
    publishers_.push_back(registry.publisher(s, ctx));
    ROS_DEBUG_STREAM(robot.name() << ": sensor '" << s.name() << "' (" << s.type() << ", " << s.rate() << " Hz)");
  }
  for (const auto& name : suite_.skipped())
    ROS_INFO_STREAM(robot.name() << ": sensor '" << name << "' is off (sensors:=" << selection.text() << ")");
  last_step_ = world.stepCount();
}

void SensorsRos::publish(std::uint64_t step) {
  if (step == last_step_)
    return;
  last_step_ = step;
  for (std::size_t i = 0; i < publishers_.size(); ++i)
    if (suite_.fresh(i))
      publishers_[i]->publish();
}

void SensorsRos::attach(BagRecorder* recorder) {
  for (auto& p : publishers_)
    p->attach(recorder);
}

void SensorsRos::restart() {
  last_step_ = world_.stepCount();
}

}  // namespace ros_layer
}  // namespace unexmin

#include <unexmin/ros_layer/sensors_ros.h>

namespace unexmin {
namespace ros_layer {

SensorsRos::SensorsRos(sim::World& world, sim::Robot& robot, const raycast::RayCaster* rays,
                       const SensorRegistry& registry, const sensors::SensorSelection& selection, ros::NodeHandle& nh,
                       bool visual)
    : world_(world) {
  suite_ = std::make_unique<sensors::SensorSuite>(world, robot, rays, registry.models(), selection, visual);
  const PublisherContext ctx{nh, "/" + robot.name() + "/"};
  for (std::size_t i = 0; i < suite_->size(); ++i) {
    sensors::Sensor& s = suite_->sensor(i);
    publishers_.push_back(registry.publisher(s, ctx));
    ROS_DEBUG_STREAM(robot.name() << ": sensor '" << s.name() << "' (" << s.type() << ", " << s.rate() << " Hz)");
  }
  for (const auto& name : suite_->skipped())
    ROS_INFO_STREAM(robot.name() << ": sensor '" << name << "' is off (sensors:=" << selection.text() << ")");
  last_step_ = world.stepCount();
}

void SensorsRos::sample(std::uint64_t step) {
  if (step == last_sampled_)
    return;
  last_sampled_ = step;
  suite_->update();
}

void SensorsRos::publish(std::uint64_t step) {
  if (step == last_step_ || step != last_sampled_)
    return;
  last_step_ = step;
  for (std::size_t i = 0; i < publishers_.size(); ++i)
    if (suite_->fresh(i))
      publishers_[i]->publish();
}

void SensorsRos::attach(BagRecorder* recorder) {
  for (auto& p : publishers_)
    p->attach(recorder);
}

void SensorsRos::restart() {
  suite_->reset(world_.seed());
  last_step_ = last_sampled_ = world_.stepCount();
}

}  // namespace ros_layer
}  // namespace unexmin

// ROS plumbing of one robot's simulated sensors: publishes each fresh sample of the robot's sensor suite (built and
// run after every physics step by the engine, engine::Engine) through its family's publisher from the
// SensorRegistry. Sensors publish on their own schedule only (their rate in sim time), never extra at the end of a
// /sim/step: the latest sample of a sensor at rate f is at most 1/f old. See docs/sensors.md and
// docs/adding_a_sensor.md.
#pragma once

#include <unexmin/ros_layer/sensor_registry.h>
#include <unexmin/sensors/sensor_suite.h>

#include <ros/ros.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace unexmin {
namespace ros_layer {

class SensorsRos {
public:
  /// Advertises the topics of `suite`'s sensors (`robot`'s, of the families `selection` keeps) under /<robot>/.
  /// `world` and `suite` (the engine's) must outlive this.
  SensorsRos(const sim::World& world, const sim::Robot& robot, sensors::SensorSuite& suite,
             const SensorRegistry& registry, const sensors::SensorSelection& selection, ros::NodeHandle& nh);

  /// Publishes the samples the suite took at this physics step (call after the step, with the world's step count).
  /// Nothing again for the same step (end of a /sim/step, after a reset).
  void publish(std::uint64_t step);
  /// The world and the suite were reset (step 0): nothing of step 0 goes out.
  void restart();
  /// Hands every sensor message to `recorder` too (null: none); it must outlive this.
  void attach(BagRecorder* recorder);

  sensors::SensorSuite& suite() { return suite_; }
  const sensors::SensorSuite& suite() const { return suite_; }

private:
  const sim::World& world_;
  sensors::SensorSuite& suite_;
  std::vector<std::unique_ptr<SensorPublisher>> publishers_;  ///< one per suite sensor
  std::uint64_t last_step_ = 0;                               ///< last step published
};

}  // namespace ros_layer
}  // namespace unexmin

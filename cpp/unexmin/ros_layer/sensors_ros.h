// ROS plumbing of one robot's simulated sensors: builds every <sensor> of the selected families from the
// robot description through the SensorRegistry (an unknown type stops start-up), runs them after every
// physics step and publishes each fresh sample through its family's publisher. Sensors publish on their own
// schedule only (their rate in sim time), never extra at the end of a /sim/step: the latest sample of a
// sensor at rate f is at most 1/f old. See docs/sensors.md and docs/adding_a_sensor.md.
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
  /// Builds `robot`'s sensors of the families `selection` keeps (throws ConfigError naming the robot, the
  /// sensor and the parameter or the known types on a bad one) and advertises their topics under /<robot>/.
  /// `rays` (the world's caster, updated by its owner after every step; may be null) must outlive this.
  /// `visual`: the simulator's visual mode (/sim/mode), passed to every sensor (SensorSetup::visual).
  SensorsRos(sim::World& world, sim::Robot& robot, const raycast::RayCaster* rays, const SensorRegistry& registry,
             const sensors::SensorSelection& selection, ros::NodeHandle& nh, bool visual = false);

  /// Samples what is due at this physics step (the cameras render, the ray sensors cast). Call after every physics
  /// step with the world's step count; a repeated call for the same step does nothing.
  void sample(std::uint64_t step);
  /// Publishes the samples sample() took at this step. Nothing for a step that was not sampled, nor again for the
  /// same step (end of a /sim/step, after a reset).
  void publish(std::uint64_t step);
  /// The world was reset (new seed, step 0): sensors back to turn-on.
  void restart();
  /// Hands every sensor message to `recorder` too (null: none); it must outlive this.
  void attach(BagRecorder* recorder);

  sensors::SensorSuite& suite() { return *suite_; }
  const sensors::SensorSuite& suite() const { return *suite_; }

private:
  sim::World& world_;
  std::unique_ptr<sensors::SensorSuite> suite_;
  std::vector<std::unique_ptr<SensorPublisher>> publishers_;  ///< one per suite sensor
  std::uint64_t last_step_ = 0;                               ///< last step published
  std::uint64_t last_sampled_ = 0;                            ///< last step sampled
};

}  // namespace ros_layer
}  // namespace unexmin

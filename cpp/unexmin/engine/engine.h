// The simulator's engine, without ROS: one World, the ray caster every ray sensor casts through and every robot's
// sensor suite, composed in one place and stepped in one order (the world, the caster, every robot's sensors). Both
// front ends run it: the simulator node (ros_layer::SimulatorRos adds its parameters, the messages and the pacing)
// and the in-process unexmin.core (cpp/python/world_binding.cpp adds the Python arguments and conversions), so the
// two give the same trajectory and sensor samples for the same world, seed and commands.
#pragma once

#include <unexmin/raycast/ray_caster.h>
#include <unexmin/sensors/sensor_factory.h>
#include <unexmin/sensors/sensor_selection.h>
#include <unexmin/sensors/sensor_suite.h>
#include <unexmin/sim/robot_description.h>
#include <unexmin/sim/world.h>
#include <unexmin/sim/world_config.h>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace unexmin {
namespace engine {

/// How an Engine runs a world, besides the world file's content and the robot descriptions.
struct EngineOptions {
  double dt = 0.002;                   ///< physics step [s] > 0
  std::uint64_t seed = 0;              ///< seed of every random generator (current, sensor noise)
  sensors::SensorSelection selection;  ///< the sensor families that run (none: no ray caster is built)
  bool visual = false;                 ///< visual mode: cameras render, lights and lasers on (SensorSetup::visual)
  int ray_caster_threads = 0;          ///< threads that cast rays, the calling one included (0 = every hardware thread)
};

class Engine {
public:
  /// Spawns the first `robots` robots of `config` (each described in `descriptions` under its name), builds the ray
  /// caster of the world file (`config.ray_caster`; only when a sensor family runs) and every robot's sensors of the
  /// selected families from `models`, which need not outlive the engine. `world_file` names the world in errors.
  /// Throws ConfigError on a bad mesh, a missing description, an unknown ray caster or a bad sensor.
  Engine(const sim::WorldConfig& config, const std::map<std::string, sim::RobotDescription>& descriptions, int robots,
         const sensors::SensorFactory& models, const EngineOptions& options, const std::string& world_file);
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  /// One physics step: when `hold`, every thruster's command is held first (its watchdog does not expire it); then
  /// the world steps, the caster takes the robots' new poses and every robot's sensors that are due sample
  /// (SensorSuite::fresh tells which).
  void step(bool hold = false);
  /// Back to t = 0 with `seed`: the world (robots at spawn at rest, actuators zero, current at its mean) and every
  /// robot's sensors at turn-on.
  void reset(std::uint64_t seed);

  sim::World& world() { return *world_; }
  const sim::World& world() const { return *world_; }
  /// The caster of every ray sensor (null when no sensor runs).
  const raycast::RayCaster* caster() const { return caster_.get(); }
  /// The sensors of world().robot(i).
  sensors::SensorSuite& suite(std::size_t i) { return *suites_.at(i); }
  const sensors::SensorSuite& suite(std::size_t i) const { return *suites_.at(i); }
  const sensors::SensorSelection& selection() const { return selection_; }

private:
  sensors::SensorSelection selection_;
  std::unique_ptr<sim::World> world_;
  std::unique_ptr<raycast::RayCaster> caster_;                 ///< built on world_, updated after every step
  std::vector<std::unique_ptr<sensors::SensorSuite>> suites_;  ///< one per robot, casting through caster_
};

}  // namespace engine
}  // namespace unexmin

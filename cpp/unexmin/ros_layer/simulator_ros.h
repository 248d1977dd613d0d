// The simulator node: runs the engine (engine::Engine: the World, the ray caster, every robot's sensors) at a fixed
// step (lockstep or real time), publishes /clock, /current and every robot's topics, and serves
// /sim/pause|unpause|reset|reset_seed|step. Parameters are documented in docs/simulator_node.md.
#pragma once

#include <unexmin/engine/engine.h>
#include <unexmin/engine/engine_settings.h>
#include <unexmin/hydro/thruster_factory.h>
#include <unexmin/ros_layer/bag_recorder.h>
#include <unexmin/ros_layer/robot_ros.h>
#include <unexmin/ros_layer/sensor_registry.h>
#include <unexmin/ros_layer/subscriber_pacer.h>

#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>
#include <unexmin/Record.h>
#include <unexmin/Reset.h>
#include <unexmin/Step.h>

#include <memory>

namespace unexmin {
namespace ros_layer {

class SimulatorRos {
public:
  /// Loads parameters, the world and the robot descriptions; throws ConfigError with a message naming the
  /// file/parameter and the problem. `registry`: the sensor families it knows, `thrusters`: the thruster
  /// dynamics and conversion families (the built-in ones by default; a test or a user program may add its own).
  SimulatorRos(ros::NodeHandle nh, ros::NodeHandle pnh, SensorRegistry registry = SensorRegistry::builtin(),
               const hydro::ThrusterFactory& thrusters = hydro::ThrusterFactory::builtin());
  /// Runs until shutdown.
  void spin();

private:
  void loadParams();
  void advance(std::uint64_t steps, bool hold = false);
  /// One engine step (commands held when `hold`), then what is due of it goes out.
  void stepOnce(bool hold = false);
  void publishClock();
  /// /clock and every robot's state now (end of a /sim/step, after a reset).
  void publishNow();
  /// Back to step 0 with `seed`: the world, the real-time pacing, every robot's streams; publishes the new state.
  void resetWorld(std::uint64_t seed);
  bool onPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onResetSeed(unexmin::Reset::Request& req, unexmin::Reset::Response& res);
  bool onStep(unexmin::Step::Request& req, unexmin::Step::Response& res);
  bool onRecord(unexmin::Record::Request& req, unexmin::Record::Response& res);

  ros::NodeHandle nh_;
  ros::NodeHandle pnh_;
  ros::CallbackQueue command_queue_;
  ros::NodeHandle command_nh_;

  std::string world_file_;
  engine::EnginePlan plan_;  ///< the world file with the engine's settings applied (engine::planEngine)
  bool realtime_ = false;
  double realtime_factor_ = 1.0;
  int seed_ = 0;
  double physics_rate_ = 500.0;
  double clock_rate_ = 100.0;
  double current_rate_ = 10.0;
  double max_wall_rate_ = 100.0;  ///< lockstep cap on /clock and joint_states [Hz of wall time]
  ros::WallTime last_wall_publish_;
  bool paused_ = false;
  PublishRates rates_;

  SensorRegistry registry_;
  bool visual_ = false;  ///< /sim/mode == visual: cameras render, lights and lasers on
  std::unique_ptr<engine::Engine> engine_;
  sim::World* world_ = nullptr;  ///< the engine's
  std::vector<std::unique_ptr<RobotRos>> robots_;
  std::map<std::string, std::uint64_t> received_;  ///< command messages applied, per publishing node
  Stream clock_pub_;
  Stream current_pub_;
  std::vector<ros::ServiceServer> services_;
  std::uint64_t clock_every_ = 1;
  std::uint64_t current_every_ = 1;
  // Real-time pacing: wall time and sim time when pacing last (re)started.
  ros::WallTime pace_wall_;
  double pace_sim_ = 0.0;
  // The simulator's own recorder (~record, ~record_topics, /sim/record; docs/recording.md).
  std::string record_path_;
  std::unique_ptr<BagRecorder> recorder_;
  // ~lockstep_wait_subscribers: before a lockstep step's messages go out, wait until subscribers took the last ones.
  bool wait_subscribers_ = false;
  SubscriberPacer pacer_;
};

}  // namespace ros_layer
}  // namespace unexmin

#include <unexmin/ros_layer/simulator_ros.h>

#include <unexmin/sim/robot_description.h>

#include <geometry_msgs/Vector3Stamped.h>
#include <rosgraph_msgs/Clock.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace unexmin {
namespace ros_layer {
namespace {

[[noreturn]] void badParam(const std::string& name, const std::string& value, const std::string& expected) {
  throw ParameterError("parameter ~" + name + " = " + value + ": expected " + expected);
}

}  // namespace

SimulatorRos::SimulatorRos(ros::NodeHandle nh, ros::NodeHandle pnh, SensorRegistry registry,
                           const hydro::ThrusterFactory& thrusters)
    : nh_(nh), pnh_(pnh), command_nh_(nh), registry_(std::move(registry)) {
  command_nh_.setCallbackQueue(&command_queue_);
  registry_.check();
  loadParams();

  std::map<std::string, sim::RobotDescription> descriptions;
  for (const std::string& name : plan_.robots) {
    const std::string param = "/" + name + "/robot_description";
    std::string xml;
    if (!nh_.getParam(param, xml))
      throw ConfigError("parameter " + param + " is not set: load the robot description (xacro) first");
    descriptions.emplace(name, sim::parseRobotDescription(xml, param, thrusters));
  }
  const sim::WorldConfig& config = plan_.config;
  engine_ = std::make_unique<engine::Engine>(config, descriptions, static_cast<int>(plan_.robots.size()),
                                             registry_.models(), plan_.options, world_file_);
  world_ = &engine_->world();
  for (std::size_t i = 0; i < world_->robotCount(); ++i)
    robots_.push_back(std::make_unique<RobotRos>(*world_, world_->robot(i), engine_->suite(i), command_nh_, nh_, rates_,
                                                 physics_rate_, received_, registry_, engine_->selection()));

  // What scripts and tools learn from the simulator (docs/simulator_node.md): the spawned robots and their
  // thruster counts.
  std::vector<std::string> names;
  for (std::size_t i = 0; i < world_->robotCount(); ++i) {
    names.push_back(world_->robot(i).name());
    nh_.setParam("/sim/thruster_count/" + world_->robot(i).name(), static_cast<int>(world_->robot(i).thrusterCount()));
  }
  nh_.setParam("/sim/robots", names);

  clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
  current_pub_ = nh_.advertise<geometry_msgs::Vector3Stamped>("/current", 10);
  clock_every_ = every(physics_rate_, clock_rate_);
  current_every_ = every(physics_rate_, current_rate_);
  services_.push_back(nh_.advertiseService("/sim/pause", &SimulatorRos::onPause, this));
  services_.push_back(nh_.advertiseService("/sim/unpause", &SimulatorRos::onUnpause, this));
  services_.push_back(nh_.advertiseService("/sim/reset", &SimulatorRos::onReset, this));
  services_.push_back(nh_.advertiseService("/sim/reset_seed", &SimulatorRos::onResetSeed, this));
  services_.push_back(nh_.advertiseService("/sim/step", &SimulatorRos::onStep, this));
  services_.push_back(nh_.advertiseService("/sim/record", &SimulatorRos::onRecord, this));
  for (auto& r : robots_)
    r->attach(recorder_.get());
  if (!record_path_.empty()) {
    try {
      recorder_->start(record_path_);
    } catch (const std::exception& e) {
      badParam("record", record_path_, std::string("a bag file that can be written (") + e.what() + ")");
    }
  }

  ROS_INFO_STREAM("unexmin simulator: world '"
                  << config.name << "' (" << world_file_ << "), " << world_->robotCount() << " robot(s), physics "
                  << physics_rate_ << " Hz, " << (realtime_ ? "real time" : "lockstep") << ", seed " << seed_
                  << ", sensors " << engine_->selection().text() << ", " << (visual_ ? "visual" : "operational")
                  << " mode, visibility " << config.visibility << (paused_ ? ", paused" : ""));
}

void SimulatorRos::loadParams() {
  if (!pnh_.getParam("world_file", world_file_) || world_file_.empty())
    badParam("world_file", "(unset)", "the path of a world file (YAML), e.g. $(find unexmin)/worlds/tank.world");
  // The engine's settings (checked once, by engine::planEngine); /sim/mode is the one not in ~.
  engine::EngineSettings settings;
  settings.world_file = world_file_;
  pnh_.param("robots", settings.robots, 1);
  std::string spawns;
  pnh_.param<std::string>("spawns", spawns, "");
  std::istringstream names(spawns);
  for (std::string name; std::getline(names, name, ',');)
    if (!name.empty())
      settings.spawns.push_back(name);
  pnh_.param("realtime", realtime_, false);
  pnh_.param("realtime_factor", realtime_factor_, 1.0);
  if (!(realtime_factor_ > 0.0))
    badParam("realtime_factor", formatNumber(realtime_factor_), "> 0");
  int seed = 0;
  pnh_.param("seed", seed, 0);
  settings.seed = seed;
  pnh_.param("paused", paused_, false);
  pnh_.param<std::string>("sensors", settings.sensors, "all");
  nh_.param<std::string>("/sim/mode", settings.mode, "operational");
  pnh_.param<std::string>("visibility", settings.visibility, "");
  pnh_.param("ray_caster_threads", settings.ray_caster_threads, 0);
  pnh_.param("physics_rate", settings.physics_rate, 500.0);
  try {
    plan_ = engine::planEngine(settings, registry_.models(), [](const std::string& name) {
      return name == "mode" ? std::string("parameter /sim/mode") : "parameter ~" + name;
    });
  } catch (const engine::SettingError& e) {
    throw ParameterError(e.what());
  }
  physics_rate_ = settings.physics_rate;
  seed_ = seed;
  visual_ = plan_.options.visual;
  auto rate = [&](const std::string& name, double& value, double fallback) {
    pnh_.param(name, value, fallback);
    if (!std::isfinite(value) || value < 0.0 || value > physics_rate_)
      badParam(name, formatNumber(value), "[0, physics_rate] Hz (0 = off)");
  };
  rate("clock_rate", clock_rate_, 100.0);
  rate("current_rate", current_rate_, 10.0);
  pnh_.param("max_wall_rate", max_wall_rate_, 100.0);
  if (!(max_wall_rate_ > 0.0) || !std::isfinite(max_wall_rate_))
    badParam("max_wall_rate", formatNumber(max_wall_rate_), "> 0 Hz");
  rate("odom_rate", rates_.odom, 50.0);
  rate("joint_state_rate", rates_.joint_states, 50.0);
  rate("thrust_rate", rates_.thrust, 50.0);
  rate("contacts_rate", rates_.contacts, 50.0);
  pnh_.param<std::string>("record", record_path_, "");
  std::string topics_text;
  pnh_.param<std::string>("record_topics", topics_text, "");
  std::vector<std::string> topics;
  std::istringstream words(topics_text);
  for (std::string t; words >> t;) {
    if (t.empty() || t[0] != '/')
      badParam("record_topics", topics_text, "absolute topic names separated by spaces");
    topics.push_back(t);
  }
  recorder_ = std::make_unique<BagRecorder>(topics);
  pnh_.param("lockstep_wait_subscribers", wait_subscribers_, false);
}

void SimulatorRos::publishClock() {
  rosgraph_msgs::Clock c;
  c.clock.fromSec(world_->time());
  recorder_->setTime(world_->time());
  publishRecorded(clock_pub_, recorder_.get(), c);
}

void SimulatorRos::publishNow() {
  recorder_->setTime(world_->time());
  publishClock();
  const ros::Time stamp(world_->time());
  for (auto& r : robots_)
    r->publish(world_->stepCount(), stamp, true);
}

void SimulatorRos::stepOnce(bool hold) {
  engine_->step(hold);  // the world, the caster, every robot's sensors
  const std::uint64_t n = world_->stepCount();
  // lockstep_wait_subscribers: the sensors have sampled (the cameras rendered) while the subscribers were still
  // taking the last step's messages; nothing of this step goes out before they have taken them all. One step's
  // messages (one per stream at most) are then in flight at a time, so neither roscpp's queue on our side nor a
  // subscriber's own queue (rosbag record: 100 per topic, a user's node often 10) can overflow.
  if (wait_subscribers_ && !realtime_)
    pacer_.waitDrained();
  const ros::Time stamp(world_->time());
  recorder_->setTime(world_->time());
  // In real time the sim-time schedules are also wall-time rates. In lockstep, /clock and the
  // viewer streams would otherwise go out RTF times faster and cost more than the physics.
  const double min_wall_period = realtime_ ? 0.0 : 1.0 / max_wall_rate_;
  const ros::WallTime wall_now = realtime_ ? ros::WallTime() : ros::WallTime::now();
  if (clock_every_ && n % clock_every_ == 0 && (wall_now - last_wall_publish_).toSec() >= min_wall_period) {
    publishClock();
    last_wall_publish_ = wall_now;
  }
  for (auto& r : robots_) {
    r->setWallGate(wall_now, min_wall_period);
    r->publish(n, stamp);
  }
  if (current_every_ && n % current_every_ == 0 && wanted(current_pub_, recorder_.get())) {
    geometry_msgs::Vector3Stamped m;
    m.header.stamp = stamp;
    m.header.frame_id = "world";
    const Eigen::Vector3d v = world_->current().velocity();
    m.vector.x = v.x();
    m.vector.y = v.y();
    m.vector.z = v.z();
    publishRecorded(current_pub_, recorder_.get(), m);
  }
}

void SimulatorRos::advance(std::uint64_t steps, bool hold) {
  for (std::uint64_t i = 0; i < steps && ros::ok(); ++i) {
    command_queue_.callAvailable();
    stepOnce(hold);
  }
  publishNow();
}

bool SimulatorRos::onPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  paused_ = true;
  publishClock();
  return true;
}

bool SimulatorRos::onUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  paused_ = false;
  pace_wall_ = ros::WallTime::now();
  pace_sim_ = world_->time();
  return true;
}

void SimulatorRos::resetWorld(std::uint64_t seed) {
  engine_->reset(seed);
  pace_wall_ = ros::WallTime::now();
  pace_sim_ = 0.0;
  for (auto& r : robots_)
    r->restart();
  publishNow();
}

bool SimulatorRos::onReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  resetWorld(world_->seed());
  return true;
}

bool SimulatorRos::onResetSeed(unexmin::Reset::Request& req, unexmin::Reset::Response& res) {
  if (req.seed < 0) {
    ROS_WARN_STREAM("/sim/reset_seed: rejected seed " << req.seed << ", expected >= 0");
    return false;
  }
  resetWorld(static_cast<std::uint64_t>(req.seed));
  res.time = world_->time();
  return true;
}

bool SimulatorRos::onStep(unexmin::Step::Request& req, unexmin::Step::Response& res) {
  std::uint64_t steps = req.steps;
  // 1e6 s of sim time at most per call, as `duration` (a uint32 step count reaches 8.6e6 s at 500 Hz).
  const double max_steps = 1e6 * physics_rate_;
  if (static_cast<double>(steps) > max_steps) {
    ROS_WARN_STREAM("/sim/step: rejected " << steps << " steps, expected at most " << max_steps << " (1e6 s)");
    return false;
  }
  if (steps == 0) {
    if (!std::isfinite(req.duration) || req.duration < 0.0 || req.duration > 1e6) {
      ROS_WARN_STREAM("/sim/step: rejected duration " << req.duration << " s, expected [0, 1e6]");
      return false;
    }
    steps = static_cast<std::uint64_t>(std::llround(req.duration * physics_rate_));
  }
  if (!req.client.empty() && req.commands > 0) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(5.0);
    while (received_[req.client] < req.commands && ros::WallTime::now() < deadline && ros::ok())
      command_queue_.callAvailable(ros::WallDuration(0.001));
    if (received_[req.client] < req.commands)
      ROS_WARN_STREAM("/sim/step: only " << received_[req.client] << " of the " << req.commands << " commands from "
                                         << req.client << " arrived within 5 s; stepping anyway");
  }
  advance(steps, req.hold);
  res.time = world_->time();
  res.step = world_->stepCount();
  const ros::Time stamp(world_->time());
  for (const auto& r : robots_)
    res.odometry.push_back(r->odometry(stamp));
  return true;
}

bool SimulatorRos::onRecord(unexmin::Record::Request& req, unexmin::Record::Response& res) {
  try {
    if (req.path.empty()) {
      if (!recorder_->active()) {
        res.ok = true;
        res.message = "not recording";
        return true;
      }
      std::uint64_t total = 0;
      for (const auto& c : recorder_->counts())
        total += c.second;
      const std::string path = recorder_->path();
      recorder_->stop();
      res.message = "closed " + path + ": " + std::to_string(total) + " messages";
    } else {
      recorder_->setTime(world_->time());
      recorder_->start(req.path);
      res.message = "recording to " + req.path;
    }
    res.ok = true;
  } catch (const std::exception& e) {
    res.ok = false;
    res.message = e.what();
    ROS_WARN_STREAM("/sim/record: " << e.what());
  }
  return true;
}

void SimulatorRos::spin() {
  ros::CallbackQueue* services = ros::getGlobalCallbackQueue();
  publishClock();
  pace_wall_ = ros::WallTime::now();
  pace_sim_ = world_->time();
  // In lockstep, service/command queues are polled every `poll_every` steps; commands therefore
  // apply with at most that much sim-time latency when free-running (none through /sim/step).
  const std::uint64_t poll_every = std::max<std::uint64_t>(1, every(physics_rate_, 1000.0));
  while (ros::ok()) {
    if (paused_) {
      services->callAvailable(ros::WallDuration(0.005));
      command_queue_.callAvailable();
      continue;
    }
    services->callAvailable();
    if (paused_)
      continue;
    for (std::uint64_t i = 0; i < poll_every; ++i) {
      command_queue_.callAvailable();
      stepOnce();
    }
    if (realtime_) {
      const double ahead =
          (world_->time() - pace_sim_) / realtime_factor_ - (ros::WallTime::now() - pace_wall_).toSec();
      if (ahead > 0.0)
        ros::WallDuration(ahead).sleep();
    }
  }
}

}  // namespace ros_layer
}  // namespace unexmin

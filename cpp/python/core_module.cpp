// unexmin._core: the simulator's engine in-process from Python (docs/python_api.md, "unexmin.core"). The engine the
// simulator node runs (engine::Engine: the World, the ray caster, every robot's sensors, stepped in one order), with
// Python's arguments and conversions. No ROS runs: the sensor models come from the simulator's one registration point
// (SensorRegistry::builtin()), whose publishers are never made here.
#include <unexmin/engine/engine.h>
#include <unexmin/ros_layer/sensor_registry.h>
#include <unexmin/sensors/dvl_sensor.h>
#include <unexmin/sensors/imu_sensor.h>
#include <unexmin/sensors/pressure_sensor.h>
#include <unexmin/sensors/sonar/m3_sensor.h>
#include <unexmin/sensors/sonar/msis_sensor.h>
#include <unexmin/sensors/vision/camera_sensor.h>
#include <unexmin/sensors/vision/sls_sensor.h>

#include <btBulletDynamicsCommon.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

namespace py = pybind11;

namespace unexmin {
namespace python {
namespace {

[[noreturn]] void badArgument(const std::string& name, const std::string& value, const std::string& expected) {
  throw py::value_error(name + " = " + value + ": expected " + expected);
}

py::array_t<double> vector3(const Eigen::Vector3d& v) {
  py::array_t<double> a(3);
  auto r = a.mutable_unchecked<1>();
  for (int i = 0; i < 3; ++i)
    r(i) = v[i];
  return a;
}

template <class T>
py::array_t<T> copyOf(const std::vector<T>& v) {
  return py::array_t<T>(static_cast<py::ssize_t>(v.size()), v.data());
}

/// The robot names a world file spawns, in its order.
std::vector<std::string> robotNames(const std::string& world_file) {
  std::vector<std::string> names;
  for (const auto& spawn : sim::loadWorldConfig(world_file).robots)
    names.push_back(spawn.name);
  return names;
}

class CoreWorld {
public:
  /// As the simulator node with ~world_file, ~robots, ~seed, ~sensors, ~visibility, ~physics_rate,
  /// ~ray_caster_threads and /sim/mode; `descriptions`: robot name -> URDF text (xacro expanded).
  CoreWorld(const std::string& world_file, const std::map<std::string, std::string>& descriptions, int robots,
            std::uint64_t seed, const std::string& sensors, const std::string& visibility, double physics_rate,
            const std::string& mode, int ray_caster_threads)
      : registry_(ros_layer::SensorRegistry::builtin()) {
    if (robots < 1 || robots > 3)
      badArgument("robots", std::to_string(robots), "1, 2 or 3");
    if (!(physics_rate >= 100.0 && physics_rate <= 20000.0))
      badArgument("physics_rate", formatNumber(physics_rate), "[100, 20000] Hz");
    if (mode != "operational" && mode != "visual")
      badArgument("mode", "'" + mode + "'", "operational|visual");
    if (visibility != "" && visibility != "none" && visibility != "low" && visibility != "medium" &&
        visibility != "high")
      badArgument("visibility", "'" + visibility + "'", "none|low|medium|high (or empty: the world file's level)");
    if (ray_caster_threads < 0)
      badArgument("ray_caster_threads", std::to_string(ray_caster_threads), ">= 0 (0 = every hardware thread)");

    sim::WorldConfig config = sim::loadWorldConfig(world_file);
    if (!visibility.empty())
      config.visibility = visibility;
    if (robots > static_cast<int>(config.robots.size()))
      badArgument("robots", std::to_string(robots),
                  "at most " + std::to_string(config.robots.size()) + " (spawn poses in " + world_file + ")");
    std::map<std::string, sim::RobotDescription> parsed;
    for (int i = 0; i < robots; ++i) {
      const std::string& name = config.robots[i].name;
      const auto found = descriptions.find(name);
      if (found == descriptions.end())
        badArgument("descriptions", "(no '" + name + "')", "a description of " + name);
      parsed.emplace(name, sim::parseRobotDescription(found->second, name + " description"));
    }
    engine::EngineOptions options;
    options.dt = 1.0 / physics_rate;
    options.seed = seed;
    options.selection = sensors::SensorSelection::parse(sensors, registry_.types(), "sensors");
    options.visual = mode == "visual";
    options.ray_caster_threads = ray_caster_threads;
    engine_ = std::make_unique<engine::Engine>(config, parsed, robots, registry_.models(), options, world_file);
  }

  /// `n` physics steps, each as the simulator's lockstep step (Engine::step): commands held (the watchdog does not
  /// expire them) when `hold`, then the world, the caster, every robot's sensors.
  void step(std::uint64_t n, bool hold) {
    const Busy busy(*this);
    for (std::uint64_t i = 0; i < n; ++i)
      engine_->step(hold);
  }

  void reset(std::uint64_t seed) {
    const Busy busy(*this);
    engine_->reset(seed);
  }

  /// True while step() or reset() runs (in another thread: they release the GIL).
  bool busy() const { return busy_; }
  sim::World& world() {
    idle();
    return engine_->world();
  }
  std::string selection() const { return engine_->selection().text(); }

  std::size_t index(const std::string& robot) const {
    idle();
    const sim::World& world = engine_->world();
    std::vector<std::string> names;
    for (std::size_t i = 0; i < world.robotCount(); ++i) {
      if (world.robot(i).name() == robot)
        return i;
      names.push_back(world.robot(i).name());
    }
    std::string known;
    for (const auto& n : names)
      known += (known.empty() ? "" : ", ") + n;
    throw py::key_error("robot = '" + robot + "': expected one of the spawned robots (" + known + ")");
  }
  sim::Robot& robot(const std::string& name) { return engine_->world().robot(index(name)); }
  sensors::SensorSuite& suite(const std::string& robot) { return engine_->suite(index(robot)); }

  sensors::Sensor& sensor(const std::string& robot, const std::string& name) {
    sensors::SensorSuite& s = suite(robot);
    if (sensors::Sensor* found = s.find(name))
      return *found;
    std::string known;
    for (std::size_t i = 0; i < s.size(); ++i)
      known += (known.empty() ? "" : ", ") + s.sensor(i).name();
    std::string off;
    for (const auto& k : s.skipped())
      off += (off.empty() ? "" : ", ") + k;
    throw py::key_error("sensor = '" + name + "': expected one of " + robot + "'s running sensors (" + known + ")" +
                        (off.empty() ? "" : "; off by sensors='" + selection() + "': " + off));
  }

private:
  /// Marks the world busy for the life of a step() or reset(); a second one at the same time raises.
  struct Busy {
    explicit Busy(CoreWorld& w) : w_(w) {
      if (w_.busy_.exchange(true))
        throw std::runtime_error(kBusy);
    }
    ~Busy() { w_.busy_ = false; }
    CoreWorld& w_;
  };
  static constexpr const char* kBusy =
      "this World is stepping (or resetting) in another thread: wait for that call to return (one thread per World)";
  void idle() const {
    if (busy_)
      throw std::runtime_error(kBusy);
  }

  std::atomic<bool> busy_{false};
  ros_layer::SensorRegistry registry_;
  std::unique_ptr<engine::Engine> engine_;
};

/// A finite command or a ValueError naming it.
double finiteCommand(const std::string& name, double value) {
  if (!std::isfinite(value))
    badArgument(name, formatNumber(value), "a finite number");
  return value;
}

void setThrusts(CoreWorld& w, const std::string& robot, const py::array_t<double, py::array::forcecast>& values) {
  sim::Robot& r = w.robot(robot);
  if (values.ndim() != 1 || static_cast<std::size_t>(values.shape(0)) != r.thrusterCount())
    badArgument("thrusts",
                std::to_string(values.size()) + " values in " + std::to_string(values.ndim()) + " dimension(s)",
                std::to_string(r.thrusterCount()) + " values in one dimension (one per thruster of " + robot + ")");
  auto v = values.unchecked<1>();
  for (std::size_t i = 0; i < r.thrusterCount(); ++i) {
    finiteCommand("thrusts[" + std::to_string(i) + "]", v(i));
    const auto& p = r.thruster(i).params();
    if (v(i) < p.min_command || v(i) > p.max_command)
      badArgument("thrusts[" + std::to_string(i) + "]", formatNumber(v(i)),
                  "[" + formatNumber(p.min_command) + ", " + formatNumber(p.max_command) + "]");
  }
  for (std::size_t i = 0; i < r.thrusterCount(); ++i)
    r.thruster(i).setCommand(v(i), w.world().time());
}

/// Replaces the means of the world's current channels (speed [m/s], horizontal and vertical angle [rad]) and
/// restarts the current at them with the world's seed; each channel's bounds widen to hold its new mean, its noise
/// and return rate stay the world file's, or its noise is zero when `steady` (the current constant at the means).
/// Kept across reset(); the world file is not changed.
void setCurrent(CoreWorld& w, double speed, double horizontal_angle, double vertical_angle, bool steady) {
  hydro::CurrentParams p = w.world().current().params();
  const hydro::CurrentParams& file = w.world().config().current;  // the noise a call without `steady` restores
  const std::tuple<hydro::GaussMarkovParams*, const hydro::GaussMarkovParams*, double> channels[] = {
      {&p.speed, &file.speed, finiteCommand("speed", speed)},
      {&p.horizontal_angle, &file.horizontal_angle, finiteCommand("horizontal_angle", horizontal_angle)},
      {&p.vertical_angle, &file.vertical_angle, finiteCommand("vertical_angle", vertical_angle)}};
  if (speed < 0.0)
    badArgument("speed", formatNumber(speed), "a speed >= 0 m/s");
  for (const auto& [channel, in_file, mean] : channels) {
    channel->mean = mean;
    channel->min = std::min(channel->min, mean);
    channel->max = std::max(channel->max, mean);
    channel->noise = steady ? 0.0 : in_file->noise;
  }
  w.world().current() = hydro::CurrentModel(p, w.world().seed());
}

/// A vector of `n` finite numbers or a ValueError naming `name`.
std::vector<double> finiteVector(const std::string& name, const py::array_t<double, py::array::forcecast>& values,
                                 py::ssize_t n, const std::string& what) {
  if (values.ndim() != 1 || values.shape(0) != n)
    badArgument(name, std::to_string(values.size()) + " values in " + std::to_string(values.ndim()) + " dimension(s)",
                std::to_string(n) + " numbers in one dimension (" + what + ")");
  const auto r = values.unchecked<1>();  // by its strides: a column or a reversed view reads its own numbers
  std::vector<double> v(static_cast<std::size_t>(n));
  for (py::ssize_t i = 0; i < n; ++i)
    v[static_cast<std::size_t>(i)] = finiteCommand(name + "[" + std::to_string(i) + "]", r(i));
  return v;
}

/// Teleports the robot's base link to `position` [m] and `orientation` (unit quaternion x, y, z, w) in the world
/// frame, at rest (Robot::setPose): from the next step on the physics and the sensors see it there. Both are checked
/// before anything moves.
void setPose(CoreWorld& w, const std::string& robot, const py::array_t<double, py::array::forcecast>& position,
             const py::array_t<double, py::array::forcecast>& orientation) {
  sim::Robot& r = w.robot(robot);
  const std::vector<double> p = finiteVector("position", position, 3, "x, y, z [m], world frame");
  const std::vector<double> q = finiteVector("orientation", orientation, 4, "a unit quaternion x, y, z, w");
  const Eigen::Quaterniond quat(q[3], q[0], q[1], q[2]);
  if (std::abs(quat.norm() - 1.0) > 1e-6)
    badArgument("orientation", "a quaternion of norm " + formatNumber(quat.norm()),
                "a unit quaternion x, y, z, w (norm 1 within 1e-6)");
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = quat.normalized().toRotationMatrix();
  pose.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  r.setPose(pose);
}

/// Whether camera `name` renders its frames in visual mode: off, its samples only move the schedule (as when nobody
/// subscribes to its image topic), on (the default) it renders every sample.
void setRendering(CoreWorld& w, const std::string& robot, const std::string& name, bool on) {
  auto* cam = dynamic_cast<sensors::vision::CameraSensor*>(&w.sensor(robot, name));
  if (cam == nullptr)
    badArgument("sensor", "'" + name + "' (family " + w.sensor(robot, name).type() + ")", "a camera");
  cam->setDemand(on ? std::function<bool()>() : [] { return false; });
}

/// The silt the thrusters raised: one row per puff (sim/sediment.h).
py::dict sediment(CoreWorld& w) {
  const auto& puffs = w.world().sediment().puffs();
  std::vector<double> centre, sigma, strength, floor_z;
  for (const auto& p : puffs) {
    for (int k = 0; k < 3; ++k)
      centre.push_back(p.centre[k]);
    sigma.push_back(p.sigma);
    strength.push_back(p.strength);
    floor_z.push_back(p.floor_z);
  }
  py::dict d;
  d["centre"] = copyOf(centre).reshape({static_cast<py::ssize_t>(puffs.size()), py::ssize_t(3)});
  d["sigma"] = copyOf(sigma);
  d["strength"] = copyOf(strength);
  d["floor_z"] = copyOf(floor_z);
  return d;
}

/// The world's `sediment:` block in force.
py::dict sedimentParams(CoreWorld& w) {
  const sim::SedimentParams& p = w.world().sediment().params();
  py::dict d;
  d["enabled"] = p.enabled;
  d["settling_speed"] = p.settling_speed;
  d["raise"] = p.raise;
  d["reach"] = p.reach;
  d["puff_size"] = p.puff_size;
  d["diffusivity"] = p.diffusivity;
  d["interval"] = p.interval;
  d["max_puffs"] = p.max_puffs;
  return d;
}

/// Ground truth of the base link as the simulator's odometry: pose in world, twist in the body frame (REP-105),
/// plus the body-frame linear acceleration over the last step.
py::dict state(CoreWorld& w, const std::string& robot) {
  const sim::RobotState s = w.robot(robot).state();
  const Eigen::Quaterniond q(s.pose.linear());
  const Eigen::Matrix3d Rt = s.pose.linear().transpose();
  py::dict d;
  d["time"] = w.world().time();
  d["position"] = vector3(s.pose.translation());
  py::array_t<double> quat(4);
  auto qr = quat.mutable_unchecked<1>();
  qr(0) = q.x();
  qr(1) = q.y();
  qr(2) = q.z();
  qr(3) = q.w();
  d["orientation"] = quat;
  d["linear_velocity"] = vector3(Rt * s.linear_velocity);
  d["angular_velocity"] = vector3(Rt * s.angular_velocity);
  d["linear_acceleration"] = vector3(Rt * s.linear_acceleration);
  return d;
}

/// Where the robot's hull touches something now (the world's meshes, another robot): Bullet's contact points of the
/// last step with a distance <= 0, read through its public contact manifolds.
py::dict contacts(CoreWorld& w, const std::string& robot) {
  const btCollisionObject* body = w.robot(robot).body();
  btDispatcher* dispatcher = w.world().physics().getDispatcher();
  std::vector<double> position, normal, depth, impulse;
  for (int i = 0; i < dispatcher->getNumManifolds(); ++i) {
    const btPersistentManifold* m = dispatcher->getManifoldByIndexInternal(i);
    const bool first = m->getBody0() == body;
    if (!first && m->getBody1() != body)
      continue;
    for (int j = 0; j < m->getNumContacts(); ++j) {
      const btManifoldPoint& p = m->getContactPoint(j);
      if (p.getDistance() > 0.0)
        continue;
      // Bullet's normal points from body 1 to body 0: turn it to point from the obstacle into the robot.
      const btVector3 at = first ? p.getPositionWorldOnB() : p.getPositionWorldOnA();
      const btVector3 n = first ? p.m_normalWorldOnB : -p.m_normalWorldOnB;
      for (int k = 0; k < 3; ++k) {
        position.push_back(at[k]);
        normal.push_back(n[k]);
      }
      depth.push_back(-p.getDistance());
      impulse.push_back(p.getAppliedImpulse());
    }
  }
  const py::ssize_t n = static_cast<py::ssize_t>(depth.size());
  py::dict d;
  d["position"] = copyOf(position).reshape({n, py::ssize_t(3)});
  d["normal"] = copyOf(normal).reshape({n, py::ssize_t(3)});
  d["depth"] = copyOf(depth);
  d["impulse"] = copyOf(impulse);
  return d;
}

/// The newest sample of one sensor as numpy arrays (copies, except camera images: see below).
py::dict sample(CoreWorld& w, const std::string& robot, const std::string& name, py::object owner) {
  sensors::Sensor& s = w.sensor(robot, name);
  py::dict d;
  d["name"] = s.name();
  d["type"] = s.type();
  d["time"] = s.sampleTime();
  d["count"] = s.sampleCount();
  if (auto* imu = dynamic_cast<sensors::ImuSensor*>(&s)) {
    const auto& x = imu->last();
    d["specific_force"] = vector3(x.specific_force);
    d["angular_velocity"] = vector3(x.angular_velocity);
    d["magnetic_field"] = vector3(x.magnetic_field);
    d["temperature"] = x.temperature;
    d["pressure"] = x.pressure;
  } else if (auto* dvl = dynamic_cast<sensors::DvlSensor*>(&s)) {
    const auto& x = dvl->last();
    d["bottom_lock"] = x.bottom_lock;
    d["velocity"] = vector3(x.velocity);
    d["altitude"] = x.altitude;
    d["pressure"] = x.pressure;
    d["temperature"] = x.temperature;
    d["sound_speed"] = x.sound_speed;
    py::array_t<double> range(4), velocity(4);
    py::array_t<bool> valid(4);
    for (int i = 0; i < 4; ++i) {
      range.mutable_at(i) = x.beams[i].range;
      velocity.mutable_at(i) = x.beams[i].velocity;
      valid.mutable_at(i) = x.beams[i].valid;
    }
    d["beam_range"] = range;
    d["beam_velocity"] = velocity;
    d["beam_valid"] = valid;
  } else if (auto* p = dynamic_cast<sensors::PressureSensor*>(&s)) {
    d["pressure"] = p->last().pressure;
  } else if (auto* m3 = dynamic_cast<sensors::sonar::M3Sensor*>(&s)) {
    d["ranges"] = copyOf(m3->last().ranges);
    d["intensities"] = copyOf(m3->last().intensities);
    py::array_t<double> angles(static_cast<py::ssize_t>(m3->beams()));
    for (std::size_t k = 0; k < m3->beams(); ++k)
      angles.mutable_at(k) = m3->beamAngle(k);
    d["beam_angles"] = angles;
  } else if (auto* msis = dynamic_cast<sensors::sonar::MsisSensor*>(&s)) {
    d["angle"] = msis->last().angle;
    d["intensity"] = copyOf(msis->last().intensity);
  } else if (auto* sls = dynamic_cast<sensors::vision::SlsSensor*>(&s)) {
    const auto& x = sls->last();
    d["motor_angle"] = x.motor_angle;
    d["ranges"] = copyOf(x.ranges);
    py::array_t<float> points({static_cast<py::ssize_t>(x.points.size()), py::ssize_t(3)});
    auto pr = points.mutable_unchecked<2>();
    for (std::size_t i = 0; i < x.points.size(); ++i)
      for (int j = 0; j < 3; ++j)
        pr(i, j) = x.points[i][j];
    d["points"] = points;
    d["intensity"] = copyOf(x.intensity);
  } else if (auto* cam = dynamic_cast<sensors::vision::CameraSensor*>(&s)) {
    const auto& f = cam->last();
    d["rendered"] = f.rendered;
    // The camera's CameraInfo numbers (the model the publisher reads): K (3 x 3, row-major as CameraInfo's) and D
    // (plumb_bob k1 k2 p1 p2 k3) of the published image.
    const auto k = cam->model().K();
    py::array_t<double> K({py::ssize_t(3), py::ssize_t(3)});
    std::copy(k.begin(), k.end(), K.mutable_data());
    d["K"] = K;
    const auto& dist = cam->model().distortion();
    d["D"] = py::array_t<double>(py::ssize_t(dist.size()), dist.data());
    if (f.rendered) {
      // A view of the frame the camera keeps (no copy): valid until the next step() or reset().
      d["image"] =
          py::array_t<std::uint8_t>({py::ssize_t(f.height), py::ssize_t(f.width), py::ssize_t(3)}, f.rgb.data(), owner);
    }
  }
  return d;
}

}  // namespace
}  // namespace python
}  // namespace unexmin

using unexmin::python::CoreWorld;
using namespace unexmin;
using namespace unexmin::python;

PYBIND11_MODULE(_core, m) {
  m.doc() = "The unexmin simulator's engine in-process (use unexmin.core; docs/python_api.md)";
  py::register_exception<ConfigError>(m, "ConfigError", PyExc_ValueError);
  m.def("robot_names", &robotNames, py::arg("world_file"), "Robot names the world file spawns, in its order.");
  py::class_<CoreWorld>(m, "World")
      .def(py::init<const std::string&, const std::map<std::string, std::string>&, int, std::uint64_t,
                    const std::string&, const std::string&, double, const std::string&, int>(),
           py::arg("world_file"), py::arg("descriptions"), py::arg("robots"), py::arg("seed"), py::arg("sensors"),
           py::arg("visibility"), py::arg("physics_rate"), py::arg("mode"), py::arg("ray_caster_threads"))
      .def("step", &CoreWorld::step, py::arg("n"), py::arg("hold"), py::call_guard<py::gil_scoped_release>())
      .def("reset", &CoreWorld::reset, py::arg("seed"), py::call_guard<py::gil_scoped_release>())
      .def_property_readonly("busy", &CoreWorld::busy)
      .def_property_readonly("time", [](CoreWorld& w) { return w.world().time(); })
      .def_property_readonly("step_count", [](CoreWorld& w) { return w.world().stepCount(); })
      .def_property_readonly("dt", [](CoreWorld& w) { return w.world().dt(); })
      .def_property_readonly("seed", [](CoreWorld& w) { return w.world().seed(); })
      .def_property_readonly("visibility", [](CoreWorld& w) { return w.world().config().visibility; })
      .def_property_readonly("sensors", &CoreWorld::selection)
      .def_property_readonly("current", [](CoreWorld& w) { return vector3(w.world().current().velocity()); })
      .def("set_current", &setCurrent, py::arg("speed"), py::arg("horizontal_angle"), py::arg("vertical_angle"),
           py::arg("steady"))
      .def("sediment", &sediment)
      .def_property_readonly("sediment_params", &sedimentParams)
      .def_property_readonly("robots",
                             [](CoreWorld& w) {
                               std::vector<std::string> names;
                               for (std::size_t i = 0; i < w.world().robotCount(); ++i)
                                 names.push_back(w.world().robot(i).name());
                               return names;
                             })
      .def("thruster_count", [](CoreWorld& w, const std::string& r) { return w.robot(r).thrusterCount(); })
      .def("set_thrusts", &setThrusts, py::arg("robot"), py::arg("values"))
      .def("thrusts",
           [](CoreWorld& w, const std::string& r) {
             sim::Robot& robot = w.robot(r);
             std::vector<double> t;
             for (std::size_t i = 0; i < robot.thrusterCount(); ++i)
               t.push_back(robot.thruster(i).thrust());
             return copyOf(t);
           })
      .def("set_pendulum",
           [](CoreWorld& w, const std::string& r, double angle) {
             sim::Robot& robot = w.robot(r);
             finiteCommand("angle", angle);
             if (!robot.hasPendulum())
               badArgument("robot", "'" + r + "'", "a robot with a pendulum");
             const auto& p = robot.pendulum().params();
             if (!robot.pendulum().setTarget(angle))
               badArgument("angle", formatNumber(angle),
                           "[" + formatNumber(p.min_angle) + ", " + formatNumber(p.max_angle) + "] rad");
           })
      .def("set_vbs",
           [](CoreWorld& w, const std::string& r, double mass) {
             sim::Robot& robot = w.robot(r);
             finiteCommand("mass", mass);
             const auto& p = robot.vbs().params();
             if (!robot.vbs().setMass(mass))
               badArgument("mass", formatNumber(mass),
                           "[" + formatNumber(p.min_mass) + ", " + formatNumber(p.max_mass) + "] kg");
           })
      .def("state", &state, py::arg("robot"))
      .def("set_pose", &setPose, py::arg("robot"), py::arg("position"), py::arg("orientation"))
      .def("set_rendering", &setRendering, py::arg("robot"), py::arg("sensor"), py::arg("on"))
      .def("contacts", &contacts, py::arg("robot"))
      .def("sensor_names",
           [](CoreWorld& w, const std::string& r) {
             std::vector<std::pair<std::string, std::string>> out;
             auto& s = w.suite(r);
             for (std::size_t i = 0; i < s.size(); ++i)
               out.emplace_back(s.sensor(i).name(), s.sensor(i).type());
             return out;
           })
      .def("base_link", [](CoreWorld& w, const std::string& r) { return w.robot(r).description().base_link; })
      .def("sample_count",
           [](CoreWorld& w, const std::string& r, const std::string& name) { return w.sensor(r, name).sampleCount(); })
      .def("sample", [](py::object self, const std::string& r, const std::string& name) {
        return sample(self.cast<CoreWorld&>(), r, name, self);
      });
}

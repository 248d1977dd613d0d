// The engine in-process from Python (docs/python_api.md, "unexmin.core"): the engine the simulator node runs
// (engine::Engine: the World, the ray caster, every robot's sensors, stepped in one order), with Python's arguments
// and conversions. Knows no ROS and no sensor family: a sample reaches Python through its family's description
// (Sensor::describe), the settings are checked by engine::planEngine.
#include "world_binding.h"

#include <unexmin/engine/engine.h>
#include <unexmin/engine/engine_settings.h>
#include <unexmin/engine/mapper.h>
#include <unexmin/sim/contacts.h>
#include <unexmin/sim/world_schema.h>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <optional>
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

/// engine::EngineSettings from Python's arguments (named as unexmin.core.World's).
engine::EngineSettings settingsOf(const std::string& world_file, int robots, const std::vector<std::string>& spawns,
                                  std::int64_t seed, const std::string& sensors, const std::string& visibility,
                                  double physics_rate, const std::string& mode, int ray_caster_threads) {
  engine::EngineSettings s;
  s.world_file = world_file;
  s.robots = robots;
  s.spawns = spawns;
  s.seed = seed;
  s.sensors = sensors;
  s.visibility = visibility;
  s.physics_rate = physics_rate;
  s.mode = mode;
  s.ray_caster_threads = ray_caster_threads;
  return s;
}

class CoreWorld {
public:
  /// As the simulator node with ~world_file, ~robots, ~spawns, ~seed, ~sensors, ~visibility, ~physics_rate,
  /// ~ray_caster_threads and /sim/mode (checked by engine::planEngine); `descriptions`: robot name -> URDF text
  /// (xacro expanded) of every robot that runs; `families`: the sensor families.
  /// `mapping`: the in-process mapper's settings (engine::mapperSettings' names; none: no mapper).
  CoreWorld(const engine::EngineSettings& settings, const std::map<std::string, std::string>& descriptions,
            sensors::SensorFactory families,
            const std::optional<std::map<std::string, engine::MapperValue>>& mapping = std::nullopt)
      : families_(std::move(families)) {
    // The mapper's settings first: a bad one raises before the world is built.
    const std::optional<engine::MapperSettings> mapper_settings =
        mapping ? std::optional<engine::MapperSettings>(engine::mapperSettings(*mapping)) : std::nullopt;
    const engine::EnginePlan plan = engine::planEngine(settings, families_);
    std::map<std::string, sim::RobotDescription> parsed;
    for (const std::string& name : plan.robots) {
      const auto found = descriptions.find(name);
      if (found == descriptions.end())
        badArgument("descriptions", "(no '" + name + "')", "a description of " + name);
      parsed.emplace(name, sim::parseRobotDescription(found->second, name + " description"));
    }
    engine_ = std::make_unique<engine::Engine>(plan.config, parsed, static_cast<int>(plan.robots.size()), families_,
                                               plan.options, settings.world_file);
    if (mapper_settings)
      mapper_ = std::make_unique<engine::Mapper>(*engine_, *mapper_settings);
  }

  /// `n` physics steps, each as the simulator's lockstep step (Engine::step): commands held (the watchdog does not
  /// expire them) when `hold`, then the world, the caster, every robot's sensors.
  void step(std::uint64_t n, bool hold) {
    const Busy busy(*this);
    for (std::uint64_t i = 0; i < n; ++i) {
      engine_->step(hold);
      if (mapper_)
        mapper_->afterStep();
    }
  }

  void reset(std::uint64_t seed) {
    const Busy busy(*this);
    engine_->reset(seed);
    if (mapper_)
      mapper_->afterReset();
  }

  /// The in-process mapper; RuntimeError when the World was made without `mapping`.
  engine::Mapper& mapper() {
    idle();
    if (!mapper_)
      throw std::runtime_error("this World maps nothing: make it with mapping=True (or a dict of mapper parameters)");
    return *mapper_;
  }
  bool mapping() const { return mapper_ != nullptr; }

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
  sensors::SensorFactory families_;
  std::unique_ptr<engine::Engine> engine_;
  std::unique_ptr<engine::Mapper> mapper_;  ///< on engine_, stepped after it (null: no mapping)
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
/// The world's water column at `point` now (water::WaterColumn::at); None in a world without one.
py::object waterAt(CoreWorld& w, const std::vector<double>& point) {
  if (point.size() != 3 || !std::all_of(point.begin(), point.end(), [](double v) { return std::isfinite(v); }))
    throw py::value_error("point: expected 3 finite numbers [m], world frame");
  const auto& column = w.world().config().water_column;
  if (!column)
    return py::none();
  const water::WaterSample s = column->at(Eigen::Vector3d(point[0], point[1], point[2]), w.world().time());
  py::dict d;
  d["depth"] = s.depth;
  d["temperature"] = s.temperature;
  d["salinity"] = s.salinity;
  d["conductivity"] = s.conductivity;
  d["ph"] = s.ph;
  d["redox"] = s.redox;
  d["oxygen"] = s.oxygen;
  d["turbidity"] = s.turbidity;
  d["density"] = s.density;
  d["sound_speed"] = s.sound_speed;
  return std::move(d);
}

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

/// Where the robot's hull touches something now (sim::contacts): position (N x 3) [m], normal (N x 3), depth (N) [m],
/// impulse (N) [N s].
py::dict contacts(CoreWorld& w, const std::string& robot) {
  const std::vector<sim::Contact> found = sim::contacts(w.world(), w.robot(robot));
  std::vector<double> position, normal, depth, impulse;
  for (const auto& c : found) {
    for (int k = 0; k < 3; ++k) {
      position.push_back(c.position[k]);
      normal.push_back(c.normal[k]);
    }
    depth.push_back(c.depth);
    impulse.push_back(c.impulse);
  }
  const py::ssize_t n = static_cast<py::ssize_t>(found.size());
  py::dict d;
  d["position"] = copyOf(position).reshape({n, py::ssize_t(3)});
  d["normal"] = copyOf(normal).reshape({n, py::ssize_t(3)});
  d["depth"] = copyOf(depth);
  d["impulse"] = copyOf(impulse);
  return d;
}

/// The in-process map's counters (the mapper node's ~stats).
py::dict mapStats(CoreWorld& w) {
  engine::Mapper& m = w.mapper();
  const engine::MapperStats s = m.stats();
  py::dict d;
  d["clouds_received"] = s.clouds_received;
  d["clouds_inserted"] = s.clouds_inserted;
  d["clouds_dropped"] = s.clouds_dropped;
  d["pending"] = s.pending;
  d["points_inserted"] = s.points_inserted;
  d["occupied_leaves"] = m.map().occupiedLeafCount();
  d["memory_bytes"] = m.map().memoryUsage();
  d["sources"] = m.sources();
  return d;
}

/// The settings in force, by the names mapperSettings() takes.
py::dict mapSettings(CoreWorld& w) {
  const engine::MapperSettings& s = w.mapper().settings();
  py::dict d;
  d["resolution"] = s.params.resolution;
  d["max_range"] = s.params.max_range;
  d["prob_hit"] = s.params.prob_hit;
  d["prob_miss"] = s.params.prob_miss;
  d["clamp_min"] = s.params.clamp_min;
  d["clamp_max"] = s.params.clamp_max;
  d["m3"] = s.sources.m3;
  d["sls_units"] = s.sources.sls_units;
  d["sonar"] = s.sources.sonar;
  d["sonar_topic"] = s.sources.sonar_topic;
  d["dvl"] = s.sources.dvl;
  d["m3_max_range"] = s.sources.m3_max_range;
  d["sls_max_range"] = s.sources.sls_max_range;
  d["sonar_max_range"] = s.sources.sonar_max_range;
  d["dvl_max_range"] = s.sources.dvl_max_range;
  d["frame_id"] = s.frame_id;
  d["tf_max_gap"] = s.tf_max_gap;
  d["tf_rate"] = s.tf_rate;
  d["sonar_threshold"] = s.sonar_threshold;
  return d;
}

/// The occupied leaves of the map: centre x, y, z and edge, one row each (N x 4) [m, the map's frame].
py::array_t<double> occupiedVoxels(CoreWorld& w) {
  const std::vector<mapping::Voxel> voxels = w.mapper().map().occupiedVoxels();
  std::vector<double> rows;
  rows.reserve(4 * voxels.size());
  for (const auto& v : voxels)
    rows.insert(rows.end(), {v.x, v.y, v.z, v.size});
  return copyOf(rows).reshape({static_cast<py::ssize_t>(voxels.size()), py::ssize_t(4)});
}

/// A sample's fields as a dict: scalars as Python numbers, arrays as numpy arrays of the field's type and shape
/// (copies, except a field the model keeps: a view owned by `owner`, valid until the next step() or reset()).
class DictWriter : public sensors::SampleWriter {
public:
  DictWriter(py::dict& d, py::object owner) : d_(d), owner_(std::move(owner)) {}
  void field(const sensors::SampleField& f) override {
    if (f.shape.empty()) {
      d_[f.name.c_str()] = scalar(f);
      return;
    }
    std::vector<py::ssize_t> shape(f.shape.begin(), f.shape.end());
    const py::dtype type(sensors::fieldTypeName(f.type));
    d_[f.name.c_str()] = f.kept ? py::array(type, shape, f.data, owner_) : py::array(type, shape, f.data);
  }

private:
  static py::object scalar(const sensors::SampleField& f) {
    switch (f.type) {
      case sensors::FieldType::float64:
        return py::float_(*static_cast<const double*>(f.data));
      case sensors::FieldType::float32:
        return py::float_(*static_cast<const float*>(f.data));
      case sensors::FieldType::uint8:
        return py::int_(*static_cast<const std::uint8_t*>(f.data));
      case sensors::FieldType::uint64:
        return py::int_(*static_cast<const std::uint64_t*>(f.data));
      case sensors::FieldType::boolean:
        return py::bool_(*static_cast<const bool*>(f.data));
    }
    return py::none();
  }
  py::dict& d_;
  py::object owner_;
};

/// The fields a sensor's sample holds: one (name, unit, dtype, shape) per field, in the family's order.
class FieldList : public sensors::SampleWriter {
public:
  void field(const sensors::SampleField& f) override {
    fields.emplace_back(f.name, f.unit, sensors::fieldTypeName(f.type), f.shape);
  }
  std::vector<std::tuple<std::string, std::string, std::string, std::vector<std::size_t>>> fields;
};

/// The newest sample of one sensor: its name, type and its family's fields (Sensor::describe).
py::dict sample(CoreWorld& w, const std::string& robot, const std::string& name, py::object owner) {
  sensors::Sensor& s = w.sensor(robot, name);
  py::dict d;
  d["name"] = s.name();
  d["type"] = s.type();
  DictWriter writer(d, std::move(owner));
  s.describe(writer);
  return d;
}

}  // namespace

void bindWorld(py::module_& m, std::function<sensors::SensorFactory()> families) {
  static py::exception<ConfigError> config_error(m, "ConfigError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p)
        std::rethrow_exception(p);
    } catch (const engine::SettingError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const ConfigError& e) {
      config_error(e.what());
    }
  });
  m.def("robot_names", &robotNames, py::arg("world_file"), "Robot names the world file spawns, in its order.");
  m.def("families", [families] { return families().types(); }, "The sensor families, sorted.");
  m.def("modes", [] { return engine::modes(); }, "The modes a world runs in.");
  m.def("mapper_setting_names", [] { return engine::mapperSettingNames(); }, "The in-process mapper's settings.");
  m.def("visibility_levels", [] { return sim::visibilityLevels(); }, "The world schema's visibility levels.");
  m.def(
      "setting_rules", [families] { return engine::settingRules(families()); },
      "(setting, what it accepts) of every engine setting, as the errors state them.");
  m.def(
      "check_settings",
      [families](int robots, std::int64_t seed, const std::string& sensors, const std::string& visibility,
                 double physics_rate, const std::string& mode, int ray_caster_threads) {
        engine::checkSettings(
            settingsOf("", robots, {}, seed, sensors, visibility, physics_rate, mode, ray_caster_threads), families());
      },
      py::arg("robots") = 1, py::arg("seed") = 0, py::arg("sensors") = "all", py::arg("visibility") = "",
      py::arg("physics_rate") = 500.0, py::arg("mode") = "operational", py::arg("ray_caster_threads") = 0,
      "ValueError naming the first engine setting out of its domain (engine::checkSettings).");
  m.def(
      "spawned_robots",
      [families](const std::string& world_file, int robots, const std::vector<std::string>& spawns) {
        engine::EngineSettings s = settingsOf(world_file, robots, spawns, 0, "none", "", 500.0, "operational", 0);
        const engine::EnginePlan plan = engine::planEngine(s, families());
        std::vector<std::pair<std::string, std::string>> out;  // (name, description file), as the world file gives
        for (std::size_t i = 0; i < plan.robots.size(); ++i)
          out.emplace_back(plan.robots[i], plan.config.robots[i].description);
        return out;
      },
      py::arg("world_file"), py::arg("robots"), py::arg("spawns"),
      "(name, description file in urdf/) of the robots a world runs with `robots` (the first ones) or `spawns` "
      "(these, in this order).");
  py::class_<CoreWorld>(m, "World", py::module_local())
      .def(py::init([families](const std::string& world_file, const std::map<std::string, std::string>& descriptions,
                               int robots, const std::vector<std::string>& spawns, std::int64_t seed,
                               const std::string& sensors, const std::string& visibility, double physics_rate,
                               const std::string& mode, int ray_caster_threads,
                               const std::optional<std::map<std::string, engine::MapperValue>>& mapping) {
             return std::make_unique<CoreWorld>(settingsOf(world_file, robots, spawns, seed, sensors, visibility,
                                                           physics_rate, mode, ray_caster_threads),
                                                descriptions, families(), mapping);
           }),
           py::arg("world_file"), py::arg("descriptions"), py::arg("robots"), py::arg("spawns"), py::arg("seed"),
           py::arg("sensors"), py::arg("visibility"), py::arg("physics_rate"), py::arg("mode"),
           py::arg("ray_caster_threads"), py::arg("mapping") = py::none())
      .def_property_readonly("mapping", &CoreWorld::mapping)
      .def("map_stats", &mapStats)
      .def("map_settings", &mapSettings)
      .def("occupied_voxels", &occupiedVoxels)
      .def(
          "save_map",
          [](CoreWorld& w, const std::string& path) {
            w.mapper().map().save(path);
            return w.mapper().map().occupiedLeafCount();
          },
          py::arg("path"))
      .def("clear_map", [](CoreWorld& w) { w.mapper().clear(); })
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
      .def("water", &waterAt, py::arg("point"))
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
      .def(
          "set_rendering",
          [](CoreWorld& w, const std::string& r, const std::string& name, bool on) {
            w.sensor(r, name).setRendering(on);
          },
          py::arg("robot"), py::arg("sensor"), py::arg("on"))
      .def(
          "fire", [](CoreWorld& w, const std::string& r, const std::string& name) { return w.sensor(r, name).fire(); },
          py::arg("robot"), py::arg("sensor"))
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
      .def("sample", [](py::object self, const std::string& r,
                        const std::string& name) { return sample(self.cast<CoreWorld&>(), r, name, self); })
      .def("sample_fields", [](CoreWorld& w, const std::string& r, const std::string& name) {
        FieldList list;
        w.sensor(r, name).describe(list);
        return list.fields;
      });
}

}  // namespace python
}  // namespace unexmin

#include <unexmin/engine/mapper.h>

#include <unexmin/core/error.h>
#include <unexmin/mapping/joint_transform.h>
#include <unexmin/sensors/dvl_sensor.h>
#include <unexmin/sensors/sonar/imaging_sonar_sensor.h>
#include <unexmin/sensors/vision/sls_sensor.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

namespace unexmin {
namespace engine {

namespace {

/// The publisher of every tf sample the mapper adds (one node: no hand-over).
constexpr const char* kPublisher = "engine";

[[noreturn]] void bad(const std::string& name, const std::string& value, const std::string& expected) {
  throw ParameterError("mapper: parameter '" + name + "' = " + value + ": expected " + expected);
}

std::string textOf(const MapperValue& v) {
  if (const bool* b = std::get_if<bool>(&v))
    return *b ? "true" : "false";
  if (const double* d = std::get_if<double>(&v))
    return formatNumber(*d);
  return "'" + std::get<std::string>(v) + "'";
}

/// One named setting: how a value of it is stored.
using Setter = std::function<void(MapperSettings&, const std::string& name, const MapperValue&)>;

Setter number(double MapperSettings::* field) {
  return [field](MapperSettings& s, const std::string& name, const MapperValue& v) {
    if (!std::holds_alternative<double>(v))
      bad(name, textOf(v), "a number");
    s.*field = std::get<double>(v);
  };
}

template <class Part>
Setter number(Part MapperSettings::* part, double Part::* field) {
  return [part, field](MapperSettings& s, const std::string& name, const MapperValue& v) {
    if (!std::holds_alternative<double>(v))
      bad(name, textOf(v), "a number");
    (s.*part).*field = std::get<double>(v);
  };
}

Setter flag(bool mapping::MapperSources::* field) {
  return [field](MapperSettings& s, const std::string& name, const MapperValue& v) {
    if (!std::holds_alternative<bool>(v))
      bad(name, textOf(v), "true or false");
    s.sources.*field = std::get<bool>(v);
  };
}

Setter text(std::string MapperSettings::* field) {
  return [field](MapperSettings& s, const std::string& name, const MapperValue& v) {
    if (!std::holds_alternative<std::string>(v))
      bad(name, textOf(v), "a text");
    s.*field = std::get<std::string>(v);
  };
}

const std::map<std::string, Setter>& setters() {
  using P = mapping::MapperParams;
  using S = mapping::MapperSources;
  static const std::map<std::string, Setter> all = {
      {"resolution", number(&MapperSettings::params, &P::resolution)},
      {"max_range", number(&MapperSettings::params, &P::max_range)},
      {"prob_hit", number(&MapperSettings::params, &P::prob_hit)},
      {"prob_miss", number(&MapperSettings::params, &P::prob_miss)},
      {"clamp_min", number(&MapperSettings::params, &P::clamp_min)},
      {"clamp_max", number(&MapperSettings::params, &P::clamp_max)},
      {"m3", flag(&S::m3)},
      {"sonar", flag(&S::sonar)},
      {"dvl", flag(&S::dvl)},
      {"sls_units",
       [](MapperSettings& s, const std::string& name, const MapperValue& v) {
         const double* d = std::get_if<double>(&v);
         if (!d || !(std::floor(*d) == *d) || !(std::abs(*d) < 1e9))
           bad(name, textOf(v), "a whole number 0..16");
         s.sources.sls_units = static_cast<int>(*d);
       }},
      {"sonar_topic",
       [](MapperSettings& s, const std::string& name, const MapperValue& v) {
         if (!std::holds_alternative<std::string>(v))
           bad(name, textOf(v), "a topic relative to /<robot>/");
         s.sources.sonar_topic = std::get<std::string>(v);
       }},
      {"m3_max_range", number(&MapperSettings::sources, &S::m3_max_range)},
      {"sls_max_range", number(&MapperSettings::sources, &S::sls_max_range)},
      {"sonar_max_range", number(&MapperSettings::sources, &S::sonar_max_range)},
      {"dvl_max_range", number(&MapperSettings::sources, &S::dvl_max_range)},
      {"frame_id", text(&MapperSettings::frame_id)},
      {"tf_max_gap", number(&MapperSettings::tf_max_gap)},
      {"tf_rate", number(&MapperSettings::tf_rate)},
      {"sonar_threshold", number(&MapperSettings::sonar_threshold)},
  };
  return all;
}

/// `topic` under /<robot>/ unless it is absolute (the simulator's publishers' rule).
std::string resolved(const std::string& robot, const std::string& topic) {
  return sensors::resolveTopic("/" + robot + "/", topic);
}

}  // namespace

MapperSettings mapperSettings(const std::map<std::string, MapperValue>& values) {
  MapperSettings s;
  for (const auto& [name, value] : values) {
    const auto it = setters().find(name);
    if (it == setters().end()) {
      std::string known;
      for (const std::string& k : mapperSettingNames())
        known += (known.empty() ? "" : ", ") + k;
      throw ParameterError("mapper: unknown parameter '" + name + "': expected one of " + known);
    }
    it->second(s, name, value);
  }
  s.params.validate();
  s.sources.resolve(s.params.max_range);
  if (s.frame_id.empty())
    bad("frame_id", "''", "a frame");
  if (!(s.tf_max_gap > 0.0) || !std::isfinite(s.tf_max_gap))
    bad("tf_max_gap", formatNumber(s.tf_max_gap), "> 0 s");
  if (!(s.tf_rate >= 0.0) || !std::isfinite(s.tf_rate))
    bad("tf_rate", formatNumber(s.tf_rate), ">= 0 Hz (0: every physics step)");
  if (!(s.sonar_threshold > 0.0) || !std::isfinite(s.sonar_threshold))
    bad("sonar_threshold", formatNumber(s.sonar_threshold), "> 0 dB");
  return s;
}

std::vector<std::string> mapperSettingNames() {
  std::vector<std::string> names;
  for (const auto& entry : setters())
    names.push_back(entry.first);
  return names;
}

mapping::ScanGeometry m3ScanGeometry(const sensors::sonar::M3Sensor& m3) {
  return mapping::ScanGeometry{static_cast<float>(m3.beamAngle(0)), static_cast<float>(m3.angleIncrement()),
                               static_cast<float>(m3.rangeMin()), static_cast<float>(m3.rangeMax())};
}

mapping::Stamp stampOf(double t) {
  const double sec = std::floor(t);
  std::int64_t nsec = static_cast<std::int64_t>(std::round((t - sec) * 1e9));
  const std::int64_t whole = static_cast<std::int64_t>(sec) + nsec / 1000000000;
  nsec %= 1000000000;
  return whole * 1000000000 + nsec;
}

Mapper::Mapper(const Engine& engine, const MapperSettings& settings)
    : engine_(engine),
      settings_(settings),
      tf_(120.0, 1.0),
      // No wall clock in-process: a cloud waits for its tf as long as it takes (the next samples always come).
      queue_(std::make_unique<mapping::CloudQueue>(settings.frame_id, std::numeric_limits<double>::max(),
                                                   settings.tf_max_gap)) {
  map_ = std::make_unique<mapping::OccupancyMap>(settings_.params);
  const double physics_rate = 1.0 / engine.world().dt();
  tf_every_ =
      settings_.tf_rate > 0.0
          ? std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(physics_rate / settings_.tf_rate)))
          : 1;
  const mapping::MapperSources& src = settings_.sources;
  std::vector<mapping::TfSample> mounts;
  for (std::size_t r = 0; r < engine.world().robotCount(); ++r) {
    const sim::Robot& robot = engine.world().robot(r);
    const sim::RobotDescription& d = robot.description();
    const sensors::SensorSuite& suite = engine.suite(r);
    RobotMount mount;
    mount.base_link = d.base_link;
    for (std::size_t i = 0; i < suite.size(); ++i) {
      const sensors::Sensor& s = suite.sensor(i);
      const std::string& name = s.name();
      const std::string& robot_name = robot.name();
      Source source{i, Source::Kind::kM3, 0.0, {}, nullptr};
      if (s.type() == "m3" && src.m3 &&
          resolved(robot_name, sensors::textParam(s, "topic", "m3/scan")) == resolved(robot_name, "m3/scan")) {
        source.kind = Source::Kind::kM3;
        source.max_range = src.m3_max_range;
        source.frames = {s.frame()};
      } else if (s.type() == "sls") {
        bool subscribed = false;
        for (int k = 0; k < src.sls_units; ++k)
          subscribed |= resolved(robot_name, sensors::textParam(s, "topic", name + "/points")) ==
                        resolved(robot_name, "sls_" + std::to_string(k) + "/points");
        if (!subscribed)
          continue;
        source.kind = Source::Kind::kSls;
        source.max_range = src.sls_max_range;
        source.frames = {dynamic_cast<const sensors::vision::SlsSensor&>(s).cameraFrame()};
      } else if (s.type() == "imaging_sonar" && src.sonar &&
                 resolved(robot_name, sensors::textParam(s, "points_topic", name + "/points")) ==
                     resolved(robot_name, src.sonar_topic)) {
        const auto& sonar = dynamic_cast<const sensors::sonar::ImagingSonarSensor&>(s);
        source.kind = Source::Kind::kSonar;
        source.max_range = src.sonar_max_range;
        source.frames = {s.frame()};
        source.detector = std::make_unique<sensors::sonar::SonarCloud>(sonar, settings_.sonar_threshold);
      } else if (s.type() == "dvl" && src.dvl &&
                 resolved(robot_name, sensors::textParam(s, "sonar_topic", name + "_sonar")) ==
                     resolved(robot_name, "dvl_sonar")) {
        source.kind = Source::Kind::kDvl;
        source.max_range = src.dvl_max_range;
        std::istringstream frames(sensors::textParam(s, "beam_frames", ""));
        for (std::size_t k = 0; k < 4; ++k) {
          std::string frame;
          source.frames.push_back(frames >> frame ? frame : s.frame());
        }
      } else {
        continue;
      }
      // Each frame's chain up to the base link: its moving joints get a tf sample with the robot's pose.
      for (const std::string& frame : source.frames) {
        std::string link = frame;
        for (std::size_t guard = 0; link != d.base_link; ++guard) {
          const auto joint =
              std::find_if(d.joints.begin(), d.joints.end(), [&](const sim::JointInfo& j) { return j.child == link; });
          if (joint == d.joints.end() || guard > d.joints.size())
            throw ConfigError("mapper: " + robot_name + "'s frame '" + frame + "' of sensor '" + name +
                              "' is not connected to its base link '" + d.base_link + "'");
          const std::size_t j = static_cast<std::size_t>(joint - d.joints.begin());
          if (joint->type != "fixed" &&
              std::find(mount.moving_joints.begin(), mount.moving_joints.end(), j) == mount.moving_joints.end())
            mount.moving_joints.push_back(j);
          link = joint->parent;
        }
      }
      mount.sources.push_back(std::move(source));
    }
    // robot_state_publisher's /tf_static: every fixed joint, the child link in the parent link.
    for (const sim::JointInfo& j : d.joints)
      if (j.type == "fixed")
        mounts.push_back(mapping::TfSample{j.parent, j.child, 0, mapping::jointOriginTransform(j.xyz, j.rpy)});
    robots_.push_back(std::move(mount));
  }
  tf_.add(mounts, kPublisher, clock_, true);
}

void Mapper::sampleTf(std::size_t r) {
  const sim::Robot& robot = engine_.world().robot(r);
  const sim::RobotDescription& d = robot.description();
  const mapping::Stamp stamp = stampOf(engine_.world().time());
  // The simulator's /tf: the odometry's pose, the rotation as the quaternion of the pose's matrix.
  const sim::RobotState s = robot.state();
  mapping::TfSample base{"world", d.base_link, stamp, {}};
  base.transform.translation = s.pose.translation();
  base.transform.rotation = Eigen::Quaterniond(s.pose.linear());
  std::vector<mapping::TfSample> samples{base};
  const std::vector<sensors::MovedJoint> moved = engine_.suite(r).movedJoints();
  for (std::size_t j : robots_[r].moving_joints) {
    const sim::JointInfo& joint = d.joints[j];
    double position = 0.0;
    for (const auto& m : moved)
      if (m.name == joint.name)
        position = m.position;
    if (joint.name == d.pendulum_joint && robot.hasPendulum())
      position = robot.pendulum().angle();
    mapping::RigidTransform motion;
    if (joint.type == "prismatic")
      motion.translation = joint.axis * position;
    else
      motion.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(position, joint.axis));
    samples.push_back(mapping::TfSample{joint.parent, joint.child, stamp,
                                        mapping::jointOriginTransform(joint.xyz, joint.rpy) * motion});
  }
  tf_.add(samples, kPublisher, clock_, false);
}

void Mapper::queueClouds(std::size_t r) {
  const sim::Robot& robot = engine_.world().robot(r);
  const sensors::SensorSuite& suite = engine_.suite(r);
  for (Source& source : robots_[r].sources) {
    if (!suite.fresh(source.sensor))
      continue;
    const sensors::Sensor& sensor = suite.sensor(source.sensor);
    auto push = [&](const std::string& frame, double time, std::vector<octomap::point3d>&& points) {
      queue_->push(
          mapping::PendingCloud{robot.name(), frame, stampOf(time), std::move(points), clock_, source.max_range});
    };
    switch (source.kind) {
      case Source::Kind::kM3: {
        const auto& m3 = dynamic_cast<const sensors::sonar::M3Sensor&>(sensor);
        push(source.frames[0], m3.last().time, mapping::scanPoints(m3ScanGeometry(m3), m3.last().ranges));
        break;
      }
      case Source::Kind::kSls: {
        const auto& sls = dynamic_cast<const sensors::vision::SlsSensor&>(sensor);
        std::vector<octomap::point3d> points;
        points.reserve(sls.last().points.size());
        for (const Eigen::Vector3f& p : sls.last().points)
          points.emplace_back(p.x(), p.y(), p.z());
        push(source.frames[0], sls.last().time, std::move(points));
        break;
      }
      case Source::Kind::kSonar: {
        const auto& sonar = dynamic_cast<const sensors::sonar::ImagingSonarSensor&>(sensor);
        if (!sonar.last().built)
          break;
        std::vector<octomap::point3d> points;
        for (const auto& p : source.detector->build(sonar.last()))
          points.emplace_back(p.xyz.x(), p.xyz.y(), p.xyz.z());
        push(source.frames[0], sonar.last().time, std::move(points));
        break;
      }
      case Source::Kind::kDvl: {
        const auto& dvl = dynamic_cast<const sensors::DvlSensor&>(sensor);
        const float range_min = static_cast<float>(dvl.rangeMin()), range_max = static_cast<float>(dvl.rangeMax());
        for (std::size_t k = 0; k < 4; ++k) {
          // The beam's sensor_msgs/Range: its float range on the beam's +x, none outside [min_range, max_range].
          const float range = static_cast<float>(dvl.last().beams[k].range);
          std::vector<octomap::point3d> points;
          if (std::isfinite(range) && range >= range_min && range <= range_max)
            points.emplace_back(range, 0.0f, 0.0f);
          push(source.frames[k], dvl.last().time, std::move(points));
        }
        break;
      }
    }
  }
}

void Mapper::drain() {
  for (;;) {
    mapping::CloudStep step = queue_->next(tf_, clock_);
    if (step.kind == mapping::CloudStep::Kind::kWait)
      break;
    if (step.kind == mapping::CloudStep::Kind::kDrop)
      continue;
    const std::vector<octomap::point3d> world = step.sensor_in_map.apply(step.cloud.points);
    const Eigen::Vector3d& t = step.sensor_in_map.translation;
    const octomap::point3d origin(static_cast<float>(t.x()), static_cast<float>(t.y()), static_cast<float>(t.z()));
    map_->insertCloud(world, origin, step.cloud.max_range);
    ++inserted_;
    points_ += step.cloud.points.size();
  }
}

void Mapper::afterStep() {
  // tf first, then the clouds (the order they reach the node in: a cloud of this step after the jump back of a reset).
  clock_ += 1.0;
  if (engine_.world().stepCount() % tf_every_ == 0)
    for (std::size_t r = 0; r < robots_.size(); ++r)
      sampleTf(r);
  clock_ += 1.0;
  for (std::size_t r = 0; r < robots_.size(); ++r)
    queueClouds(r);
  drain();
}

void Mapper::afterReset() {
  clock_ += 1.0;
  for (std::size_t r = 0; r < robots_.size(); ++r)
    sampleTf(r);
  clock_ += 1.0;
  drain();
}

void Mapper::clear() {
  map_->reset();
}

MapperStats Mapper::stats() const {
  MapperStats s;
  s.clouds_received = queue_->received();
  s.clouds_inserted = inserted_;
  s.clouds_dropped = queue_->dropped();
  s.pending = queue_->size();
  s.points_inserted = points_;
  return s;
}

std::vector<std::string> Mapper::sources() const {
  std::vector<std::string> out;
  for (std::size_t r = 0; r < robots_.size(); ++r)
    for (const Source& s : robots_[r].sources)
      out.push_back(engine_.world().robot(r).name() + "/" + engine_.suite(r).sensor(s.sensor).name());
  return out;
}

}  // namespace engine
}  // namespace unexmin

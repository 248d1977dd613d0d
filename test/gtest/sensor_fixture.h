// Test fixture for the navigation sensors: the sphere robot of sphere_fixture.h plus sensor mount
// links and <sensor> elements written by the test, and a world (open water or a shipped world file)
// with that robot and its SensorSuite casting through the world's ray caster as the simulator builds it
// (raycast::makeRayCaster, Embree by default; own hull excluded).
#pragma once

#include <unexmin/engine/sensor_families.h>
#include <unexmin/raycast/ray_caster.h>
#include <unexmin/raycast/ray_caster_factory.h>
#include <unexmin/sensors/dvl_sensor.h>
#include <unexmin/sensors/imu_sensor.h>
#include <unexmin/sensors/pressure_sensor.h>
#include <unexmin/sensors/sensor_suite.h>
#include <unexmin/sensors/sonar/imaging_sonar_sensor.h>
#include <unexmin/sensors/sonar/m3_sensor.h>
#include <unexmin/sensors/sonar/msis_sensor.h>
#include <unexmin/sensors/sonar/side_scan_sensor.h>
#include <unexmin/sensors/vision/sls_sensor.h>
#include "sphere_fixture.h"

#include <btBulletDynamicsCommon.h>

#include <map>
#include <memory>
#include <sstream>
#include <string>

namespace unexmin {
namespace test {

/// <link> + fixed <joint> of `link` under T/base_link (or `parent`) at xyz [m] / rpy [rad].
inline std::string mountLink(const std::string& link, const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy,
                             const std::string& parent = "T/base_link") {
  std::ostringstream o;
  o.precision(17);
  o << "<link name='" << link << "'/><joint name='" << link << "_joint' type='fixed'><parent link='" << parent
    << "'/><child link='" << link << "'/><origin xyz='" << xyz.transpose() << "' rpy='" << rpy.transpose()
    << "'/></joint>\n";
  return o.str();
}

/// The UX-1's DVL mount (hull bottom, Nortek axes: rpy pi 0 0) and its four beam frames, as
/// urdf/sensors.xacro writes them: beam i at rpy (0, -(pi/2 - a), c0 + i pi/2).
inline std::string dvlLinks(double beam_angle, double azimuth_0, double hull_radius = 0.3) {
  std::string out = mountLink("T/dvl_link", Eigen::Vector3d(0, 0, -hull_radius), Eigen::Vector3d(M_PI, 0, 0));
  for (int i = 0; i < 4; ++i)
    out += mountLink("T/dvl_beam_" + std::to_string(i) + "_link", Eigen::Vector3d::Zero(),
                     Eigen::Vector3d(0, -(M_PI / 2 - beam_angle), azimuth_0 + i * M_PI / 2), "T/dvl_link");
  return out;
}

/// <sensor> element; `params` maps name -> value text.
inline std::string sensorXml(const std::string& name, const std::string& type, const std::string& link, double rate,
                             const std::map<std::string, std::string>& params) {
  std::ostringstream o;
  o.precision(17);
  o << "<sensor name='" << name << "' type='" << type << "' link='" << link << "' rate='" << rate << "'>";
  for (const auto& kv : params)
    o << "<param name='" << kv.first << "' value='" << kv.second << "'/>";
  o << "</sensor>\n";
  return o.str();
}

/// The sphere robot's URDF with extra links (before <unexmin>) and sensors (inside it).
inline std::string sensorUrdf(const SphereSpec& s, const std::string& links, const std::string& sensors) {
  std::string urdf = sphereUrdf(s);
  urdf.insert(urdf.find("<unexmin>"), links);
  urdf.insert(urdf.find("</unexmin>"), sensors);
  return urdf;
}

inline std::string num(double v) {
  std::ostringstream o;
  o.precision(17);
  o << v;
  return o.str();
}

/// The models of the simulator's sensor families (engine/sensor_families.cpp; the simulator adds their publishers).
inline const sensors::SensorFactory& coreModels() {
  static const sensors::SensorFactory factory = engine::sensorFamilies();  // the simulator's one registration
  return factory;
}

/// A world with one robot (named after the world's first spawn) described by `urdf`, the world's ray caster
/// of back end `backend` (`caster_threads` threads, 0 = every hardware thread) and the robot's sensor suite, reset with
/// the world's seed.
struct SensorWorld {
  SensorWorld(const sim::WorldConfig& config, const std::string& urdf, std::uint64_t seed = 1, double dt = 0.002,
              const std::string& backend = "embree", int caster_threads = 0) {
    std::map<std::string, sim::RobotDescription> d;
    d.emplace(config.robots.at(0).name, sim::parseRobotDescription(urdf, "(test robot)"));
    world = std::make_unique<sim::World>(config, d, 1, dt, seed);
    raycast::RayCasterOptions options;
    options.threads = caster_threads;
    caster = raycast::makeRayCaster(backend, *world, options);
    caster->update();
    suite = std::make_unique<sensors::SensorSuite>(*world, robot(), caster.get(), coreModels());
  }

  sim::Robot& robot() { return world->robot(0); }
  /// One physics step and the sensors after it (the caster updated in between, as the simulator does).
  void step() {
    world->step();
    caster->update();
    suite->update();
  }
  /// Steps until sensor `s` has taken `n` more samples.
  void samples(const sensors::Sensor& s, std::uint64_t n) {
    const std::uint64_t target = s.sampleCount() + n;
    while (s.sampleCount() < target)
      step();
  }
  template <class T>
  T& sensor(const std::string& name) {
    return dynamic_cast<T&>(*suite->find(name));
  }
  /// Teleports the robot and sets its world velocities [m/s, rad/s].
  void place(const Eigen::Isometry3d& pose, const Eigen::Vector3d& v = Eigen::Vector3d::Zero(),
             const Eigen::Vector3d& w = Eigen::Vector3d::Zero()) {
    robot().setPose(pose);
    robot().body()->setLinearVelocity(btVector3(v.x(), v.y(), v.z()));
    robot().body()->setAngularVelocity(btVector3(w.x(), w.y(), w.z()));
  }

  std::unique_ptr<sim::World> world;
  std::unique_ptr<raycast::RayCaster> caster;
  std::unique_ptr<sensors::SensorSuite> suite;
};

/// A sphere with no damping at all: set velocities stay constant (closed-form motion).
inline SphereSpec undampedSphere() {
  SphereSpec s;
  for (double& v : s.lin)
    v = 0.0;
  for (double& v : s.quad)
    v = 0.0;
  return s;
}

}  // namespace test
}  // namespace unexmin

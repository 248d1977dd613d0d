// Test fixture for the sonars (cpp/unexmin/sensors/sonar/msis_sensor.h, m3_sensor.h): the sphere robot of
// sphere_fixture.h with an MSIS head (base on the hull top, head on a continuous joint about z) and an M3 link, worlds
// of STL meshes written by the test (icosphere, boxes) or shipped world files, and the robot's SensorSuite casting
// through the world's Embree caster (the simulator's default).
#pragma once

#include "mesh_fixture.h"
#include "sensor_fixture.h"

#include <unexmin/water/seawater.h>
#include <unexmin/water/water_column.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace unexmin {
namespace test {

/// Open water with the robot "T" at `robot` and the given meshes.
inline sim::WorldConfig meshWorld(const std::vector<std::pair<std::string, Geometry>>& meshes,
                                  const Eigen::Vector3d& robot) {
  sim::WorldConfig config = openWater(SphereSpec(), robot);
  for (const auto& [name, geometry] : meshes) {
    sim::MeshEntry entry;
    entry.name = name;
    entry.file = writeStl(name, geometry);
    config.meshes.push_back(entry);
  }
  return config;
}

/// MSIS base on the hull at `base_xyz`/`base_rpy` (base link frame), head `head_height` above it on the
/// continuous joint T/msis_head_joint (axis z). Head link: T/msis_head_link.
inline std::string msisLinks(const Eigen::Vector3d& base_xyz = Eigen::Vector3d(0, 0, 0.3),
                             const Eigen::Vector3d& base_rpy = Eigen::Vector3d::Zero(), double head_height = 0.06) {
  return mountLink("T/msis_base_link", base_xyz, base_rpy) +
         "<link name='T/msis_head_link'/><joint name='T/msis_head_joint' type='continuous'>"
         "<parent link='T/msis_base_link'/><child link='T/msis_head_link'/><origin xyz='0 0 " +
         num(head_height) + "' rpy='0 0 0'/><axis xyz='0 0 1'/></joint>\n";
}

/// A plate target 1 cm thick facing -x (the multipath tests): its near face `ahead` [m] in front of `sensor` (world
/// +x), centred on the sensor's y, `width` x `height` [m], its centre `below_surface` [m] below the free surface
/// (z = 0).
inline Geometry plateTarget(const Eigen::Vector3d& sensor, double ahead, double below_surface, double width = 0.6,
                            double height = 0.2) {
  const Eigen::Vector3d c(sensor.x() + ahead, sensor.y(), -below_surface);
  return box(c + Eigen::Vector3d(0, -width / 2, -height / 2), c + Eigen::Vector3d(0.01, width / 2, height / 2));
}

/// `world` filled with fresh water (salinity 0) at `temperature` [degC] throughout (docs/worlds.md "Water column").
inline void fillWithFreshWater(sim::WorldConfig& world, double temperature) {
  water::Profile profile;
  profile.rows.resize(1);
  profile.rows[0].temperature = temperature;
  water::checkProfile(profile, "water.profile");
  world.water_column =
      std::make_shared<const water::WaterColumn>(profile, std::vector<water::Region>{}, world.surface_z, world.gravity);
}

/// Sound speed of fresh water at `temperature` [degC] at `point` (world frame) of `world`, by the seawater functions
/// (Chen & Millero) at the hydrostatic pressure of its depth, 1e-4 x 1000 kg/m^3 x g x depth [dbar] [m/s].
inline double freshWaterSoundSpeed(const sim::WorldConfig& world, double temperature, const Eigen::Vector3d& point) {
  return water::soundSpeed(0.0, temperature, 1e-4 * 1000.0 * world.gravity * (world.surface_z - point.z()));
}

/// The sonar tests' world: a SensorWorld (Embree caster).
using SonarWorld = SensorWorld;

}  // namespace test
}  // namespace unexmin

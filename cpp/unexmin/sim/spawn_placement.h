// Spawn poses for the robots a world file does not list (a team with more vehicles of a type than the world names):
// the rule of docs/worlds.md, "Robots the world does not list". ROS-free.
#pragma once

#include <unexmin/sim/robot_description.h>
#include <unexmin/sim/world_config.h>

#include <Eigen/Geometry>

#include <functional>
#include <string>
#include <vector>

namespace unexmin {
namespace sim {

/// Water kept between a placed robot's hull sphere and a wall, the free surface or another robot's hull sphere [m].
constexpr double kSpawnMargin = 0.3;
/// How far the placement searches: lattice points up to this many steps from the anchor along each axis.
constexpr int kSpawnSteps = 6;

/// Radius of the sphere about the body origin that holds the hull [m]: half the diagonal of <bounding_box> when the
/// description gives one, else the hydrodynamic radius (or the radius of the sphere of the hull's volume).
double hullRadius(const RobotDescription& description);

/// What the placement asks of the world's collision meshes (world frame, [m]).
struct SpawnProbe {
  /// True when a sphere of `radius` at `centre` touches no collision mesh.
  std::function<bool(const Eigen::Vector3d& centre, double radius)> clear;
  /// True when the segment from `a` to `b` crosses no collision mesh.
  std::function<bool(const Eigen::Vector3d& a, const Eigen::Vector3d& b)> open;
};

/// Gives every spawn among the first `count` of `spawns` with `placed == false` a pose, in order: the first point
/// p = anchor + R_yaw (i, j, k) s of the lattice of step s = 2 r + kSpawnMargin (r = radii[n], the robot's hull
/// radius) about its anchor (the pose it holds, turned by the anchor's yaw), |i|, |j|, |k| <= kSpawnSteps, taken
/// nearest first (then level before up or down, then +x, -x, +y, -y, ...), such that the hull sphere with
/// kSpawnMargin is under the surface `surface_z`, touches no wall (probe.clear), is reached from the anchor
/// without crossing a wall (probe.open: the same water as the anchor), and keeps r + r_other + kSpawnMargin from
/// every other robot's spawn. The orientation is the anchor's. Throws ConfigError naming `file`, the robot and the
/// search when no point passes.
void placeSpawns(std::vector<RobotSpawn>& spawns, const std::vector<double>& radii, std::size_t count, double surface_z,
                 const SpawnProbe& probe, const std::string& file);

}  // namespace sim
}  // namespace unexmin

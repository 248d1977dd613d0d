// Where a robot of the world starts: its name, its description file and its base link's pose (a world file's
// `robots:` entry, docs/worlds.md). Knows no ROS.
#pragma once

#include <Eigen/Geometry>

#include <string>

namespace unexmin {
namespace sim {

struct RobotSpawn {
  std::string name;         ///< Robot namespace, e.g. "UX_1".
  std::string description;  ///< Robot description file name in the package's urdf/ folder.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< base_link in the world frame.
  /// False for a robot the world file does not list (a team's extra vehicle): the world places it by the rule of
  /// sim/spawn_placement.h, and `pose` holds its anchor's pose until then.
  bool placed = true;
};

}  // namespace sim
}  // namespace unexmin

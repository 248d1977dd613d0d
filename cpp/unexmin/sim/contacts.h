// Where a robot's hull touches something (the world's meshes, another robot) after the last physics step: Bullet's
// contact points with a distance <= 0, read through its public contact manifolds. Knows no ROS.
#pragma once

#include <unexmin/sim/robot.h>
#include <unexmin/sim/world.h>

#include <Eigen/Core>

#include <vector>

namespace unexmin {
namespace sim {

struct Contact {
  Eigen::Vector3d position{0, 0, 0};  ///< on the obstacle, world frame [m]
  Eigen::Vector3d normal{0, 0, 1};    ///< unit, from the obstacle into the robot, world frame
  double depth = 0.0;                 ///< penetration [m] >= 0
  double impulse = 0.0;               ///< normal impulse Bullet applied in the last step [N s]
};

/// The contacts of `robot` (of `world`) now.
std::vector<Contact> contacts(World& world, Robot& robot);

}  // namespace sim
}  // namespace unexmin

#include <unexmin/sensors/magnetic_field.h>

#include <unexmin/sim/world.h>

#include <vector>

namespace unexmin {
namespace sensors {

Eigen::Vector3d magnetometerField(const SensorContext& ctx, const Eigen::Isometry3d& mount) {
  const Eigen::Isometry3d& pose = ctx.state.pose;
  const Eigen::Vector3d external = pose.linear().transpose() * ctx.world.magneticField(pose * mount.translation());
  const sim::RobotMagnetics& own = ctx.robot.description().magnetics;
  thread_local std::vector<double> thrust;
  thrust.resize(own.thruster_field.size());
  for (std::size_t i = 0; i < thrust.size() && i < ctx.robot.thrusterCount(); ++i)
    thrust[i] = ctx.robot.thruster(i).thrust();
  return mount.linear().transpose() * own.read(external, thrust);
}

}  // namespace sensors
}  // namespace unexmin

// The UNEXMIN simulator process (like gzserver): see docs/simulator_node.md.
#include <unexmin/ros_layer/simulator_ros.h>

#include <csignal>
#include <stdexcept>

namespace {

/// SIGTERM (roslaunch's escalation, `kill`) ends the process as SIGINT does: the spin loop returns and
/// the recorder closes and indexes its bag.
void requestShutdown(int) {
  ros::requestShutdown();
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "simulator");
  // Outlives `sim`: when the last NodeHandle goes, roscpp shuts rosconsole down and the start-up
  // error below would not be printed.
  ros::NodeHandle nh;
  std::signal(SIGTERM, requestShutdown);
  try {
    unexmin::ros_layer::SimulatorRos sim(nh, ros::NodeHandle("~"));
    sim.spin();
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM("unexmin simulator cannot start: " << e.what());
    return 1;
  }
  return 0;
}

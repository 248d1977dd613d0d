// The mapper node: see docs/mapping.md.
#include <unexmin/ros_layer/mapper_ros.h>

int main(int argc, char** argv) {
  ros::init(argc, argv, "mapper");
  ros::NodeHandle nh;  // outlives the mapper, so its start-up error is printed
  try {
    unexmin::ros_layer::MapperRos(nh, ros::NodeHandle("~")).spin();
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM("unexmin mapper: " << e.what());
    return 1;
  }
  return 0;
}

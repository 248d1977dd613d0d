#include <unexmin/ros_layer/m3_cloud.h>

#include <unexmin/ros_layer/sensor_publisher.h>

#include <cmath>
#include <cstring>
#include <vector>

namespace unexmin {
namespace ros_layer {

sensor_msgs::PointCloud2 scanToCloud(const sensor_msgs::LaserScan& scan)
{
  std::vector<float> xyz;  // valid beams only, as the rospy translator keeps them
  xyz.reserve(3 * scan.ranges.size());
  for (std::size_t k = 0; k < scan.ranges.size(); ++k) {
    const double r = scan.ranges[k];
    if (!std::isfinite(r) || r < scan.range_min || r > scan.range_max) continue;
    const double a = static_cast<double>(scan.angle_min) + static_cast<double>(k) * static_cast<double>(scan.angle_increment);
    xyz.insert(xyz.end(), {static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)), 0.0f});
  }
  sensor_msgs::PointCloud2 cloud;
  cloud.header = scan.header;
  SensorPublisher::floatCloud(cloud, {"x", "y", "z"}, xyz.size() / 3);
  cloud.is_dense = false;  // as sensor_msgs.point_cloud2.create_cloud
  if (!xyz.empty()) std::memcpy(cloud.data.data(), xyz.data(), xyz.size() * sizeof(float));
  return cloud;
}

}  // namespace ros_layer
}  // namespace unexmin

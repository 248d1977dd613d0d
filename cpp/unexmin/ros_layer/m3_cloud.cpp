#include <unexmin/ros_layer/m3_cloud.h>

#include <unexmin/mapping/scan_points.h>
#include <unexmin/ros_layer/sensor_publisher.h>

#include <cstring>
#include <vector>

namespace unexmin {
namespace ros_layer {

sensor_msgs::PointCloud2 scanToCloud(const sensor_msgs::LaserScan& scan) {
  const std::vector<octomap::point3d> points = mapping::scanPoints(
      mapping::ScanGeometry{scan.angle_min, scan.angle_increment, scan.range_min, scan.range_max}, scan.ranges);
  std::vector<float> xyz;
  xyz.reserve(3 * points.size());
  for (const octomap::point3d& p : points)
    xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
  sensor_msgs::PointCloud2 cloud;
  cloud.header = scan.header;
  SensorPublisher::floatCloud(cloud, {"x", "y", "z"}, points.size());
  cloud.is_dense = false;  // as sensor_msgs.point_cloud2.create_cloud
  if (!xyz.empty())
    std::memcpy(cloud.data.data(), xyz.data(), xyz.size() * sizeof(float));
  return cloud;
}

}  // namespace ros_layer
}  // namespace unexmin

#include <unexmin/ros/m3_cloud.h>

#include <cmath>
#include <cstring>

namespace unexmin {
namespace ros_layer {

sensor_msgs::PointCloud2 scanToCloud(const sensor_msgs::LaserScan& scan)
{
  sensor_msgs::PointCloud2 cloud;
  cloud.header = scan.header;
  cloud.height = 1;
  const char* names[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    sensor_msgs::PointField f;
    f.name = names[i];
    f.offset = static_cast<std::uint32_t>(4 * i);
    f.datatype = sensor_msgs::PointField::FLOAT32;
    f.count = 1;
    cloud.fields.push_back(f);
  }
  cloud.is_bigendian = false;
  cloud.point_step = 12;
  cloud.is_dense = false;  // as sensor_msgs.point_cloud2.create_cloud
  cloud.data.reserve(12 * scan.ranges.size());
  std::uint32_t n = 0;
  for (std::size_t k = 0; k < scan.ranges.size(); ++k) {
    const double r = scan.ranges[k];
    if (!std::isfinite(r) || r < scan.range_min || r > scan.range_max) continue;
    const double a = static_cast<double>(scan.angle_min) + static_cast<double>(k) * static_cast<double>(scan.angle_increment);
    const float p[3] = {static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)), 0.0f};
    const std::size_t at = cloud.data.size();
    cloud.data.resize(at + sizeof(p));
    std::memcpy(&cloud.data[at], p, sizeof(p));
    ++n;
  }
  cloud.width = n;
  cloud.row_step = cloud.point_step * n;
  return cloud;
}

}  // namespace ros_layer
}  // namespace unexmin

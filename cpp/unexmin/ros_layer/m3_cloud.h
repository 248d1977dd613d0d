// The M3 translation of python/unexmin/translators/m3.py (scan_to_cloud), in C++ so that it keeps up in lockstep:
// sensor_msgs/LaserScan of first echoes -> sensor_msgs/PointCloud2 (x y z FLOAT32, the real M3 driver's
// PointCloudXYZ), header kept; the points are mapping::scanPoints' (cpp/unexmin/mapping/scan_points.h), the
// valid beams only. test/pytest/test_cpp_translations.py compares it with the Python function on the simulator's
// messages.
#pragma once

#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>

namespace unexmin {
namespace ros_layer {

sensor_msgs::PointCloud2 scanToCloud(const sensor_msgs::LaserScan& scan);

}  // namespace ros_layer
}  // namespace unexmin

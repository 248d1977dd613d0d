// A planar laser scan (sensor_msgs/LaserScan's geometry, REP-117) as points in the sensor frame: beam k at angle
// a_k = angle_min + k * angle_increment [rad] with range r_k [m] gives (r_k cos a_k, r_k sin a_k, 0) [m]; beams with
// no echo (+-inf, NaN, outside [range_min, range_max]) are left out. The angle is computed in double from the float
// fields, each coordinate rounded to float. The one conversion of the M3 cloud and of the mapper; its Python twin
// is unexmin.m3_translator.scan_points. Knows no ROS.
#pragma once

#include <octomap/octomap_types.h>

#include <vector>

namespace unexmin {
namespace mapping {

/// The fields of a LaserScan that place its beams.
struct ScanGeometry {
  float angle_min = 0.0f;        ///< angle of beam 0 [rad]
  float angle_increment = 0.0f;  ///< angle between beams [rad]
  float range_min = 0.0f;        ///< shortest valid range [m]
  float range_max = 0.0f;        ///< longest valid range [m]
};

/// The points [m, sensor frame] of the valid beams of ranges [m], in beam order.
std::vector<octomap::point3d> scanPoints(const ScanGeometry& scan, const std::vector<float>& ranges);

}  // namespace mapping
}  // namespace unexmin

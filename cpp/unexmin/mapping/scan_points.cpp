#include <unexmin/mapping/scan_points.h>

#include <cmath>

namespace unexmin {
namespace mapping {

std::vector<octomap::point3d> scanPoints(const ScanGeometry& scan, const std::vector<float>& ranges) {
  std::vector<octomap::point3d> points;
  points.reserve(ranges.size());
  for (std::size_t k = 0; k < ranges.size(); ++k) {
    const double r = ranges[k];
    if (!std::isfinite(r) || r < scan.range_min || r > scan.range_max)
      continue;  // no echo
    const double a =
        static_cast<double>(scan.angle_min) + static_cast<double>(k) * static_cast<double>(scan.angle_increment);
    points.emplace_back(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)), 0.0f);
  }
  return points;
}

}  // namespace mapping
}  // namespace unexmin

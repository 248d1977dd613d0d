#include <unexmin/mapping/map_display.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace mapping {

Colour heightColour(double z, double lo, double hi) {
  const double t = hi > lo ? std::min(1.0, std::max(0.0, (z - lo) / (hi - lo))) : 0.5;
  const double h = (1.0 - t) * 4.0;  // 4 (blue) .. 0 (red) on the six-sector hue wheel
  const int i = static_cast<int>(std::floor(h));
  const double f = h - i;
  Colour c;
  switch (i) {
    case 0:
      c = {1.0f, static_cast<float>(f), 0.0f, 1.0f};
      break;
    case 1:
      c = {static_cast<float>(1 - f), 1.0f, 0.0f, 1.0f};
      break;
    case 2:
      c = {0.0f, 1.0f, static_cast<float>(f), 1.0f};
      break;
    case 3:
      c = {0.0f, static_cast<float>(1 - f), 1.0f, 1.0f};
      break;
    default:
      c = {0.0f, 0.0f, 1.0f, 1.0f};
      break;
  }
  return c;
}

std::vector<CubeList> occupiedCubes(OccupancyMap& map, const std::vector<Voxel>& voxels) {
  double lo = 0, hi = 0;
  if (!voxels.empty()) {
    const auto mm =
        std::minmax_element(voxels.begin(), voxels.end(), [](const Voxel& a, const Voxel& b) { return a.z < b.z; });
    lo = mm.first->z;
    hi = mm.second->z;
  }
  const octomap::OcTree& tree = map.tree();
  const unsigned depths = tree.getTreeDepth() + 1;
  std::vector<CubeList> lists(depths);
  for (unsigned d = 0; d < depths; ++d)
    lists[d].size = tree.getNodeSize(d);
  for (const Voxel& v : voxels) {
    const unsigned d = std::min<unsigned>(
        depths - 1, static_cast<unsigned>(std::lround(tree.getTreeDepth() - std::log2(v.size / tree.getResolution()))));
    lists[d].cells.push_back(v);
    lists[d].colours.push_back(heightColour(v.z, lo, hi));
  }
  return lists;
}

std::vector<octomap::point3d> voxelCentres(const std::vector<Voxel>& voxels) {
  std::vector<octomap::point3d> centres;
  centres.reserve(voxels.size());
  for (const Voxel& v : voxels) {
    centres.emplace_back(static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z));
  }
  return centres;
}

}  // namespace mapping
}  // namespace unexmin

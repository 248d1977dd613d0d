// What the mapper shows of a map, as plain data the node turns into messages: the occupied leaves as one cube
// list per leaf size (pruned leaves are larger), coloured by height from blue (lowest) to red (highest), as
// octomap_server's occupied_cells_vis_array; and their centres as a point cloud. Knows no ROS.
#pragma once

#include <unexmin/mapping/occupancy_map.h>

#include <vector>

namespace unexmin {
namespace mapping {

/// An RGBA colour, each channel in [0, 1].
struct Colour {
  float r = 0.0f, g = 0.0f, b = 0.0f, a = 1.0f;
};

/// The occupied leaves of one size.
struct CubeList {
  double size = 0.0;            ///< edge of the cubes [m]
  std::vector<Voxel> cells;     ///< their centres [m, map frame]
  std::vector<Colour> colours;  ///< one per cell
};

/// The colour of height z [m] in [lo, hi]: hue from blue (lo) through cyan, green and yellow to red (hi); 0.5 of the
/// way when hi <= lo.
Colour heightColour(double z, double lo, double hi);

/// The occupied leaves of map as cube lists, one per tree depth (the root's first, leaves of resolution last), each
/// cell coloured by its height between the lowest and highest occupied leaf. Lists of a depth without leaves are
/// empty.
std::vector<CubeList> occupiedCubes(OccupancyMap& map, const std::vector<Voxel>& voxels);

/// The centres [m, map frame] of the voxels, rounded to float.
std::vector<octomap::point3d> voxelCentres(const std::vector<Voxel>& voxels);

}  // namespace mapping
}  // namespace unexmin

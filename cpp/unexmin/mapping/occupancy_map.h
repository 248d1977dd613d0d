// A world-frame occupancy map (an OctoMap OcTree) built from point clouds, each ray-cast from its own sensor
// origin. Per cloud, every voxel is updated once (occupied wins over free), the leaves are visited in Morton
// order so that one descent serves neighbouring voxels, and each touched inner node is updated (or pruned)
// once per cloud, not once per voxel below it as OctoMap's updateNode does. The result equals OctoMap's own
// insertPointCloud on the same clouds (test_mapping.cpp checks it voxel for voxel). Knows no ROS.
#pragma once

#include <unexmin/mapping/key_set.h>
#include <unexmin/mapping/mapper_params.h>

#include <octomap/OcTree.h>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace unexmin {
namespace mapping {

/// What one insertCloud() did.
struct CloudStats {
  std::size_t points = 0;           ///< points handed in
  std::size_t invalid = 0;          ///< non-finite or outside the tree: ignored
  std::size_t beyond_range = 0;     ///< farther than the range: free space up to it, no endpoint
  std::size_t occupied_voxels = 0;  ///< distinct voxels updated as occupied
  std::size_t free_voxels = 0;      ///< distinct voxels updated as free
};

/// One occupied leaf of the pruned tree: its centre [m, world frame] and edge [m].
struct Voxel {
  double x, y, z, size;
};

class OccupancyMap {
public:
  /// Throws ParameterError when params are out of range.
  explicit OccupancyMap(const MapperParams& params);
  ~OccupancyMap();

  /// Ray-casts every point of a cloud [m, world frame] from the sensor origin [m, world frame]: the voxels
  /// between origin and point become freer, the point's voxel more occupied; points beyond max_range only
  /// carve free space up to max_range.
  CloudStats insertCloud(const std::vector<octomap::point3d>& points, const octomap::point3d& origin);
  /// The same with this cloud's own max_range [m] in place of the parameter (a source whose far echoes are
  /// less trusted): points farther than it from the origin are not marked occupied and their rays carve free
  /// space up to it only. <= 0: no limit. Throws ParameterError when it is not finite.
  CloudStats insertCloud(const std::vector<octomap::point3d>& points, const octomap::point3d& origin, double max_range);

  /// Brings inner nodes up to date and prunes, if anything changed since the last call (insertCloud keeps
  /// the tree up to date: this is for trees changed otherwise).
  void update();
  /// The tree, updated.
  const octomap::OcTree& tree();
  /// Occupied leaves of the updated tree (what OctoMap's tools count reading the saved map).
  std::size_t occupiedLeafCount();
  /// The occupied leaves of the updated tree.
  std::vector<Voxel> occupiedVoxels();
  /// Writes the updated tree as OctoMap's binary .bt (maximum likelihood) to path, through a temporary
  /// file renamed into place, so an interrupted save leaves the previous file. Throws Error on failure.
  void save(const std::string& path);
  /// OctoMap's binary serialisation of the updated tree (the data of an octomap_msgs/Octomap).
  std::string binaryData();
  /// Empties the map.
  void reset();

  const MapperParams& params() const { return params_; }
  /// Clouds and points inserted since construction or reset().
  std::size_t clouds() const { return clouds_; }
  std::size_t points() const { return points_; }
  /// Memory of the tree [bytes] (OctoMap's estimate).
  std::size_t memoryUsage() const;

private:
  /// Adds the voxels a ray crosses from origin (its key and Morton code) to end (its Morton code) as free.
  void traceRay(const octomap::point3d& origin, const octomap::OcTreeKey& key_origin, uint64_t code_origin,
                const octomap::point3d& end, uint64_t code_end);

  class Tree;
  MapperParams params_;
  std::unique_ptr<Tree> tree_;
  KeySet keys_;
  bool dirty_ = false;
  std::size_t clouds_ = 0;
  std::size_t points_ = 0;
};

}  // namespace mapping
}  // namespace unexmin

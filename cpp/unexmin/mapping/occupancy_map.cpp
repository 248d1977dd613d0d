#include <unexmin/mapping/occupancy_map.h>

#include <unexmin/core/error.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

namespace unexmin {
namespace mapping {

/// OctoMap's OcTree with a batched leaf update that reaches its protected root.
class OccupancyMap::Tree : public octomap::OcTree {
public:
  using octomap::OcTree::OcTree;

  /// Adds log-odds hit (occupied bit set) or miss to the leaf of every entry (code << 1 | occupied, sorted by
  /// code), clamped, creating leaves and expanding pruned nodes as OctoMap's updateNode does. Each inner node
  /// the batch touched is brought up to date (maximum of its children, or pruned when its 8 children are equal
  /// leaves) once, when the sorted walk leaves its subtree for good: the tree stays as OctoMap's
  /// updateInnerOccupancy() and prune() would leave it, at the cost of the touched nodes only.
  void apply(const std::vector<uint64_t>& entries) {
    if (entries.empty())
      return;
    const float hit = getProbHitLog(), miss = getProbMissLog();
    const float lo = getClampingThresMinLog(), hi = getClampingThresMaxLog();
    constexpr unsigned depth_max = 16;
    std::array<octomap::OcTreeNode*, depth_max + 1> path{};
    std::array<bool, depth_max + 1> created{};
    if (root == nullptr) {
      root = new octomap::OcTreeNode();
      ++tree_size;
      created[0] = true;
    }
    path[0] = root;
    uint64_t previous = 0;
    bool first = true;
    for (uint64_t entry : entries) {
      const uint64_t code = entry >> 1;
      // The nodes down to the depth where this code leaves the previous one's path are shared.
      unsigned start = 0;
      if (!first) {
        start = depth_max - 1 - (63 - __builtin_clzll(code ^ previous)) / 3;
        for (unsigned depth = depth_max - 1; depth > start; --depth)
          finish(path[depth]);
      }
      for (unsigned depth = start; depth < depth_max; ++depth) {
        octomap::OcTreeNode* node = path[depth];
        const unsigned pos = (code >> (3 * (depth_max - 1 - depth))) & 7u;
        bool child_created = false;
        if (!nodeChildExists(node, pos)) {
          if (!nodeHasChildren(node) && !created[depth]) {
            expandNode(node);  // a pruned node: its children take its value
          } else {
            createNodeChild(node, pos);
            child_created = true;
          }
        }
        path[depth + 1] = getNodeChild(node, pos);
        created[depth + 1] = child_created;
      }
      octomap::OcTreeNode* leaf = path[depth_max];
      const float value = leaf->getLogOdds() + ((entry & 1u) ? hit : miss);  // OcTreeNode::addValue, inlined
      leaf->setLogOdds(value < lo ? lo : (value > hi ? hi : value));
      previous = code;
      first = false;
    }
    for (unsigned depth = depth_max; depth-- > 0;)
      finish(path[depth]);
    size_changed = true;
  }

private:
  /// An inner node whose children are final: pruned if they are 8 equal leaves, else it takes their maximum.
  void finish(octomap::OcTreeNode* node) {
    if (!nodeHasChildren(node))
      return;
    // One pass over the children for both pruneNode's test (8 leaves of equal value) and
    // updateOccupancyChildren's maximum.
    bool collapsible = true;
    float max = -std::numeric_limits<float>::max();
    const octomap::OcTreeNode* first = nullptr;
    for (unsigned i = 0; i < 8; ++i) {
      if (!nodeChildExists(node, i)) {
        collapsible = false;
        continue;
      }
      const octomap::OcTreeNode* child = getNodeChild(node, i);
      if (first == nullptr)
        first = child;
      collapsible = collapsible && !nodeHasChildren(child) && *child == *first;
      max = std::max(max, child->getLogOdds());
    }
    if (collapsible)
      pruneNode(node);
    else
      node->setLogOdds(max);
  }
};

OccupancyMap::OccupancyMap(const MapperParams& params) : params_(params) {
  params_.validate();
  reset();
}

OccupancyMap::~OccupancyMap() = default;

void OccupancyMap::reset() {
  tree_ = std::make_unique<Tree>(params_.resolution);
  tree_->setProbHit(params_.prob_hit);
  tree_->setProbMiss(params_.prob_miss);
  tree_->setClampingThresMin(params_.clamp_min);
  tree_->setClampingThresMax(params_.clamp_max);
  dirty_ = false;
  clouds_ = 0;
  points_ = 0;
}

void OccupancyMap::traceRay(const octomap::point3d& origin, const octomap::OcTreeKey& key_origin, uint64_t code_origin,
                            const octomap::point3d& end, uint64_t code_end) {
  // 3D DDA through the voxels from origin's to end's, both excluded unless distinct (origin included):
  // the same walk as OctoMap's computeRayKeys (the same double-precision arithmetic, the same choice of axis
  // on ties), so both mark the same voxels free. The key is carried as its Morton code, stepped per axis.
  if (code_origin == code_end)
    return;
  keys_.addFree(code_origin);
  octomap::point3d direction = end - origin;
  const float length = static_cast<float>(direction.norm());
  direction /= length;
  const double resolution = tree_->getResolution();
  int step[3];
  double t_max[3], t_delta[3];
  for (unsigned i = 0; i < 3; ++i) {
    step[i] = direction(i) > 0.0 ? 1 : (direction(i) < 0.0 ? -1 : 0);
    if (step[i] != 0) {
      double border = tree_->keyToCoord(key_origin[i]);
      border += static_cast<float>(step[i] * resolution * 0.5);
      t_max[i] = (border - origin(i)) / direction(i);
      t_delta[i] = resolution / std::fabs(direction(i));
    } else {
      t_max[i] = std::numeric_limits<double>::max();
      t_delta[i] = std::numeric_limits<double>::max();
    }
  }
  // The key is carried as its Morton code and stepped along one axis without decoding it: for +1 the other
  // axes' bits are set so that the carry runs through them, for -1 they are cleared so that the borrow does
  // (the key wraps at 16 bits as OctoMap's does).
  uint64_t axis_bits[3], fill[3], add[3];
  for (unsigned i = 0; i < 3; ++i) {
    axis_bits[i] = kMortonAxisBits << i;
    fill[i] = step[i] > 0 ? ~axis_bits[i] : 0;
    add[i] = step[i] > 0 ? uint64_t(1) << i : ~(uint64_t(1) << i) + 1;  // +1 or -1 in the axis's field
  }
  // The axis to step next: the smallest t_max, ties to the higher axis as computeRayKeys does
  // (t_max[0] < t_max[1] ? (t_max[0] < t_max[2] ? 0 : 2) : (t_max[1] < t_max[2] ? 1 : 2)). The three t_max
  // are kept in registers; an axis is stepped by a select of masks, not a branch on its sign.
  double t0 = t_max[0], t1 = t_max[1], t2 = t_max[2];
  const double d0 = t_delta[0], d1 = t_delta[1], d2 = t_delta[2];
  uint64_t code = code_origin;
  for (;;) {
    unsigned dim;
    if (t0 < t1) {
      if (t0 < t2) {
        dim = 0;
        t0 += d0;
      } else {
        dim = 2;
        t2 += d2;
      }
    } else {
      if (t1 < t2) {
        dim = 1;
        t1 += d1;
      } else {
        dim = 2;
        t2 += d2;
      }
    }
    const uint64_t moved = ((code & axis_bits[dim]) | fill[dim]) + add[dim];
    code = (moved & axis_bits[dim]) | (code & ~axis_bits[dim]);
    if (code == code_end)
      return;
    if (std::min(std::min(t0, t1), t2) > length)
      return;
    keys_.addFree(code);
  }
}

CloudStats OccupancyMap::insertCloud(const std::vector<octomap::point3d>& points, const octomap::point3d& origin) {
  return insertCloud(points, origin, params_.max_range);
}

CloudStats OccupancyMap::insertCloud(const std::vector<octomap::point3d>& points, const octomap::point3d& origin,
                                     double max_range) {
  if (!std::isfinite(max_range))
    throw ParameterError("mapper: a cloud's range = " + formatNumber(max_range) + ": expected a finite number of m");
  CloudStats stats;
  stats.points = points.size();
  if (!std::isfinite(origin.x()) || !std::isfinite(origin.y()) || !std::isfinite(origin.z())) {
    stats.invalid = points.size();
    return stats;
  }
  // An origin outside the tree casts no ray (as computeRayKeys refuses it); the endpoints still count.
  octomap::OcTreeKey key_origin;
  const bool rays = tree_->coordToKeyChecked(origin, key_origin);
  const uint64_t code_origin = rays ? mortonCode(key_origin) : 0;
  keys_.clear();
  for (const octomap::point3d& p : points) {
    octomap::OcTreeKey key;
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()) || !tree_->coordToKeyChecked(p, key)) {
      ++stats.invalid;
      continue;
    }
    if (max_range <= 0.0 || (p - origin).norm() <= max_range) {
      const uint64_t code = mortonCode(key);
      if (rays)
        traceRay(origin, key_origin, code_origin, p, code);
      keys_.addOccupied(code);
    } else {
      ++stats.beyond_range;
      const octomap::point3d end = origin + (p - origin).normalized() * static_cast<float>(max_range);
      if (rays && tree_->coordToKeyChecked(end, key))
        traceRay(origin, key_origin, code_origin, end, mortonCode(key));
    }
  }
  const std::vector<uint64_t>& entries = keys_.sorted();
  for (uint64_t e : entries)
    ++((e & 1u) ? stats.occupied_voxels : stats.free_voxels);
  tree_->apply(entries);
  ++clouds_;
  points_ += points.size();
  return stats;
}

void OccupancyMap::update() {
  if (!dirty_)
    return;
  tree_->updateInnerOccupancy();
  tree_->prune();
  dirty_ = false;
}

const octomap::OcTree& OccupancyMap::tree() {
  update();
  return *tree_;
}

std::size_t OccupancyMap::occupiedLeafCount() {
  update();
  std::size_t n = 0;
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it) {
    if (tree_->isNodeOccupied(*it))
      ++n;
  }
  return n;
}

std::vector<Voxel> OccupancyMap::occupiedVoxels() {
  update();
  std::vector<Voxel> voxels;
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it) {
    if (tree_->isNodeOccupied(*it))
      voxels.push_back({it.getX(), it.getY(), it.getZ(), it.getSize()});
  }
  return voxels;
}

void OccupancyMap::save(const std::string& path) {
  update();
  const std::string tmp = path + ".tmp";
  {
    std::ofstream file(tmp, std::ios_base::out | std::ios_base::binary);
    if (!file || !tree_->writeBinaryConst(file) || !file.flush()) {
      std::remove(tmp.c_str());
      throw Error("mapper: cannot write the map to '" + tmp + "'");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw Error("mapper: cannot move the map to '" + path + "'");
  }
}

std::string OccupancyMap::binaryData() {
  update();
  std::stringstream data;
  tree_->writeBinaryData(data);
  return data.str();
}

std::size_t OccupancyMap::memoryUsage() const {
  return tree_->memoryUsage();
}

}  // namespace mapping
}  // namespace unexmin

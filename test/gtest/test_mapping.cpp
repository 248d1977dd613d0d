// The occupancy mapper (cpp/unexmin/mapping) against closed forms: a closed box room scanned from its centre
// by a vertical fan turning about z; the free-space range; per-cloud deduplication; the sensor origin of each
// cloud; and voxel-for-voxel equality with OctoMap's own insertPointCloud on the same clouds.
#include <unexmin/mapping/occupancy_map.h>

#include "expect_error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace unexmin {
namespace mapping {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// An axis-aligned box room: centre and half extents [m].
struct Room {
  octomap::point3d c{0.03f, -0.02f, 0.01f};
  octomap::point3d h{3.0f, 2.0f, 1.5f};

  /// Range [m] from p (inside) along the unit direction d to the walls.
  double range(const octomap::point3d& p, const octomap::point3d& d) const {
    double t = 1e9;
    for (unsigned i = 0; i < 3; ++i) {
      if (d(i) > 1e-12)
        t = std::min(t, double(c(i) + h(i) - p(i)) / d(i));
      if (d(i) < -1e-12)
        t = std::min(t, double(c(i) - h(i) - p(i)) / d(i));
    }
    return t;
  }
  /// Distance [m] from p to the room's surface (inside or outside).
  double surfaceDistance(double x, double y, double z) const {
    const double q[3] = {std::fabs(x - c(0)) - h(0), std::fabs(y - c(1)) - h(1), std::fabs(z - c(2)) - h(2)};
    double outside = 0.0;
    for (double v : q)
      outside += std::max(v, 0.0) * std::max(v, 0.0);
    if (outside > 0.0)
      return std::sqrt(outside);
    return -std::max({q[0], q[1], q[2]});
  }
  bool inside(double x, double y, double z, double margin) const {
    return std::fabs(x - c(0)) < h(0) - margin && std::fabs(y - c(1)) < h(1) - margin &&
           std::fabs(z - c(2)) < h(2) - margin;
  }
};

/// One ping of a vertical fan (beams from -90 to +90 degrees of elevation) at heading yaw [rad] from origin,
/// ranges to the room's walls with Gaussian noise sigma [m].
std::vector<octomap::point3d> fanCloud(const Room& room, const octomap::point3d& origin, double yaw, int beams,
                                       double sigma, std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<octomap::point3d> cloud;
  for (int b = 0; b < beams; ++b) {
    const double el = -kPi / 2 + kPi * b / (beams - 1);
    const octomap::point3d d(std::cos(el) * std::cos(yaw), std::cos(el) * std::sin(yaw), std::sin(el));
    const double r = room.range(origin, d) + (sigma > 0 ? noise(rng) : 0.0);
    cloud.push_back(origin + d * static_cast<float>(r));
  }
  return cloud;
}

/// The clouds of one full turn (one ping per degree), seeded.
std::vector<std::vector<octomap::point3d>> turn(const Room& room, const octomap::point3d& origin, int pings = 360) {
  std::mt19937 rng(12);
  std::vector<std::vector<octomap::point3d>> clouds;
  for (int i = 0; i < pings; ++i)
    clouds.push_back(fanCloud(room, origin, 2 * kPi * i / pings, 181, 0.01, rng));
  return clouds;
}

/// Both trees hold the same leaves (key, depth, log-odds).
void expectSameTree(const octomap::OcTree& a, const octomap::OcTree& b) {
  ASSERT_EQ(a.getNumLeafNodes(), b.getNumLeafNodes());
  auto ia = a.begin_leafs(), ib = b.begin_leafs();
  std::size_t differ = 0;
  for (; ia != a.end_leafs() && ib != b.end_leafs(); ++ia, ++ib) {
    if (ia.getKey() != ib.getKey() || ia.getDepth() != ib.getDepth() ||
        std::fabs(ia->getLogOdds() - ib->getLogOdds()) > 1e-5f) {
      ++differ;
    }
  }
  EXPECT_EQ(differ, 0u);
}

const octomap::point3d kCentre(0.03f, -0.02f, 0.01f);

TEST(OccupancyMap, RoomMappedFromItsCentreMatchesTheWalls) {
  const Room room;
  MapperParams params;
  OccupancyMap map(params);
  for (const auto& cloud : turn(room, kCentre))
    map.insertCloud(cloud, kCentre);
  const double tau = params.resolution;

  // Precision: occupied voxel centres within one voxel of the analytic walls.
  const std::vector<Voxel> voxels = map.occupiedVoxels();
  ASSERT_GT(voxels.size(), 1000u);
  std::size_t near = 0;
  for (const Voxel& v : voxels)
    near += std::fabs(room.surfaceDistance(v.x, v.y, v.z)) <= tau;
  const double precision = double(near) / voxels.size();
  EXPECT_GE(precision, 0.95);

  // Coverage: samples of the six walls (every 5 cm) with an occupied voxel centre within tau.
  const octomap::OcTree& tree = map.tree();
  std::size_t samples = 0, covered = 0;
  const double step = 0.05;
  for (unsigned axis = 0; axis < 3; ++axis) {
    const unsigned u = (axis + 1) % 3, w = (axis + 2) % 3;
    for (int side = -1; side <= 1; side += 2) {
      for (double a = -room.h(u) + step / 2; a < room.h(u); a += step) {
        for (double b = -room.h(w) + step / 2; b < room.h(w); b += step) {
          double p[3];
          p[axis] = room.c(axis) + side * room.h(axis);
          p[u] = room.c(u) + a;
          p[w] = room.c(w) + b;
          ++samples;
          bool hit = false;
          for (int dx = -1; dx <= 1 && !hit; ++dx)
            for (int dy = -1; dy <= 1 && !hit; ++dy)
              for (int dz = -1; dz <= 1 && !hit; ++dz) {
                const octomap::point3d q(p[0] + dx * tau, p[1] + dy * tau, p[2] + dz * tau);
                octomap::OcTreeKey key;
                if (!tree.coordToKeyChecked(q, key))
                  continue;
                const octomap::OcTreeNode* node = tree.search(key);
                if (node == nullptr || !tree.isNodeOccupied(node))
                  continue;
                const octomap::point3d centre = tree.keyToCoord(key);
                hit = std::sqrt(std::pow(centre.x() - p[0], 2) + std::pow(centre.y() - p[1], 2) +
                                std::pow(centre.z() - p[2], 2)) <= tau;
              }
          covered += hit;
        }
      }
    }
  }
  const double coverage = double(covered) / samples;
  EXPECT_GE(coverage, 0.9);
  RecordProperty("precision", std::to_string(precision));
  RecordProperty("coverage", std::to_string(coverage));
  std::printf("room: %zu occupied voxels, precision %.4f, coverage %.4f (%zu wall samples)\n", voxels.size(), precision,
              coverage, samples);
}

TEST(OccupancyMap, FreeSpaceInsideTheRoomIsFreeAndNothingOutsideIsKnown) {
  const Room room;
  OccupancyMap map(MapperParams{});
  for (const auto& cloud : turn(room, kCentre))
    map.insertCloud(cloud, kCentre);
  const octomap::OcTree& tree = map.tree();
  const double res = tree.getResolution();
  std::size_t inside = 0, known = 0, occupied = 0;
  for (double x = room.c(0) - room.h(0); x < room.c(0) + room.h(0); x += res)
    for (double y = room.c(1) - room.h(1); y < room.c(1) + room.h(1); y += res)
      for (double z = room.c(2) - room.h(2); z < room.c(2) + room.h(2); z += res) {
        if (!room.inside(x, y, z, 2 * res))
          continue;
        ++inside;
        const octomap::OcTreeNode* node = tree.search(x, y, z);
        if (node == nullptr)
          continue;
        ++known;
        occupied += tree.isNodeOccupied(node);
      }
  ASSERT_GT(inside, 50000u);
  EXPECT_EQ(occupied, 0u);
  EXPECT_GE(double(known) / inside, 0.99);
  // Nothing more than a voxel outside the walls is known.
  std::size_t outside = 0;
  for (auto it = tree.begin_leafs(); it != tree.end_leafs(); ++it) {
    outside += room.surfaceDistance(it.getX(), it.getY(), it.getZ()) > 1.5 * res &&
               !room.inside(it.getX(), it.getY(), it.getZ(), 0.0);
  }
  EXPECT_EQ(outside, 0u);
}

/// The voxel at (x, y, 0.05) [m]: 'u' unknown, 'o' occupied, 'f' free.
char stateAt(const octomap::OcTree& tree, double x, double y) {
  const octomap::OcTreeNode* node = tree.search(x, y, 0.05);
  return node == nullptr ? 'u' : (tree.isNodeOccupied(node) ? 'o' : 'f');
}

TEST(OccupancyMap, EndpointsBeyondMaxRangeAreNotOccupiedButCarveFreeSpaceUpToIt) {
  MapperParams params;
  params.max_range = 10.0;
  OccupancyMap map(params);
  const octomap::point3d origin(0.05f, 0.05f, 0.05f);
  const CloudStats stats =
      map.insertCloud({octomap::point3d(15.05f, 0.05f, 0.05f), octomap::point3d(0.05f, 4.05f, 0.05f)}, origin);
  EXPECT_EQ(stats.beyond_range, 1u);
  EXPECT_EQ(stats.occupied_voxels, 1u);
  const auto state = [&map](double x, double y) { return stateAt(map.tree(), x, y); };
  EXPECT_EQ(state(5.05, 0.05), 'f');
  EXPECT_EQ(state(9.85, 0.05), 'f');
  EXPECT_EQ(state(10.45, 0.05), 'u');
  EXPECT_EQ(state(15.05, 0.05), 'u');
  EXPECT_EQ(state(0.05, 3.95), 'f');
  EXPECT_EQ(state(0.05, 4.05), 'o');
  EXPECT_EQ(map.occupiedLeafCount(), 1u);
}

TEST(OccupancyMap, ACloudsOwnRangeMarksNothingBeyondItAndCarvesUpToIt) {
  // Points at 3, 6 and 9 m along x, y and -x from the origin, inserted with a range of 5 m into a map whose
  // max_range is 10 m: only the 3 m point is occupied, the 6 and 9 m rays are free up to 5 m and unknown
  // beyond; the result is voxel for voxel a map whose max_range is 5 m.
  MapperParams wide;
  wide.max_range = 10.0;
  MapperParams narrow;
  narrow.max_range = 5.0;
  const octomap::point3d origin(0.05f, 0.05f, 0.05f);
  const std::vector<octomap::point3d> cloud = {octomap::point3d(3.05f, 0.05f, 0.05f),
                                               octomap::point3d(0.05f, 6.05f, 0.05f),
                                               octomap::point3d(-8.95f, 0.05f, 0.05f)};
  OccupancyMap limited(wide), reference(narrow), full(wide);
  const CloudStats stats = limited.insertCloud(cloud, origin, 5.0);
  EXPECT_EQ(stats.beyond_range, 2u);
  EXPECT_EQ(stats.occupied_voxels, 1u);
  reference.insertCloud(cloud, origin);
  expectSameTree(limited.tree(), reference.tree());
  const auto state = [&limited](double x, double y) { return stateAt(limited.tree(), x, y); };
  EXPECT_EQ(state(3.05, 0.05), 'o');
  EXPECT_EQ(state(0.05, 4.85), 'f');
  EXPECT_EQ(state(0.05, 5.45), 'u');
  EXPECT_EQ(state(0.05, 6.05), 'u');
  EXPECT_EQ(state(-4.75, 0.05), 'f');
  EXPECT_EQ(state(-5.35, 0.05), 'u');
  EXPECT_EQ(state(-8.95, 0.05), 'u');
  // The same cloud without a range of its own: the map's 10 m, every point occupied.
  EXPECT_EQ(full.insertCloud(cloud, origin).occupied_voxels, 3u);
  EXPECT_EQ(full.occupiedLeafCount(), 3u);
  EXPECT_TRUE(
      test::contains(test::thrownMessage([&] { limited.insertCloud(cloud, origin, std::nan("")); }), "range = nan"));
}

TEST(OccupancyMap, RepeatedPointsInOneCloudUpdateEachVoxelOnce) {
  const Room room;
  const auto clouds = turn(room, kCentre, 60);
  OccupancyMap once(MapperParams{}), thrice(MapperParams{});
  for (const auto& cloud : clouds) {
    once.insertCloud(cloud, kCentre);
    std::vector<octomap::point3d> repeated;
    for (int k = 0; k < 3; ++k)
      repeated.insert(repeated.end(), cloud.begin(), cloud.end());
    thrice.insertCloud(repeated, kCentre);
  }
  expectSameTree(once.tree(), thrice.tree());
  // One cloud's endpoint voxel gets exactly one hit: log-odds of 0.7.
  OccupancyMap single(MapperParams{});
  const octomap::point3d p(1.05f, 0.05f, 0.05f);
  single.insertCloud({p, p, p, p}, octomap::point3d(0.05f, 0.05f, 0.05f));
  const octomap::OcTreeNode* node = single.tree().search(p);
  ASSERT_NE(node, nullptr);
  EXPECT_NEAR(node->getOccupancy(), 0.7, 1e-6);
}

TEST(OccupancyMap, TheCloudsOriginDecidesWhichSpaceIsCarved) {
  const Room room;
  const auto clouds = turn(room, kCentre, 90);
  OccupancyMap right(MapperParams{}), wrong(MapperParams{});
  const octomap::point3d world_origin(8.0f, 6.0f, 0.0f);  // outside the room
  for (const auto& cloud : clouds) {
    right.insertCloud(cloud, kCentre);
    wrong.insertCloud(cloud, world_origin);
  }
  const auto freeOutside = [&](const octomap::OcTree& tree) {
    std::size_t n = 0;
    for (auto it = tree.begin_leafs(); it != tree.end_leafs(); ++it) {
      n += !tree.isNodeOccupied(*it) && room.surfaceDistance(it.getX(), it.getY(), it.getZ()) > 0.15 &&
           !room.inside(it.getX(), it.getY(), it.getZ(), 0.0);
    }
    return n;
  };
  EXPECT_EQ(freeOutside(right.tree()), 0u);
  EXPECT_GT(freeOutside(wrong.tree()), 1000u);
  // Between the false origin and the room: carved by the wrong map only.
  const octomap::OcTreeNode* between = wrong.tree().search(5.5, 4.1, 0.0);
  ASSERT_NE(between, nullptr);
  EXPECT_FALSE(wrong.tree().isNodeOccupied(between));
  EXPECT_EQ(right.tree().search(5.5, 4.1, 0.0), nullptr);
}

/// Inserts the clouds, each from its origin, into our map and into OctoMap's own tree by insertPointCloud, and
/// expects the same leaves, for a free-space range of 10 m and of 2.5 m (rays cut short).
void expectSameAsOctoMap(const std::vector<std::vector<octomap::point3d>>& clouds,
                         const std::vector<octomap::point3d>& origins) {
  for (double max_range : {10.0, 2.5}) {
    MapperParams params;
    params.max_range = max_range;
    OccupancyMap ours(params);
    octomap::OcTree theirs(params.resolution);
    theirs.setProbHit(params.prob_hit);
    theirs.setProbMiss(params.prob_miss);
    theirs.setClampingThresMin(params.clamp_min);
    theirs.setClampingThresMax(params.clamp_max);
    for (std::size_t k = 0; k < clouds.size(); ++k) {
      ours.insertCloud(clouds[k], origins[k]);
      octomap::Pointcloud pc;
      for (const auto& p : clouds[k])
        pc.push_back(p);
      theirs.insertPointCloud(pc, origins[k], max_range, false, false);
    }
    theirs.updateInnerOccupancy();
    theirs.prune();
    SCOPED_TRACE("max_range " + std::to_string(max_range));
    expectSameTree(ours.tree(), theirs);
    EXPECT_GT(ours.occupiedLeafCount(), 500u);
  }
}

TEST(OccupancyMap, EqualsOctoMapsInsertPointCloudVoxelForVoxel) {
  const Room room;
  const auto clouds = turn(room, kCentre, 120);
  expectSameAsOctoMap(clouds, std::vector<octomap::point3d>(clouds.size(), kCentre));
}

TEST(OccupancyMap, EqualsOctoMapFromMovingOriginsInEveryDirection) {
  // Origins anywhere in the room (either side of the key space's centre at 0), rays in random directions, one
  // in eight along an axis or in an axis plane (direction components exactly 0: axes the walk never steps).
  const Room room;
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<std::vector<octomap::point3d>> clouds;
  std::vector<octomap::point3d> origins;
  for (int k = 0; k < 60; ++k) {
    const octomap::point3d origin(room.c.x() + static_cast<float>(0.8 * room.h.x() * unit(rng)),
                                  room.c.y() + static_cast<float>(0.8 * room.h.y() * unit(rng)),
                                  room.c.z() + static_cast<float>(0.8 * room.h.z() * unit(rng)));
    std::vector<octomap::point3d> cloud;
    for (int b = 0; b < 200; ++b) {
      octomap::point3d d(static_cast<float>(unit(rng)), static_cast<float>(unit(rng)), static_cast<float>(unit(rng)));
      if (b % 8 == 0)
        d(b / 8 % 3) = 0.0f;
      if (b % 16 == 0)
        d((b / 8 + 1) % 3) = 0.0f;
      d.normalize();
      cloud.push_back(origin + d * static_cast<float>(room.range(origin, d) + noise(rng)));
    }
    clouds.push_back(cloud);
    origins.push_back(origin);
  }
  expectSameAsOctoMap(clouds, origins);
}

TEST(OccupancyMap, SavedMapReadsBackWithTheSameOccupiedLeaves) {
  const Room room;
  OccupancyMap map(MapperParams{});
  for (const auto& cloud : turn(room, kCentre, 90))
    map.insertCloud(cloud, kCentre);
  const std::string path = testing::TempDir() + "/unexmin_room.bt";
  map.save(path);
  octomap::OcTree read(0.1);
  ASSERT_TRUE(read.readBinary(path));
  std::size_t occupied = 0;
  for (auto it = read.begin_leafs(); it != read.end_leafs(); ++it)
    occupied += read.isNodeOccupied(*it);
  EXPECT_EQ(occupied, map.occupiedLeafCount());
  EXPECT_GT(occupied, 500u);
  map.reset();
  EXPECT_EQ(map.occupiedLeafCount(), 0u);
  EXPECT_THROW(map.save("/nonexistent-folder/x.bt"), Error);
}

TEST(MapperParams, OutOfRangeValuesNameTheParameter) {
  MapperParams p;
  p.resolution = 0.0;
  EXPECT_TRUE(test::contains(test::thrownMessage([&] { OccupancyMap m(p); }), "'resolution' = 0"));
  p = MapperParams{};
  p.prob_hit = 0.4;
  EXPECT_TRUE(test::contains(test::thrownMessage([&] { p.validate(); }), "'prob_hit' = 0.4"));
  p = MapperParams{};
  p.clamp_min = 0.45;
  EXPECT_TRUE(test::contains(test::thrownMessage([&] { p.validate(); }), "'clamp_min' = 0.45"));
  p = MapperParams{};
  p.max_range = std::nan("");
  EXPECT_TRUE(test::contains(test::thrownMessage([&] { p.validate(); }), "'max_range' = nan"));
}

}  // namespace
}  // namespace mapping
}  // namespace unexmin

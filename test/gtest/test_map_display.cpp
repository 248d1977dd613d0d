// mapping::occupiedCubes, heightColour and voxelCentres: the hue wheel at its five stops and in between, the
// leaves sorted into one cube list per size with the tree's node sizes, coloured between the lowest and highest
// leaf, and the centres of a map's occupied leaves.
#include <unexmin/mapping/map_display.h>

#include <gtest/gtest.h>

#include <cmath>

namespace unexmin {
namespace mapping {
namespace {

void expectColour(const Colour& c, float r, float g, float b) {
  EXPECT_FLOAT_EQ(c.r, r);
  EXPECT_FLOAT_EQ(c.g, g);
  EXPECT_FLOAT_EQ(c.b, b);
  EXPECT_FLOAT_EQ(c.a, 1.0f);
}

TEST(MapDisplay, HeightColourRunsFromBlueToRed) {
  expectColour(heightColour(-2.0, -2.0, 2.0), 0, 0, 1);    // lowest: blue
  expectColour(heightColour(-1.0, -2.0, 2.0), 0, 1, 1);    // a quarter up: cyan
  expectColour(heightColour(0.0, -2.0, 2.0), 0, 1, 0);     // halfway: green
  expectColour(heightColour(1.0, -2.0, 2.0), 1, 1, 0);     // three quarters: yellow
  expectColour(heightColour(2.0, -2.0, 2.0), 1, 0, 0);     // highest: red
  expectColour(heightColour(1.5, -2.0, 2.0), 1, 0.5f, 0);  // 7/8 of the way: between yellow and red
  expectColour(heightColour(9.0, -2.0, 2.0), 1, 0, 0);     // clamped
  expectColour(heightColour(3.0, 1.0, 1.0), 0, 1, 0);      // one height only: the middle
}

TEST(MapDisplay, OneCubeListPerLeafSizeColouredByHeight) {
  MapperParams params;
  params.resolution = 0.1;
  OccupancyMap map(params);
  const std::vector<Voxel> voxels = {{0.05, 0.05, -1.0, 0.1}, {1.1, 0.3, 1.0, 0.2}, {0.15, 0.05, 0.0, 0.1}};
  const std::vector<CubeList> cubes = occupiedCubes(map, voxels);
  ASSERT_EQ(cubes.size(), 17u);  // depths 0 (root) .. 16 (leaves)
  EXPECT_NEAR(cubes[16].size, 0.1, 1e-12);
  EXPECT_NEAR(cubes[15].size, 0.2, 1e-12);
  EXPECT_NEAR(cubes[0].size, 0.1 * std::pow(2.0, 16), 1e-6);
  ASSERT_EQ(cubes[16].cells.size(), 2u);
  ASSERT_EQ(cubes[15].cells.size(), 1u);
  for (unsigned d = 0; d < 15; ++d)
    EXPECT_TRUE(cubes[d].cells.empty()) << d;
  EXPECT_EQ(cubes[16].cells[0].z, -1.0);
  expectColour(cubes[16].colours[0], 0, 0, 1);
  expectColour(cubes[16].colours[1], 0, 1, 0);
  expectColour(cubes[15].colours[0], 1, 0, 0);
  EXPECT_EQ(cubes[15].cells[0].x, 1.1);
}

TEST(MapDisplay, ShowsTheOccupiedLeavesOfAMap) {
  MapperParams params;
  params.resolution = 0.1;
  OccupancyMap map(params);
  // Three walls hit from the origin, each point at a voxel centre.
  const std::vector<octomap::point3d> hits = {{1.05f, 0.05f, 0.05f}, {0.05f, 2.05f, 0.05f}, {0.05f, 0.05f, -1.05f}};
  for (int i = 0; i < 3; ++i)
    map.insertCloud(hits, octomap::point3d(0.05f, 0.05f, 0.05f));
  const std::vector<Voxel> voxels = map.occupiedVoxels();
  ASSERT_EQ(voxels.size(), 3u);
  const std::vector<octomap::point3d> centres = voxelCentres(voxels);
  ASSERT_EQ(centres.size(), 3u);
  for (const octomap::point3d& hit : hits) {
    int found = 0;
    for (const octomap::point3d& c : centres)
      found += (c - hit).norm() < 1e-4;
    EXPECT_EQ(found, 1) << hit;
  }
  const std::vector<CubeList> cubes = occupiedCubes(map, voxels);
  EXPECT_EQ(cubes.back().cells.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    const double z = cubes.back().cells[k].z;
    const Colour c = cubes.back().colours[k];
    if (z < -1.0)
      expectColour(c, 0, 0, 1);  // the floor hit, lowest
    if (z > 0.0)
      expectColour(c, 1, 0, 0);  // the two at 0.05 m, highest
  }
}

}  // namespace
}  // namespace mapping
}  // namespace unexmin

// Bullet's shape of a static mesh and its BVH cache (cpp/unexmin/sim/collision_shape.h): a sphere's shape built, then
// read from the cache, answers seeded rays from its centre at its radius and exactly as the built one; another mesh,
// a damaged or cut cache file and a folder that cannot be written all build the BVH again with the same answers;
// which meshes get a cache file; a mesh of more triangles than one part of Bullet's BVH numbers answers on each of
// them.
#include <unexmin/raycast/bullet_ray_caster.h>
#include <unexmin/sim/collision_shape.h>
#include "mesh_fixture.h"
#include "temp_dir.h"

#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace unexmin {
namespace test {
namespace {

sim::TriangleMesh sphereMesh(double radius, int levels) {
  const Geometry g = icosphere(Eigen::Vector3d(1, 2, 3), radius, levels);
  sim::TriangleMesh m;
  m.name = "ball";
  for (const auto& v : g.vertices)
    m.vertices.push_back(v.cast<float>());
  m.indices = g.indices;
  return m;
}

struct RayAnswer {
  float fraction;
  btVector3 normal;
  int triangle;
};

/// Bullet's closest hit of rays from the sphere's centre in `n` seeded directions, `length` long.
std::vector<RayAnswer> castRays(sim::MeshCollisionShape& shape, int n, double length) {
  btCollisionObject object;
  object.setCollisionShape(&shape.shape());
  std::mt19937_64 rng(20261126);
  std::normal_distribution<double> g;
  std::vector<RayAnswer> out;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d d = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    const btVector3 from(1, 2, 3), to = from + btVector3(d.x(), d.y(), d.z()) * length;
    struct Closest : btCollisionWorld::ClosestRayResultCallback {
      using ClosestRayResultCallback::ClosestRayResultCallback;
      btScalar addSingleResult(btCollisionWorld::LocalRayResult& r, bool world) override {
        triangle = r.m_localShapeInfo ? r.m_localShapeInfo->m_triangleIndex : -1;
        return ClosestRayResultCallback::addSingleResult(r, world);
      }
      int triangle = -1;
    } callback(from, to);
    btCollisionWorld::rayTestSingle(btTransform(btQuaternion::getIdentity(), from),
                                    btTransform(btQuaternion::getIdentity(), to), &object, &shape.shape(),
                                    btTransform::getIdentity(), callback);
    out.push_back(
        {callback.hasHit() ? callback.m_closestHitFraction : -1.0f, callback.m_hitNormalWorld, callback.triangle});
  }
  return out;
}

void expectSameAnswers(const std::vector<RayAnswer>& a, const std::vector<RayAnswer>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].fraction, b[i].fraction) << "ray " << i;
    EXPECT_EQ(a[i].triangle, b[i].triangle) << "ray " << i;
    EXPECT_TRUE(a[i].normal == b[i].normal) << "ray " << i;
  }
}

bool exists(const std::string& path) {
  return std::ifstream(path).good();
}

constexpr double kRadius = 2.0, kLength = 5.0;
constexpr int kRays = 500;

TEST(CollisionShape, TheCachedBvhAnswersAsTheBuiltOneAndTheSphereAtItsRadius) {
  const sim::TriangleMesh mesh = sphereMesh(kRadius, 4);  // 5120 triangles
  const std::string cache = testTempDir() + "ball.ply.bvh";
  std::remove(cache.c_str());
  sim::MeshCollisionShape built(mesh, cache);
  EXPECT_FALSE(built.fromCache());
  ASSERT_TRUE(exists(cache));
  sim::MeshCollisionShape read(mesh, cache);
  EXPECT_TRUE(read.fromCache());
  sim::MeshCollisionShape plain(mesh);  // no cache at all
  EXPECT_FALSE(plain.fromCache());
  const std::vector<RayAnswer> a = castRays(plain, kRays, kLength);
  expectSameAnswers(a, castRays(built, kRays, kLength));
  expectSameAnswers(a, castRays(read, kRays, kLength));
  // The icosphere's flat faces lie inside the sphere by at most 1 - cos(edge angle / 2) of its radius (about 0.3 %
  // at 4 subdivisions): every ray hits within that of the radius, on a triangle of the mesh.
  for (const RayAnswer& r : a) {
    ASSERT_GE(r.fraction, 0.0f);
    EXPECT_NEAR(r.fraction * kLength, kRadius, 0.006 * kRadius);
    EXPECT_GE(r.triangle, 0);
    EXPECT_LT(r.triangle, static_cast<int>(mesh.triangleCount()));
  }
}

TEST(CollisionShape, AnotherMeshOrADamagedFileBuildsTheBvhAgain) {
  const std::string cache = testTempDir() + "changing.ply.bvh";
  std::remove(cache.c_str());
  sim::TriangleMesh mesh = sphereMesh(kRadius, 3);
  {
    sim::MeshCollisionShape first(mesh, cache);
  }
  // One vertex moved by a millimetre: another mesh; its BVH is built and replaces the file.
  mesh.vertices[7].x() += 0.001f;
  sim::MeshCollisionShape moved(mesh, cache);
  EXPECT_FALSE(moved.fromCache());
  sim::MeshCollisionShape plain(mesh);
  const std::vector<RayAnswer> a = castRays(plain, kRays, kLength);
  expectSameAnswers(a, castRays(moved, kRays, kLength));
  EXPECT_TRUE(sim::MeshCollisionShape(mesh, cache).fromCache()) << "the file now holds the moved mesh's BVH";

  std::string bytes;
  {
    std::ifstream in(cache, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  ASSERT_GT(bytes.size(), 1000u);
  std::string damaged = bytes;
  damaged[bytes.size() / 2] = static_cast<char>(damaged[bytes.size() / 2] ^ 0x5A);  // one byte of a node
  const std::string cut = bytes.substr(0, bytes.size() - 16);
  for (const std::string& content : {damaged, cut, bytes + "x"}) {
    std::ofstream(cache, std::ios::binary) << content;
    sim::MeshCollisionShape again(mesh, cache);
    EXPECT_FALSE(again.fromCache()) << "a file of " << content.size() << " bytes (the good one: " << bytes.size()
                                    << ")";
    expectSameAnswers(a, castRays(again, kRays, kLength));
  }
  EXPECT_TRUE(sim::MeshCollisionShape(mesh, cache).fromCache()) << "rewritten";
}

TEST(CollisionShape, AFolderThatCannotBeWrittenKeepsNoCache) {
  const sim::TriangleMesh mesh = sphereMesh(kRadius, 2);
  const std::string cache = testTempDir() + "no_such_folder/ball.ply.bvh";
  sim::MeshCollisionShape shape(mesh, cache);
  EXPECT_FALSE(shape.fromCache());
  EXPECT_FALSE(exists(cache));
  sim::MeshCollisionShape plain(mesh);
  expectSameAnswers(castRays(plain, kRays, kLength), castRays(shape, kRays, kLength));
}

TEST(CollisionShape, AMeshOfMoreThan2To21TrianglesAnswersOnEveryTriangle) {
  // A flat grid of 1025 x 1025 cells of 1 cm at z = 0, two triangles per cell in row order: 2 101 250 triangles, more
  // than Bullet's quantised BVH numbers within one part (2^21). A ray straight down through the middle of a triangle
  // 1 m above it meets that triangle at 1 m, whatever its number: the first, the last of the first 2^21, the first and
  // the last after them.
  const int n = 1025;
  const float h = 0.01f;
  sim::TriangleMesh mesh;
  mesh.name = "grid";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      mesh.vertices.emplace_back(h * static_cast<float>(i), h * static_cast<float>(j), 0.0f);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, c, b, d, c});
    }
  ASSERT_GT(mesh.triangleCount(), sim::kBulletPartTriangles);
  sim::MeshCollisionShape shape(mesh);
  btCollisionObject object;
  object.setCollisionShape(&shape.shape());
  raycast::BulletTarget target;
  target.object = &object;
  target.index = 0;
  target.mesh = &mesh;
  raycast::BulletRayCaster caster({target});
  const int last = static_cast<int>(mesh.triangleCount()) - 1, part = static_cast<int>(sim::kBulletPartTriangles);
  for (const int t : {0, part - 1, part, part + 1, last}) {
    Eigen::Vector3f centre = Eigen::Vector3f::Zero();
    for (int k = 0; k < 3; ++k)
      centre += mesh.vertices[mesh.indices[3 * t + k]] / 3.0f;
    raycast::Ray ray;
    ray.origin = centre + Eigen::Vector3f(0.0f, 0.0f, 1.0f);
    ray.direction = Eigen::Vector3f(0.0f, 0.0f, -1.0f);
    ray.max_range = 2.0f;
    std::vector<raycast::Hit> hits;
    caster.cast({ray}, hits);
    ASSERT_TRUE(hits.at(0).hit()) << "triangle " << t;
    EXPECT_EQ(hits[0].primitive, t);
    EXPECT_NEAR(hits[0].range, 1.0f, 1e-5f) << "triangle " << t;
    EXPECT_NEAR(hits[0].u, 1.0f / 3.0f, 1e-3f) << "triangle " << t;  // its middle
    EXPECT_NEAR(hits[0].v, 1.0f / 3.0f, 1e-3f) << "triangle " << t;
  }
}

TEST(CollisionShape, OnlyLargeMeshesGetACacheFile) {
  sim::MeshEntry entry;
  entry.file = "/some/where/mine.ply";
  sim::TriangleMesh mesh;
  mesh.indices.resize(3 * (sim::kBvhCacheMinTriangles - 1));
  EXPECT_EQ(sim::bvhCacheFile(entry, mesh), "");
  mesh.indices.resize(3 * sim::kBvhCacheMinTriangles);
  EXPECT_EQ(sim::bvhCacheFile(entry, mesh), "/some/where/mine.ply.bvh");
}

}  // namespace
}  // namespace test
}  // namespace unexmin

// Triangle meshes written by the tests themselves (boxes, icospheres) as binary STL files the
// simulator's mesh loader reads back: shared by the ray-caster and sonar tests.
#pragma once

#include "temp_dir.h"

#include <gtest/gtest.h>
#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace unexmin {
namespace test {

struct Geometry {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<int> indices;
};

/// Binary STL in the test process's temporary folder; returns its path.
inline std::string writeStl(const std::string& name, const Geometry& g) {
  const std::string path = testTempDir() + name + ".stl";
  std::ofstream out(path, std::ios::binary);
  char header[80] = {};
  out.write(header, sizeof(header));
  const std::uint32_t count = static_cast<std::uint32_t>(g.indices.size() / 3);
  out.write(reinterpret_cast<const char*>(&count), 4);
  for (std::size_t t = 0; t < g.indices.size(); t += 3) {
    float data[12] = {};
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c)
        data[3 + 3 * k + c] = static_cast<float>(g.vertices[g.indices[t + k]][c]);
    out.write(reinterpret_cast<const char*>(data), sizeof(data));
    const std::uint16_t attribute = 0;
    out.write(reinterpret_cast<const char*>(&attribute), 2);
  }
  return path;
}

/// Icosahedron subdivided `levels` times, vertices on the sphere (centre, radius).
inline Geometry icosphere(const Eigen::Vector3d& centre, double radius, int levels) {
  const double p = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> v = {{-1, p, 0},  {1, p, 0},  {-1, -p, 0}, {1, -p, 0}, {0, -1, p},  {0, 1, p},
                                    {0, -1, -p}, {0, 1, -p}, {p, 0, -1},  {p, 0, 1},  {-p, 0, -1}, {-p, 0, 1}};
  for (auto& x : v)
    x.normalize();
  std::vector<int> f = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                        4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                        6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    const auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = midpoint.find(key);
      if (it != midpoint.end())
        return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return midpoint[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<int> next;
    for (std::size_t t = 0; t < f.size(); t += 3) {
      const int a = f[t], b = f[t + 1], c = f[t + 2], ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    f = std::move(next);
  }
  Geometry g;
  for (const auto& x : v)
    g.vertices.push_back(centre + radius * x);
  g.indices = f;
  return g;
}

/// Axis-aligned box [lo, hi], 12 triangles.
inline Geometry box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  Geometry g;
  for (int i = 0; i < 8; ++i)
    g.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  g.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
               2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  return g;
}

}  // namespace test
}  // namespace unexmin

// Test fixture for the imaging and side-scan sonars (cpp/unexmin/sensors/sonar/imaging_sonar_sensor.h,
// side_scan_sensor.h): the sphere robot "T" with one sonar on the link T/sonar_link at its centre (the hull is
// invisible to its own rays), in open water with meshes written by the test, and the shadow's closed form.
#pragma once

#include "sonar_fixture.h"

#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace unexmin {
namespace test {

constexpr double kDegree = M_PI / 180.0;

/// A world with `meshes` and the robot at `at` (world; surface z = 0) carrying one sensor of `type` at `rate` [Hz]
/// on T/sonar_link, turned by `rpy` [rad] from the base link; the caster on `caster_threads` threads (0: every hardware
/// thread).
inline std::unique_ptr<SonarWorld> sonarRig(const std::vector<std::pair<std::string, Geometry>>& meshes,
                                            const Eigen::Vector3d& at, const Eigen::Vector3d& rpy,
                                            const std::string& type, double rate,
                                            const std::map<std::string, std::string>& params, std::uint64_t seed = 1,
                                            int caster_threads = 0) {
  const std::string urdf = sensorUrdf(SphereSpec(), mountLink("T/sonar_link", Eigen::Vector3d::Zero(), rpy),
                                      sensorXml("sonar", type, "T/sonar_link", rate, params));
  return std::make_unique<SonarWorld>(meshWorld(meshes, at), urdf, seed, 0.002, "embree", caster_threads);
}

/// A flat floor, its top `altitude` [m] below `at`, 200 m square.
inline Geometry floorBelow(const Eigen::Vector3d& at, double altitude) {
  const double top = at.z() - altitude;
  return box(Eigen::Vector3d(at.x() - 100, at.y() - 100, top - 1), Eigen::Vector3d(at.x() + 100, at.y() + 100, top));
}

/// The acoustic shadow of a box of height h [m] standing on a flat floor, seen from a sonar `altitude` H [m] above
/// the floor, whose near face is at horizontal distance d [m] and far face at d + t: the slant ranges [m] of the last
/// echo of the box (its far top edge) and of the first floor echo behind it (similar triangles: the ray over the far
/// top edge meets the floor at horizontal distance (d + t) H / (H - h)).
struct Shadow {
  double start = 0.0, end = 0.0;
};
inline Shadow boxShadow(double altitude, double d, double t, double h) {
  const double x = (d + t) * altitude / (altitude - h);
  return {std::hypot(d + t, altitude - h), std::hypot(x, altitude)};
}

/// Bins [first, last] of the longest run of zero codes in `line` after its first non-zero code, {-1, -1} for none.
inline std::pair<int, int> longestGap(const std::vector<std::uint8_t>& line) {
  std::pair<int, int> best{-1, -1};
  int best_length = 0, i = 0;
  const int n = static_cast<int>(line.size());
  while (i < n && line[i] == 0)
    ++i;
  while (i < n) {
    while (i < n && line[i] != 0)
      ++i;
    const int start = i;
    while (i < n && line[i] == 0)
      ++i;
    if (i < n && i - start > best_length) {  // a gap closed by an echo
      best = {start, i - 1};
      best_length = i - start;
    }
  }
  return best;
}

}  // namespace test
}  // namespace unexmin

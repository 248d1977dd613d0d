#include <unexmin/sim/spawn_placement.h>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace unexmin {
namespace sim {
namespace {

/// 0, 1, -1, 2, -2, ... up to +-n: the order in which ties are taken.
std::vector<int> outward(int n) {
  std::vector<int> v{0};
  for (int i = 1; i <= n; ++i) {
    v.push_back(i);
    v.push_back(-i);
  }
  return v;
}

/// Lattice offsets (in steps) nearest first, then level (k = 0) before up or down, then in `outward` order.
std::vector<Eigen::Vector3i> latticeOffsets() {
  std::vector<Eigen::Vector3i> offsets;
  for (int k : outward(kSpawnSteps))
    for (int j : outward(kSpawnSteps))
      for (int i : outward(kSpawnSteps))
        if (i != 0 || j != 0 || k != 0)
          offsets.emplace_back(i, j, k);
  std::stable_sort(offsets.begin(), offsets.end(), [](const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
    return std::make_tuple(a.squaredNorm(), std::abs(a.z())) < std::make_tuple(b.squaredNorm(), std::abs(b.z()));
  });
  return offsets;
}

}  // namespace

double hullRadius(const RobotDescription& description) {
  if (description.hull_box.maxCoeff() > 0.0)
    return 0.5 * description.hull_box.norm();
  if (description.hydro.radius > 0.0)
    return description.hydro.radius;
  return std::cbrt(3.0 * description.hydro.volume / (4.0 * M_PI));
}

void placeSpawns(std::vector<RobotSpawn>& spawns, const std::vector<double>& radii, std::size_t count, double surface_z,
                 const SpawnProbe& probe, const std::string& file) {
  if (radii.size() < count || spawns.size() < count)
    throw ConfigError(file + ": spawn placement given " + formatNumber(radii.size()) + " hull radii and " +
                      formatNumber(spawns.size()) + " spawns for " + formatNumber(count) + " robots");
  const std::vector<Eigen::Vector3i> offsets = latticeOffsets();
  for (std::size_t n = 0; n < count; ++n) {
    if (spawns[n].placed)
      continue;
    const double r = radii[n];
    const double step = 2.0 * r + kSpawnMargin;
    const Eigen::Isometry3d anchor = spawns[n].pose;
    const Eigen::Vector3d heading = anchor.linear().col(0);
    const double yaw = std::atan2(heading.y(), heading.x());
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    bool found = false;
    for (const Eigen::Vector3i& o : offsets) {
      const Eigen::Vector3d p = anchor.translation() + turn * (step * o.cast<double>());
      if (p.z() + r + kSpawnMargin > surface_z)
        continue;
      bool apart = true;
      for (std::size_t m = 0; m < count && apart; ++m)
        if (m != n && spawns[m].placed)
          apart = (spawns[m].pose.translation() - p).norm() >= r + radii[m] + kSpawnMargin - 1e-9;
      if (!apart || !probe.clear(p, r + kSpawnMargin) || !probe.open(anchor.translation(), p))
        continue;
      spawns[n].pose.translation() = p;
      spawns[n].placed = true;
      found = true;
      break;
    }
    const auto mm = [](double x) { return formatNumber(std::round(1000.0 * x) / 1000.0); };
    if (!found)
      throw ConfigError(file + ": no room for robot '" + spawns[n].name + "' (hull radius " + mm(r) +
                        " m): no point of the " + mm(step) + " m lattice within " + formatNumber(kSpawnSteps) +
                        " steps of its anchor lies " + formatNumber(kSpawnMargin) +
                        " m clear of the walls, the surface and the other robots in the anchor's water; list it "
                        "in 'robots'");
  }
}

}  // namespace sim
}  // namespace unexmin

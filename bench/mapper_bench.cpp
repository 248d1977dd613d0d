// Insertion speed of the mapper (cpp/unexmin/mapping) against OctoMap's own insertPointCloud used the way
// octomap_server uses it (non-lazy updates, the whole tree pruned after every cloud), on the same clouds:
// M3-like pings (a 256-beam fan over 130 degrees) from a robot flying and turning through a 40 m x 5 m x 4 m
// gallery (ranges up to about 10 m, free-space range 10 m). Not a test; docs/benchmarks.md "Mapping".
//
//   mapper_bench [resolution_m=0.1] [max_range_m=10] [pings=2000] [runs=5]
#include <unexmin/mapping/occupancy_map.h>

#include <octomap/OcTree.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

/// CPU time of this (single-threaded) process [s]: what the machine's other load disturbs least.
double cpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/// Minimum and median of a list of times.
struct Times {
  std::vector<double> t;
  double min() {
    std::sort(t.begin(), t.end());
    return t.front();
  }
  double median() {
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
  }
};
constexpr double kPi = 3.14159265358979323846;

struct Ping {
  octomap::point3d origin;
  std::vector<octomap::point3d> points;
};

/// Range [m] from p inside the box [lo, hi] along the unit direction d.
double boxRange(const octomap::point3d& p, const octomap::point3d& d, const octomap::point3d& lo,
                const octomap::point3d& hi) {
  double t = 1e9;
  for (unsigned i = 0; i < 3; ++i) {
    if (d(i) > 1e-9)
      t = std::min(t, double(hi(i) - p(i)) / d(i));
    if (d(i) < -1e-9)
      t = std::min(t, double(lo(i) - p(i)) / d(i));
  }
  return t;
}

std::vector<Ping> makePings(int count) {
  const octomap::point3d lo(0, -2.5, -2), hi(40, 2.5, 2);
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<Ping> pings;
  for (int k = 0; k < count; ++k) {
    const double t = k / 40.0;  // 40 Hz
    Ping ping;
    ping.origin = octomap::point3d(static_cast<float>(2.0 + 0.3 * t), static_cast<float>(0.8 * std::sin(0.2 * t)),
                                   static_cast<float>(0.5 * std::sin(0.13 * t)));
    const double yaw = 0.6 * std::sin(0.1 * t), pitch = 0.3 * std::sin(0.07 * t);
    for (int b = 0; b < 256; ++b) {
      // The fan in the robot's vertical plane across its heading, tilted forward by 'pitch'.
      const double a = -65.0 * kPi / 180 + 130.0 * kPi / 180 * b / 255;
      octomap::point3d d(static_cast<float>(std::sin(pitch)), static_cast<float>(std::sin(a)),
                         static_cast<float>(std::cos(a)));
      if (b % 2)
        d.z() = -d.z();
      d.normalize();
      const octomap::point3d dw(static_cast<float>(std::cos(yaw) * d.x() - std::sin(yaw) * d.y()),
                                static_cast<float>(std::sin(yaw) * d.x() + std::cos(yaw) * d.y()), d.z());
      const double r = boxRange(ping.origin, dw, lo, hi) + noise(rng);
      ping.points.push_back(ping.origin + dw * static_cast<float>(r));
    }
    pings.push_back(std::move(ping));
  }
  return pings;
}

}  // namespace

int main(int argc, char** argv) {
  const double resolution = argc > 1 ? std::atof(argv[1]) : 0.1;
  const double max_range = argc > 2 ? std::atof(argv[2]) : 10.0;
  const int count = argc > 3 ? std::atoi(argv[3]) : 2000;
  const int repeats = std::max(1, argc > 4 ? std::atoi(argv[4]) : 5);
  const std::vector<Ping> pings = makePings(count);
  std::size_t points = 0;
  for (const Ping& p : pings)
    points += p.points.size();

  unexmin::mapping::MapperParams params;
  params.resolution = resolution;
  params.max_range = max_range;
  std::vector<octomap::Pointcloud> clouds(pings.size());
  for (std::size_t k = 0; k < pings.size(); ++k)
    for (const auto& p : pings[k].points)
      clouds[k].push_back(p);

  // The two alternate, `repeats` times each, on a fresh map: the minimum and the median time of each are
  // reported, wall-clock and CPU time (the machine is shared; the minimum is the least disturbed run, and the
  // CPU time leaves out the time other processes held the core).
  Times wall_ours, wall_theirs, cpu_ours, cpu_theirs;
  std::size_t occupied_ours = 0, occupied_theirs = 0, memory_ours = 0, leaves_differ = 0;
  double worst = 0.0;
  for (int r = 0; r < repeats; ++r) {
    // Ours: insert every cloud; update() once a second of pings (40 clouds), as the node does on its timer (a
    // no-op: insertCloud keeps inner nodes and pruning up to date).
    unexmin::mapping::OccupancyMap ours(params);
    auto t0 = Clock::now();
    double c0 = cpuSeconds();
    for (std::size_t k = 0; k < pings.size(); ++k) {
      ours.insertCloud(pings[k].points, pings[k].origin);
      if (k % 40 == 39)
        ours.update();
    }
    ours.update();
    wall_ours.t.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    cpu_ours.t.push_back(cpuSeconds() - c0);
    occupied_ours = ours.occupiedLeafCount();
    memory_ours = ours.memoryUsage();

    // octomap_server's way: insertPointCloud (non-lazy) and prune after every cloud.
    octomap::OcTree theirs(resolution);
    theirs.setProbHit(params.prob_hit);
    theirs.setProbMiss(params.prob_miss);
    theirs.setClampingThresMin(params.clamp_min);
    theirs.setClampingThresMax(params.clamp_max);
    t0 = Clock::now();
    c0 = cpuSeconds();
    for (std::size_t k = 0; k < pings.size(); ++k) {
      const auto k0 = Clock::now();
      theirs.insertPointCloud(clouds[k], pings[k].origin, max_range, false, false);
      theirs.prune();
      worst = std::max(worst, std::chrono::duration<double>(Clock::now() - k0).count());
    }
    wall_theirs.t.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    cpu_theirs.t.push_back(cpuSeconds() - c0);
    theirs.updateInnerOccupancy();
    theirs.prune();
    occupied_theirs = 0;
    for (auto it = theirs.begin_leafs(); it != theirs.end_leafs(); ++it)
      occupied_theirs += theirs.isNodeOccupied(*it);
    // The two trees leaf for leaf: same key, depth and log-odds.
    const octomap::OcTree& mine = ours.tree();
    leaves_differ = mine.getNumLeafNodes() > theirs.getNumLeafNodes()
                        ? mine.getNumLeafNodes() - theirs.getNumLeafNodes()
                        : theirs.getNumLeafNodes() - mine.getNumLeafNodes();
    auto a = mine.begin_leafs(), b = theirs.begin_leafs();
    for (; a != mine.end_leafs() && b != theirs.end_leafs(); ++a, ++b) {
      leaves_differ += a.getKey() != b.getKey() || a.getDepth() != b.getDepth() || a->getLogOdds() != b->getLogOdds();
    }
  }

  std::printf("mapper_bench: %d clouds, %zu points, resolution %g m, max range %g m, %d runs each\n", count, points,
              resolution, max_range, repeats);
  std::printf(
      "  ours (dedup, Morton-ordered batch):      wall min %7.3f s (%9.0f points/s), median %7.3f s; "
      "CPU min %7.3f s, median %7.3f s\n",
      wall_ours.min(), points / wall_ours.min(), wall_ours.median(), cpu_ours.min(), cpu_ours.median());
  std::printf(
      "  OctoMap insertPointCloud + prune/cloud:  wall min %7.3f s (%9.0f points/s), median %7.3f s; "
      "CPU min %7.3f s, median %7.3f s; worst cloud %.1f ms (wall)\n",
      wall_theirs.min(), points / wall_theirs.min(), wall_theirs.median(), cpu_theirs.min(), cpu_theirs.median(),
      1e3 * worst);
  std::printf("  speed-up wall %.1fx (minima), %.1fx (medians); CPU %.1fx (minima), %.1fx (medians)\n",
              wall_theirs.min() / wall_ours.min(), wall_theirs.median() / wall_ours.median(),
              cpu_theirs.min() / cpu_ours.min(), cpu_theirs.median() / cpu_ours.median());
  std::printf(
      "  occupied leaves: ours %zu, OctoMap %zu; leaves differing (key, depth or log-odds) %zu; "
      "tree memory ours %zu bytes\n",
      occupied_ours, occupied_theirs, leaves_differ, memory_ours);
  return leaves_differ == 0 ? 0 : 1;
}

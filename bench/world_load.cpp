// Where a world's load goes, stage by stage, with no ROS: the mesh files read (loadMesh), the world built (the meshes
// read again and Bullet's BVH of every collision mesh), the ray caster built (Embree's scene); for each stage its wall
// time, its CPU time (every thread of the process; the figure to compare on a loaded machine) and the peak resident
// memory of the process during it (a mesh's Bullet BVH comes from its cache file when there is one: run twice).
// --compare then adds the alternatives to these stages, on top of the memory above: the BVH built, the triangles
// copied into Embree's own buffers (and the same rays cast by both Embree scenes), every file read by assimp.
// Not a test: results go to docs/benchmarks.md.
//   world_load <world file> [--compare]
#include <unexmin/raycast/embree_ray_caster.h>
#include <unexmin/raycast/ray_caster_factory.h>
#include <unexmin/sim/collision_shape.h>
#include <unexmin/sim/mesh.h>
#include <unexmin/sim/world.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <map>
#include <random>
#include <string>

namespace {

double cpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double wallSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// A field of /proc/self/status in MB (VmRSS, VmHWM).
double statusMb(const std::string& field) {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.compare(0, field.size() + 1, field + ":") == 0)
      return std::stod(line.substr(field.size() + 1)) / 1024.0;
  return -1.0;
}

/// Peak resident memory counted afresh from now (Linux: /proc/self/clear_refs, 5).
void resetPeak() {
  std::ofstream("/proc/self/clear_refs") << "5";
}

/// Times one stage and prints it.
template <typename F>
void stage(const char* name, F f) {
  resetPeak();
  const double w0 = wallSeconds(), c0 = cpuSeconds();
  f();
  std::printf("%-34s wall %7.2f s  cpu %7.2f s  peak RSS %7.0f MB  RSS after %7.0f MB\n", name, wallSeconds() - w0,
              cpuSeconds() - c0, statusMb("VmHWM"), statusMb("VmRSS"));
  std::fflush(stdout);
}

/// The per-step cost of the two ways of building Embree's scene: the same seeded rays (200,000 from `origin` in every
/// direction, 50 m long) cast on one thread by each caster, alternately three times; prints the least CPU time of
/// each and whether every hit is the same.
void compareCasts(const unexmin::raycast::RayCaster& in_place, const unexmin::raycast::RayCaster& copied,
                  const Eigen::Vector3f& origin) {
  std::mt19937_64 rng(7);
  std::normal_distribution<float> g;
  std::vector<unexmin::raycast::Ray> rays(200000);
  for (unexmin::raycast::Ray& r : rays) {
    r.origin = origin;
    r.direction = Eigen::Vector3f(g(rng), g(rng), g(rng)).normalized();
    r.max_range = 50.0f;
  }
  std::vector<unexmin::raycast::Hit> a, b;
  double best[2] = {1e9, 1e9};
  for (int round = 0; round < 3; ++round)
    for (int k = 0; k < 2; ++k) {
      const double c0 = cpuSeconds();
      (k == 0 ? in_place : copied).cast(rays, k == 0 ? a : b);
      best[k] = std::min(best[k], cpuSeconds() - c0);
    }
  std::size_t same = 0, hits = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    hits += a[i].hit();
    same += a[i].range == b[i].range && a[i].primitive == b[i].primitive && a[i].index == b[i].index &&
            a[i].u == b[i].u && a[i].v == b[i].v;
  }
  std::printf("casts of %zu rays (%zu hits): in place %.3f s CPU, copied %.3f s CPU; the same hit for %zu rays\n",
              rays.size(), hits, best[0], best[1], same);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const bool compare = argc == 3 && std::string(argv[2]) == "--compare";
  if (argc < 2 || argc > 3 || (argc == 3 && !compare)) {
    std::fprintf(stderr, "usage: world_load <world file> [--compare]\n");
    return 2;
  }
  try {
    unexmin::sim::WorldConfig config;
    stage("world file", [&] { config = unexmin::sim::loadWorldConfig(argv[1]); });
    std::size_t triangles = 0;
    stage("mesh files read (loadMesh)", [&] {
      for (const unexmin::sim::MeshEntry& e : config.meshes)
        if (e.collision || e.seen_by_cameras || e.seen_by_sonars)
          triangles += unexmin::sim::loadMesh(e).triangleCount();
    });
    std::unique_ptr<unexmin::sim::World> world;
    stage("world (read + Bullet BVH)", [&] {
      world = std::make_unique<unexmin::sim::World>(config, std::map<std::string, unexmin::sim::RobotDescription>(), 0,
                                                    0.002, 0);
    });
    std::unique_ptr<unexmin::raycast::RayCaster> caster;
    unexmin::raycast::RayCasterOptions one_thread;  // the per-step comparison below: one core's CPU time
    one_thread.threads = compare ? 1 : 0;
    stage("ray caster", [&] { caster = unexmin::raycast::makeRayCaster(config.ray_caster, *world, one_thread); });
    if (compare) {  // after the stages above, whose memory they add to
      stage("(before) Bullet BVH, no cache", [&] {
        for (std::size_t i = 0; i < world->meshCount(); ++i)
          if (world->meshBody(i))
            unexmin::sim::MeshCollisionShape shape(world->mesh(i));
      });
      std::unique_ptr<unexmin::raycast::EmbreeRayCaster> copied;
      stage("(before) embree, triangles copied", [&] {
        copied = std::make_unique<unexmin::raycast::EmbreeRayCaster>(unexmin::raycast::seenMeshes(*world),
                                                                     unexmin::raycast::RobotSphereSource(), one_thread);
      });
      if (config.ray_caster == "embree" && !config.robots.empty())
        compareCasts(*caster, *copied, config.robots[0].pose.translation().cast<float>());
      copied.reset();
      stage("(before) mesh files read by assimp", [&] {
        for (const unexmin::sim::MeshEntry& e : config.meshes)
          if (e.collision || e.seen_by_cameras || e.seen_by_sonars)
            unexmin::sim::loadMeshWithAssimp(e);
      });
    }
    std::printf("%zu triangles read (%s); %s caster; load average %s\n", triangles, argv[1], caster->name(),
                [] {
                  std::ifstream in("/proc/loadavg");
                  std::string a;
                  in >> a;
                  return a;
                }()
                    .c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "world_load: %s\n", e.what());
    return 1;
  }
  return 0;
}

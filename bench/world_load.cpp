// Where a world's load goes, stage by stage, with no ROS: the mesh files read (loadMesh), the world built (the meshes
// read again and Bullet's BVH of every collision mesh), the ray caster built (Embree's scene); for each stage its wall
// time, its CPU time (every thread of the process; the figure to compare on a loaded machine) and the peak resident
// memory of the process during it (a mesh's Bullet BVH comes from its cache file when there is one: run twice).
// --compare then adds the ways these stages went before, on top of the memory above: the BVH built, the triangles
// copied into Embree's own buffers, every file read by assimp. Not a test: results go to docs/benchmarks.md.
//   world_load <world file> [--compare]
#include <unexmin/raycast/embree_ray_caster.h>
#include <unexmin/sim/collision_shape.h>
#include <unexmin/sim/mesh.h>
#include <unexmin/sim/world.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <map>
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
    stage("ray caster", [&] { caster = unexmin::raycast::makeRayCaster(config.ray_caster, *world); });
    if (compare) {  // after the stages above, whose memory they add to
      stage("(before) Bullet BVH, no cache", [&] {
        for (std::size_t i = 0; i < world->meshCount(); ++i)
          if (world->meshBody(i))
            unexmin::sim::MeshCollisionShape shape(world->mesh(i));
      });
      stage("(before) embree, triangles copied", [&] {
        unexmin::raycast::EmbreeRayCaster copied(unexmin::raycast::seenMeshes(*world),
                                                 unexmin::raycast::RobotSphereSource());
      });
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

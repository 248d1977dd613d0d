// Cost of the navigation sensor models in the ROS-free core: World::step() of the UX-1 in the tank
// with and without SensorSuite::update() after it (every sensor of the UX-1's description: IMU every step,
// DVL 4 rays at 8 Hz, pressure, MSIS, M3, the 4 SLS units; rays through the world's caster as the simulator builds it).
// Built by catkin (target sensors_core_cost, not a test) and run by bench/sensors_rtf.py --core:
//   sensors_core_cost <expanded UX-1 URDF> <tank.world> [steps] [robots] [threads]
// robots (1-3, default 1): the world's first spawns, each with that description and its own sensor suite.
// threads: the caster's threads, the caller included (default 0: every hardware thread; 1: every ray cast on the
// calling thread, as bench/m3_callgrind.sh needs to count a sensor's casts with it).
// Besides wall time per step it prints the process's CPU time per step (every thread: the caster's workers too),
// which moves less than wall time on a machine other jobs load.
#include <unexmin/raycast/ray_caster.h>
#include <unexmin/raycast/ray_caster_factory.h>
#include <unexmin/ros_layer/sensor_registry.h>
#include <unexmin/sensors/sensor_suite.h>

#include <btBulletDynamicsCommon.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

/// CPU time of this process, every thread [s].
static double cpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

int main(int argc, char** argv) {
  using namespace unexmin;
  if (argc < 3) {
    std::fprintf(stderr, "usage: sensors_core_cost <urdf> <world> [steps] [robots] [threads]\n");
    return 2;
  }
  std::ifstream in(argv[1]);
  std::stringstream urdf;
  urdf << in.rdbuf();
  const sim::WorldConfig config = sim::loadWorldConfig(argv[2]);
  const long steps = argc > 3 ? std::atol(argv[3]) : 200000;
  const int robots = argc > 4 ? std::atoi(argv[4]) : 1;
  raycast::RayCasterOptions options;
  options.threads = argc > 5 ? std::atoi(argv[5]) : 0;
  if (robots < 1 || robots > static_cast<int>(config.robots.size())) {
    std::fprintf(stderr, "robots = %d: expected 1 .. %zu (the spawns of %s)\n", robots, config.robots.size(), argv[2]);
    return 2;
  }
  std::map<std::string, sim::RobotDescription> d;
  for (int r = 0; r < robots; ++r)
    d.emplace(config.robots[r].name, sim::parseRobotDescription(urdf.str(), argv[1]));
  // The simulator's own families (only their models are used: nothing here touches ROS).
  const ros_layer::SensorRegistry registry = ros_layer::SensorRegistry::builtin();
  const sensors::SensorFactory& models = registry.models();
  for (int with = 0; with < 2; ++with) {
    sim::World world(config, d, robots, 0.002, 0);
    const auto caster = raycast::makeRayCaster(config.ray_caster, world, options);
    std::vector<std::unique_ptr<sensors::SensorSuite>> suites;
    for (int r = 0; r < robots; ++r)
      suites.push_back(std::make_unique<sensors::SensorSuite>(world, world.robot(r), caster.get(), models));
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = cpuSeconds();
    for (long i = 0; i < steps; ++i) {
      world.step();
      if (with) {
        caster->update();
        for (auto& suite : suites)
          suite->update();
      }
    }
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double c = cpuSeconds() - c0;
    std::printf("%-22s %6.2f us/step  (RTF %6.0f)  CPU %6.2f us/step (RTF per core-second %6.0f)\n",
                with ? "physics + sensors" : "physics only", 1e6 * s / steps, steps * world.dt() / s, 1e6 * c / steps,
                steps * world.dt() / c);
  }
  return 0;
}

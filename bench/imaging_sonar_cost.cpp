// What the imaging sonar costs of a core (docs/benchmarks.md "Imaging sonar"): World::step() of a robot carrying it
// in a world, with and without the sonar's update after each step (its pings at its rate of sim time: rays through
// the world's caster, the echoes, the receiver), and the Cartesian fan image of each ping (FanImage::render, what
// the publisher adds when someone subscribes to the fan). CPU time of the process (every thread) per second of sim
// time is the share of a core. Built by catkin (target imaging_sonar_cost, not a test):
//   imaging_sonar_cost <expanded URDF with an imaging_sonar> <world> [seconds of sim time, 10] [caster threads, 1]
// e.g. with test/rostest/sonar_images.urdf.xacro expanded for name:=UX_1 and worlds/mine.world.
#include <unexmin/raycast/ray_caster.h>
#include <unexmin/raycast/ray_caster_factory.h>
#include <unexmin/ros_layer/sensor_registry.h>
#include <unexmin/sensors/sensor_selection.h>
#include <unexmin/sensors/sensor_suite.h>
#include <unexmin/sensors/sonar/fan_image.h>
#include <unexmin/sensors/sonar/imaging_sonar_sensor.h>

#include <cstdio>
#include <ctime>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

namespace {

/// CPU time of this process, every thread [s].
double cpuTime() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

/// The whole text of the file at `path`.
std::string readText(const char* path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

int main(int argc, char** argv) {
  using namespace unexmin;
  if (argc < 3)
    return std::fprintf(stderr, "usage: imaging_sonar_cost <urdf> <world> [seconds] [threads]\n"), 2;
  const std::string urdf = readText(argv[1]);
  const sim::WorldConfig config = sim::loadWorldConfig(argv[2]);
  const double seconds = argc > 3 ? std::atof(argv[3]) : 10.0;
  raycast::RayCasterOptions options;
  options.threads = argc > 4 ? std::atoi(argv[4]) : 1;
  std::map<std::string, sim::RobotDescription> d;
  d.emplace(config.robots.at(0).name, sim::parseRobotDescription(urdf, argv[1]));
  const ros_layer::SensorRegistry registry = ros_layer::SensorRegistry::builtin();
  const auto only = sensors::SensorSelection::parse("imaging_sonar", registry.types(), "imaging_sonar_cost");
  double cost[2] = {0.0, 0.0};
  for (int with = 0; with < 2; ++with) {
    sim::World world(config, d, 1, 0.002, 0);
    const auto caster = raycast::makeRayCaster(config.ray_caster, world, options);
    sensors::SensorSuite suite(world, world.robot(0), caster.get(), registry.models(), only);
    if (suite.size() != 1) {
      std::fprintf(stderr, "%s: expected one imaging_sonar sensor, found %zu\n", argv[1], suite.size());
      return 2;
    }
    auto& sonar = dynamic_cast<sensors::sonar::ImagingSonarSensor&>(suite.sensor(0));
    const sensors::sonar::FanImage fan(sonar.beams(), sonar.fovH(), sonar.bins(), sonar.rangeMin(), sonar.rangeMax(),
                                       sonar.fanHeight());
    std::vector<std::uint8_t> image;
    const long steps = static_cast<long>(seconds / world.dt() + 0.5);
    const double c0 = cpuTime();
    double render = 0.0;
    for (long i = 0; i < steps; ++i) {
      world.step();
      if (!with)
        continue;
      caster->update();
      suite.update();
      if (suite.fresh(0)) {
        const double r0 = cpuTime();
        fan.render(sonar.last().codes, image);
        render += cpuTime() - r0;
      }
    }
    cost[with] = (cpuTime() - c0) / seconds;
    if (with) {
      std::printf("imaging sonar: %zu beams x %zu rays, %zu bins, %g Hz: %llu pings in %g s of sim time\n",
                  sonar.beams(), sonar.raysPerPing() / sonar.beams(), sonar.bins(), sonar.rate(),
                  static_cast<unsigned long long>(sonar.sampleCount()), seconds);
      std::printf("physics only             %6.3f core\n", cost[0]);
      std::printf("physics + imaging sonar  %6.3f core\n", cost[1]);
      std::printf("imaging sonar            %6.3f core (%.2f ms per ping, of which the fan image %.2f ms)\n",
                  cost[1] - cost[0], 1e3 * (cost[1] - cost[0]) * seconds / sonar.sampleCount(),
                  1e3 * render / sonar.sampleCount());
    }
  }
  return 0;
}

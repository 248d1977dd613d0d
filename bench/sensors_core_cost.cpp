// Cost of the navigation sensor models in the ROS-free core: World::step() of the UX-1 in the tank
// with and without SensorSuite::update() after it (every sensor of the UX-1's description: IMU every step,
// DVL 4 rays at 8 Hz, pressure, MSIS, M3, the 4 SLS units; rays through the world's caster as the simulator builds it). Built
// by catkin (target sensors_core_cost, not a test) and run by bench/sensors_rtf.py --core:
//   sensors_core_cost <expanded UX-1 URDF> <tank.world> [steps]
#include <unexmin/raycast/ray_caster.h>
#include <unexmin/ros/sensor_registry.h>
#include <unexmin/sensors/sensor_suite.h>

#include <btBulletDynamicsCommon.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

int main(int argc, char** argv)
{
  using namespace unexmin;
  if (argc < 3) {
    std::fprintf(stderr, "usage: sensors_core_cost <urdf> <world> [steps]\n");
    return 2;
  }
  std::ifstream in(argv[1]);
  std::stringstream urdf;
  urdf << in.rdbuf();
  const sim::WorldConfig config = sim::loadWorldConfig(argv[2]);
  const std::map<std::string, sim::RobotDescription> d{{"UX_1", sim::parseRobotDescription(urdf.str(), argv[1])}};
  const long steps = argc > 3 ? std::atol(argv[3]) : 200000;
  // The simulator's own families (only their models are used: nothing here touches ROS).
  const ros_layer::SensorRegistry registry = ros_layer::SensorRegistry::builtin();
  const sensors::SensorFactory& models = registry.models();
  for (int with = 0; with < 2; ++with) {
    sim::World world(config, d, 1, 0.002, 0);
    const auto caster = raycast::makeRayCaster(config.ray_caster, world);
    sensors::SensorSuite suite(world, world.robot(0), caster.get(), models);
    const auto t0 = std::chrono::steady_clock::now();
    for (long i = 0; i < steps; ++i) {
      world.step();
      if (with) {
        caster->update();
        suite.update();
      }
    }
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%-22s %6.2f us/step  (RTF %6.0f)\n", with ? "physics + sensors" : "physics only", 1e6 * s / steps,
                steps * world.dt() / s);
  }
  return 0;
}

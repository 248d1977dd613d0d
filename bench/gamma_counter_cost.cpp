// The cost of one sample of the gamma counter (cpp/unexmin/sensors/science/gamma_counter_sensor.h) in the shipped
// mine (worlds/mine.world, meshes from scripts/setup.sh), the world given a granite host rock (3.5 % K, 4 ppm U, 17 ppm
// Th) and 12 barren ore pockets around the robot (the mine ships no geology): CPU time of Sensor::update() alone per
// sample, the caster on the calling thread (one core), at the UX_1 spawn (>= 1.5 m of water to the walls) and with the
// hull 5 cm from the shaft wall. The sensor is the UX-1's <sensor type="gamma_counter"> with its rate raised to the
// physics rate so that every update samples. Not a test; at the UX-1's 1 Hz, CPU per sample / 1 s is its share of a
// core.
//   gamma_counter_cost <expanded UX-1 URDF> <mine.world> [samples (default 2000)]
#include <unexmin/geo/geology.h>
#include <unexmin/raycast/ray_caster.h>
#include <unexmin/raycast/ray_caster_factory.h>
#include <unexmin/sensors/science/gamma_counter_sensor.h>
#include <unexmin/sim/world_config.h>
#include <unexmin/sim/world_geology.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

/// CPU time of this process [s].
double cpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace unexmin;
  if (argc < 3) {
    std::fprintf(stderr, "usage: gamma_counter_cost <urdf> <world> [samples]\n");
    return 2;
  }
  std::ifstream in(argv[1]);
  std::stringstream urdf;
  urdf << in.rdbuf();
  sim::WorldConfig config = sim::loadWorldConfig(argv[2]);
  const long samples = argc > 3 ? std::atol(argv[3]) : 2000;
  const Eigen::Vector3d spawn = config.robots.at(0).pose.translation();

  const geo::MineralTable table = geo::MineralTable::load(sim::mineralTableFile());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  std::vector<geo::Body> bodies;
  for (int i = 0; i < 12; ++i) {
    geo::Body b;
    b.name = "b" + std::to_string(i);
    b.kind = static_cast<geo::BodyKind>(i % 2);  // ellipsoids and boxes: ore pockets
    b.pose = Eigen::Translation3d(spawn + Eigen::Vector3d(u(rng), u(rng), u(rng))) *
             Eigen::AngleAxisd(u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized());
    b.size = Eigen::Vector3d(4, 3, 2);
    b.rock = geo::mixRock(table, {{"chalcopyrite", 0.3}, {"pyrite", 0.2}, {"quartz", 0.5}}, "bench");
    bodies.push_back(b);
  }
  config.geology = std::make_shared<const geo::Geology>(geo::mixRock(table, {{"granite", 1.0}}, "bench"), bodies);

  std::map<std::string, sim::RobotDescription> d;
  d.emplace(config.robots[0].name, sim::parseRobotDescription(urdf.str(), argv[1]));
  const sim::RobotDescription& description = d.at(config.robots[0].name);
  sim::World world(config, d, 1, 0.002, 0);
  raycast::RayCasterOptions options;
  options.threads = 1;
  const auto caster = raycast::makeRayCaster(config.ray_caster, world, options);
  caster->update();

  sim::SensorSpec spec;
  bool found = false;
  for (const sim::SensorSpec& s : description.sensors)
    if (s.type == "gamma_counter") {
      spec = s;
      found = true;
    }
  if (!found) {
    std::fprintf(stderr, "%s has no <sensor type=\"gamma_counter\">\n", argv[1]);
    return 2;
  }
  spec.rate = 1.0 / world.dt();  // every update samples
  spec.params["integration_time"] = {world.dt()};
  const sensors::SensorSetup setup{config.robots[0].name, description, world.dt()};
  sensors::science::GammaCounterSensor gamma(spec, setup);
  gamma.reset(1);

  // The shaft wall behind the spawn (-x): the hull placed 5 cm from it.
  std::vector<raycast::Ray> probe(1);
  probe[0].origin = spawn.cast<float>();
  probe[0].direction = Eigen::Vector3f(-1, 0, 0);
  probe[0].max_range = 20.0f;
  std::vector<raycast::Hit> hit;
  caster->cast(probe, hit, 0);
  const double wall = hit[0].range;

  const struct {
    const char* name;
    Eigen::Isometry3d pose;
  } places[] = {
      {"spawn", config.robots[0].pose},
      {"hull 5 cm from the wall", Eigen::Isometry3d(Eigen::Translation3d(spawn - Eigen::Vector3d(wall - 0.35, 0, 0)) *
                                                    Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()))}};
  std::printf("gamma counter, %s: wall %.2f m behind the spawn; CPU per sample (one core)\n", argv[2], wall);
  for (const auto& place : places) {
    world.robot(0).setPose(place.pose);
    double cpu = 0.0, flux = 0.0;
    for (long i = 0; i < samples; ++i) {
      world.step();
      world.robot(0).setPose(place.pose);  // held in place
      caster->update();
      const sensors::SensorContext ctx{world, world.robot(0), world.robot(0).state(), caster.get(), 0};
      const double c0 = cpuSeconds();
      gamma.update(ctx);
      cpu += cpuSeconds() - c0;
      flux += gamma.last().flux[sensors::science::kPotassium];
    }
    const sensors::science::GammaSample& g = gamma.last();
    std::printf(
        "  %-24s %7.1f us/sample (%.4f %% of a core at 1 Hz); K-line flux %.3g /(cm^2 s); true rates K %.2f, U "
        "%.2f, Th %.2f, total %.1f cps\n",
        place.name, 1e6 * cpu / samples, 1e2 * cpu / samples, flux / samples, g.true_rate[0], g.true_rate[1],
        g.true_rate[2], g.true_rate_total);
  }
  return 0;
}

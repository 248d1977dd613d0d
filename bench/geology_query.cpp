// The cost of the geology and water-column queries (geo/geology.h, water/water_column.h): nanoseconds per query at
// random points of a 100 m cube, for a geology of a host and `bodies` bodies (the four kinds in turn, half of them
// bounded), and for the water column's at() and densityAt(), in CPU time. Not a test: results go to docs/benchmarks.md.
//   geology_query [bodies (default 12)] [queries (default 2000000)]
#include <unexmin/geo/geology.h>
#include <unexmin/sim/world_geology.h>
#include <unexmin/water/water_column.h>

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>
#include <vector>

namespace geo = unexmin::geo;
namespace water = unexmin::water;

namespace {

/// CPU time of this (single-threaded) process [s]: on a shared machine the figure that does not depend on the load.
double now() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

int main(int argc, char** argv) {
  const int bodies = argc > 1 ? std::atoi(argv[1]) : 12;
  const long queries = argc > 2 ? std::atol(argv[2]) : 2000000;
  const geo::MineralTable table = geo::MineralTable::load(unexmin::sim::mineralTableFile());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-50.0, 50.0), angle(-3.0, 3.0);
  std::vector<geo::Body> list;
  for (int i = 0; i < bodies; ++i) {
    geo::Body b;
    b.name = "b" + std::to_string(i);
    b.kind = static_cast<geo::BodyKind>(i % 4);
    b.pose = Eigen::Translation3d(u(rng), u(rng), u(rng)) *
             Eigen::AngleAxisd(angle(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized());
    b.size = b.kind == geo::BodyKind::vein      ? Eigen::Vector3d(15, 15, 0.5)
             : b.kind == geo::BodyKind::stratum ? Eigen::Vector3d(INFINITY, INFINITY, 3)
                                                : Eigen::Vector3d(4, 3, 2);
    b.rock = geo::mixRock(table, {{"chalcopyrite", 0.3}, {"pyrite", 0.2}, {"quartz", 0.5}}, "bench");
    list.push_back(b);
  }
  const geo::Geology g(geo::mixRock(table, {{"granite", 1.0}}, "bench"), list);
  std::vector<Eigen::Vector3d> points(4096);
  for (auto& p : points)
    p = Eigen::Vector3d(u(rng), u(rng), u(rng));

  double sink = 0.0;
  double t0 = now();
  for (long i = 0; i < queries; ++i)
    sink += g.bodyAt(points[static_cast<std::size_t>(i) & 4095]);
  const double body_ns = (now() - t0) / queries * 1e9;
  t0 = now();
  for (long i = 0; i < queries; ++i) {
    const geo::Rock& r = g.rockAt(points[static_cast<std::size_t>(i) & 4095]);
    sink += r.albedo.x() + r.reflectanceAt(550.0 + (i & 255)) + r.potassium;
  }
  const double rock_ns = (now() - t0) / queries * 1e9;

  water::Profile p;
  for (double d : {0.0, 20.0, 20.0, 60.0, 120.0}) {
    water::WaterRow r;
    r.depth = d;
    r.temperature = d < 20.0 ? 12.0 : 16.0;
    r.conductivity = d < 20.0 ? 500.0 : 9000.0;
    p.rows.push_back(r);
  }
  p.conductivity = true;
  p.boundary = {true, 20.0, 0.5, 3600.0, 0.0};
  water::checkProfile(p, "bench");
  const water::WaterColumn c(p, {}, 0.0, 9.81);
  const long wq = queries / 10;
  t0 = now();
  for (long i = 0; i < wq; ++i)
    sink += c.at(points[static_cast<std::size_t>(i) & 4095], 0.01 * i).sound_speed;
  const double at_ns = (now() - t0) / wq * 1e9;
  t0 = now();
  for (long i = 0; i < wq; ++i)
    sink += c.densityAt(points[static_cast<std::size_t>(i) & 4095], 0.01 * i);
  const double density_ns = (now() - t0) / wq * 1e9;

  std::printf("geology of %d bodies: bodyAt %.1f ns, bodyAt + rock's albedo, reflectance and K %.1f ns per query\n",
              bodies, body_ns, rock_ns);
  std::printf("water column (conductivity rows, heaving boundary): at() %.0f ns, densityAt() %.0f ns per query\n",
              at_ns, density_ns);
  std::printf("(checksum %g)\n", sink);
  return 0;
}

// Frames per second of one camera model (cpp/unexmin/sensors/vision/camera_sensor.h) in visual mode: the UX-1 at
// its spawn pose in a world (the flooded mine by default), lights and water of the world's visibility (or
// --visibility), its SLS laser line if the description has one, noise on; the ROS-free core only (no message
// is built). Also times the same camera's primary rays alone (the ray-casting share of a frame) and, with
// --shadows, the frame with shadow rays. "cpu" is the process's CPU time per frame over all threads: on a busy
// machine it stays near what an idle one needs, while wall time (mean, best, fps) grows with the load. Built by catkin
// (target camera_fps, not a test); docs/benchmarks.md:
//   xacro urdf/ux1.urdf.xacro name:=UX_1 > /tmp/ux1.urdf
//   camera_fps /tmp/ux1.urdf worlds/mine.world [--camera camera_4] [--frames 20] [--size 640x480]
//              [--visibility none|low|medium|high] [--shadows] [--ppm out.ppm] [--pose x y z yaw] [--threads N]
//              [--set name=value]...
// --set: a camera parameter as the description's <param> would give it (e.g. --set forward_scatter=false).
// --threads: the caster's threads (default 0 = every hardware thread); --threads 1 under
// `valgrind --tool=callgrind` counts a frame's instructions, whatever else the machine is doing.
// --size may be given more than once (default: 640x480 and 2054x1544).
#include <unexmin/raycast/ray_caster.h>
#include <unexmin/raycast/ray_caster_factory.h>
#include <unexmin/sensors/vision/camera_sensor.h>

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace unexmin;
using Clock = std::chrono::steady_clock;

namespace {

double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

/// CPU time of the whole process so far (every thread, user + system) [s].
double cpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Result {
  double first = 0.0, mean = 0.0, best = 0.0, rays = 0.0, mean_value = 0.0, median_range = 0.0;
  double cpu = 0.0;       ///< CPU time per frame, all threads [s]
  double rays_cpu = 0.0;  ///< CPU time of the primary rays alone [s]
  int frames = 0;
};

/// Renders `frames` frames of `spec` (at `width` x `height`, one per physics step) and times them.
Result run(sim::World& world, raycast::RayCaster& caster, sim::SensorSpec spec, int width, int height, int frames,
           bool shadows, const std::string& ppm, const std::vector<std::pair<std::string, std::string>>& set) {
  for (const auto& kv : set) {
    spec.params.erase(kv.first);
    spec.text[kv.first] = kv.second;
  }
  spec.params["width"] = {static_cast<double>(width)};
  spec.params["height"] = {static_cast<double>(height)};
  spec.params["render_scale"] = {1.0};
  spec.text["shadows"] = shadows ? "true" : "false";
  spec.params.erase("shadows");
  spec.rate = 1.0 / world.dt();  // a frame at every physics step
  const sim::Robot& robot = world.robot(0);
  const sensors::SensorSetup setup{robot.name(), robot.description(), world.dt(), true};
  sensors::vision::CameraSensor camera(spec, setup);
  camera.reset(1);

  Result r;
  std::vector<double> times;
  for (int k = 0; k <= frames; ++k) {
    world.step();
    caster.update();
    const sim::RobotState state = robot.state();
    const sensors::SensorContext ctx{world, robot, state, &caster, 0};
    const double c0 = cpuSeconds();
    const auto a = Clock::now();
    camera.update(ctx);
    const auto b = Clock::now();
    if (k == 0)
      r.first = seconds(a, b);  // builds the ray directions and the backscatter table
    else {
      times.push_back(seconds(a, b));
      r.cpu += (cpuSeconds() - c0) / frames;
    }
  }
  r.frames = frames;
  for (double t : times)
    r.mean += t / frames;
  r.best = *std::min_element(times.begin(), times.end());
  double sum = 0.0;
  for (std::uint8_t v : camera.last().rgb)
    sum += v;
  r.mean_value = sum / camera.last().rgb.size();
  std::vector<float> ranges = camera.last().range;
  std::nth_element(ranges.begin(), ranges.begin() + ranges.size() / 2, ranges.end());
  r.median_range = ranges[ranges.size() / 2];

  // The same frame's primary rays alone, through the same caster.
  const sensors::vision::CameraModel& m = camera.model();
  const Eigen::Isometry3d cam = robot.state().pose * spec.pose;
  std::vector<raycast::Ray> rays(static_cast<std::size_t>(m.width()) * m.height());
  for (int v = 0; v < m.height(); ++v)
    for (int u = 0; u < m.width(); ++u) {
      raycast::Ray& ray = rays[static_cast<std::size_t>(v) * m.width() + u];
      ray.origin = cam.translation().cast<float>();
      ray.direction = (cam.linear() * m.ray(u, v)).cast<float>();
      ray.max_range = static_cast<float>(camera.clipFar());
    }
  std::vector<raycast::Hit> hits;
  double best = 1e9;
  const double c0 = cpuSeconds();
  for (int k = 0; k < 3; ++k) {
    const auto a = Clock::now();
    caster.cast(rays, hits, 0);
    best = std::min(best, seconds(a, Clock::now()));
  }
  r.rays_cpu = (cpuSeconds() - c0) / 3;
  r.rays = best;

  if (!ppm.empty()) {
    std::ofstream out(ppm, std::ios::binary);
    out << "P6\n" << m.width() << " " << m.height() << "\n255\n";
    out.write(reinterpret_cast<const char*>(camera.last().rgb.data()),
              static_cast<std::streamsize>(camera.last().rgb.size()));
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(
        stderr,
        "usage: camera_fps <urdf> <world> [--camera NAME] [--frames N] [--size WxH]... "
        "[--visibility LEVEL] [--shadows] [--ppm FILE] [--pose X Y Z YAW] [--threads N] [--set NAME=VALUE]...\n");
    return 2;
  }
  std::string camera_name = "camera_0", visibility, ppm;
  std::vector<double> pose;  // x y z [m] yaw [rad] of the robot instead of its spawn pose
  int frames = 20, threads = 0;
  bool shadows = false;
  std::vector<std::pair<int, int>> sizes;
  std::vector<std::pair<std::string, std::string>> set;  // --set name=value
  for (int i = 3; i < argc; ++i) {
    const std::string a = argv[i];
    const bool more = i + 1 < argc;
    if (a == "--camera" && more)
      camera_name = argv[++i];
    else if (a == "--frames" && more)
      frames = std::max(1, std::atoi(argv[++i]));
    else if (a == "--visibility" && more)
      visibility = argv[++i];
    else if (a == "--ppm" && more)
      ppm = argv[++i];
    else if (a == "--shadows")
      shadows = true;
    else if (a == "--set" && more && std::strchr(argv[i + 1], '=')) {
      const std::string kv = argv[++i];
      set.emplace_back(kv.substr(0, kv.find('=')), kv.substr(kv.find('=') + 1));
    } else if (a == "--threads" && more)
      threads = std::max(0, std::atoi(argv[++i]));
    else if (a == "--pose" && i + 4 < argc)
      for (int k = 0; k < 4; ++k)
        pose.push_back(std::atof(argv[++i]));
    else if (a == "--size" && more) {
      int w = 0, h = 0;
      if (std::sscanf(argv[++i], "%dx%d", &w, &h) != 2 || w < 1 || h < 1) {
        std::fprintf(stderr, "camera_fps: --size %s: expected WxH\n", argv[i]);
        return 2;
      }
      sizes.emplace_back(w, h);
    } else {
      std::fprintf(stderr, "camera_fps: unknown argument '%s'\n", a.c_str());
      return 2;
    }
  }
  if (sizes.empty())
    sizes = {{640, 480}, {2054, 1544}};

  std::ifstream in(argv[1]);
  std::stringstream urdf;
  urdf << in.rdbuf();
  sim::WorldConfig config = sim::loadWorldConfig(argv[2]);
  if (!visibility.empty())
    config.visibility = visibility;
  if (!pose.empty())
    config.robots.at(0).pose =
        sim::poseFromXyzRpy(Eigen::Vector3d(pose[0], pose[1], pose[2]), Eigen::Vector3d(0, 0, pose[3]));
  const sim::RobotDescription description = sim::parseRobotDescription(urdf.str(), argv[1]);
  const std::map<std::string, sim::RobotDescription> d{{config.robots.at(0).name, description}};
  sim::World world(config, d, 1, 0.002, 1);
  raycast::RayCasterOptions options;
  options.threads = threads;
  auto caster = raycast::makeRayCaster(config.ray_caster, world, options);
  caster->update();
  const sim::SensorSpec* spec = nullptr;
  for (const auto& s : world.robot(0).description().sensors)
    if (s.name == camera_name)
      spec = &s;
  if (!spec || spec->type != "camera") {
    std::fprintf(stderr, "camera_fps: no camera '%s' in %s\n", camera_name.c_str(), argv[1]);
    return 2;
  }

  std::printf("world %s (visibility %s), %s of %s, %u hardware threads, caster %s with %d threads%s\n",
              config.name.c_str(), config.visibility.c_str(), camera_name.c_str(), config.robots.at(0).name.c_str(),
              std::thread::hardware_concurrency(), caster->name(), caster->threads(), shadows ? ", shadows on" : "");
  std::printf("%-11s %7s %10s %10s %7s %10s %10s %14s %11s\n", "size", "frames", "mean [ms]", "best [ms]", "fps",
              "cpu [ms]", "rays [ms]", "rays cpu [ms]", "first [ms]");
  for (const auto& s : sizes) {
    const Result r = run(world, *caster, *spec, s.first, s.second, frames, shadows, ppm, set);
    char size[32];
    std::snprintf(size, sizeof size, "%dx%d", s.first, s.second);
    std::printf(
        "%-11s %7d %10.1f %10.1f %7.2f %10.1f %10.1f %14.1f %11.1f   (mean pixel value %.1f, median range "
        "%.2f m)\n",
        size, r.frames, 1e3 * r.mean, 1e3 * r.best, 1.0 / r.mean, 1e3 * r.cpu, 1e3 * r.rays, 1e3 * r.rays_cpu,
        1e3 * r.first, r.mean_value, r.median_range);
  }
  {
    // Operational mode (last: the robot drifts with the current meanwhile): the same camera at full resolution,
    // no rendering: the cost of a sample.
    const sim::Robot& robot = world.robot(0);
    sim::SensorSpec op = *spec;
    op.rate = 1.0 / world.dt();
    const sensors::SensorSetup setup{robot.name(), robot.description(), world.dt(), false};
    sensors::vision::CameraSensor camera(op, setup);
    camera.reset(1);
    const int n = 20000;
    double spent = 0.0;
    for (int k = 0; k < n; ++k) {
      world.step();
      const sim::RobotState state = robot.state();
      const sensors::SensorContext ctx{world, robot, state, caster.get(), 0};
      const auto a = Clock::now();
      camera.update(ctx);
      spent += seconds(a, Clock::now());
    }
    std::printf("operational mode (no rendering): %.2f us per sample (%d samples)\n", 1e6 * spent / n, n);
  }
  return 0;
}

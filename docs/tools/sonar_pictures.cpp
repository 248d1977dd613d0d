// The sonar pictures of docs/sonars.md, in the thesis's layout (6.1.1-6.1.2): MSIS scans of the
// anchor in the shipped tank world from long, medium and close range (one full head turn each, the shipped
// UX-1's MSIS with all its noise models), and an M3 scan of it. ROS-free: the world, the UX-1's sensor suite and
// the world's ray caster as the simulator builds them; the robot is held at each place (teleported before every
// physics step). Built by catkin (target sonar_pictures, not a test); run by docs/tools/sonar_pictures.sh:
//   sonar_pictures <expanded UX-1 URDF> <tank.world> <output directory>
// Writes msis_long.png, msis_medium.png, msis_close.png (the sonar image: 2 range_max square, 1 px = 1 cm, head
// at the centre, x up, colour = intensity), m3_anchor.png (the fan of first returns over 40 pings) and
// m3_surface_shallow.png, m3_surface_deep.png (the robot pitched 5 deg up, the fan 0.4 and 2 m deep: surface
// multipath).
#include <unexmin/raycast/ray_caster.h>
#include <unexmin/raycast/ray_caster_factory.h>
#include <unexmin/ros_layer/sensor_registry.h>
#include <unexmin/sensors/sensor_suite.h>
#include <unexmin/sensors/sonar/m3_sensor.h>
#include <unexmin/sensors/sonar/msis_sensor.h>

#include <zlib.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using Image = std::vector<std::array<std::uint8_t, 3>>;

void chunk(std::ofstream& out, const char* type, const std::vector<std::uint8_t>& data) {
  const auto be32 = [&](std::uint32_t v) {
    const char b[4] = {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
                       static_cast<char>(v)};
    out.write(b, 4);
  };
  be32(static_cast<std::uint32_t>(data.size()));
  std::vector<std::uint8_t> crc_data(type, type + 4);
  crc_data.insert(crc_data.end(), data.begin(), data.end());
  out.write(reinterpret_cast<const char*>(crc_data.data()), static_cast<std::streamsize>(crc_data.size()));
  be32(static_cast<std::uint32_t>(crc32(0, crc_data.data(), static_cast<uInt>(crc_data.size()))));
}

/// An 8-bit RGB PNG (zlib).
void writePng(const std::string& path, int w, int h, const Image& px) {
  std::vector<std::uint8_t> raw;
  for (int y = 0; y < h; ++y) {
    raw.push_back(0);  // filter: none
    for (int x = 0; x < w; ++x)
      raw.insert(raw.end(), px[y * w + x].begin(), px[y * w + x].end());
  }
  uLongf n = compressBound(raw.size());
  std::vector<std::uint8_t> z(n);
  compress2(z.data(), &n, raw.data(), raw.size(), 9);
  z.resize(n);
  std::ofstream out(path, std::ios::binary);
  out.write("\x89PNG\r\n\x1a\n", 8);
  const std::vector<std::uint8_t> ihdr = {static_cast<std::uint8_t>(w >> 24),
                                          static_cast<std::uint8_t>(w >> 16),
                                          static_cast<std::uint8_t>(w >> 8),
                                          static_cast<std::uint8_t>(w),
                                          static_cast<std::uint8_t>(h >> 24),
                                          static_cast<std::uint8_t>(h >> 16),
                                          static_cast<std::uint8_t>(h >> 8),
                                          static_cast<std::uint8_t>(h),
                                          8,
                                          2,
                                          0,
                                          0,
                                          0};
  chunk(out, "IHDR", ihdr);
  chunk(out, "IDAT", z);
  chunk(out, "IEND", {});
}

/// Intensity 0..1 -> the sonar-display colours (black, blue, yellow, red), as the Seanet-style palette.
std::array<std::uint8_t, 3> palette(float v) {
  const float stops[4][3] = {{0, 0, 0}, {0, 60, 255}, {255, 255, 0}, {255, 0, 0}};
  const float t = std::min(1.0f, std::max(0.0f, v)) * 3.0f;
  const int i = std::min(2, static_cast<int>(t));
  const float f = t - i;
  std::array<std::uint8_t, 3> c;
  for (int k = 0; k < 3; ++k)
    c[k] = static_cast<std::uint8_t>(stops[i][k] + f * (stops[i + 1][k] - stops[i][k]));
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace unexmin;
  if (argc < 4) {
    std::fprintf(stderr, "usage: sonar_pictures <urdf> <world> <output directory>\n");
    return 2;
  }
  std::ifstream in(argv[1]);
  std::stringstream urdf;
  urdf << in.rdbuf();
  sim::WorldConfig config = sim::loadWorldConfig(argv[2]);
  config.robots.resize(1);
  const std::string out_dir = argv[3];
  const std::map<std::string, sim::RobotDescription> d{
      {config.robots[0].name, sim::parseRobotDescription(urdf.str(), argv[1])}};
  const ros_layer::SensorRegistry registry = ros_layer::SensorRegistry::builtin();

  // The anchor hangs at (0, 0) from 1.8 to 2.39 m depth; the robot 2.4 m deep (the head 2.07 m) facing it from -x at
  // these distances (centre to anchor axis) [m]: the thesis's long, medium and close scans (6.1.1).
  struct Place {
    const char* name;
    double distance;
  };
  for (const Place& place : {Place{"long", 2.6}, Place{"medium", 1.6}, Place{"close", 0.9}}) {
    sim::World world(config, d, 1, 0.002, 7);
    const auto caster = raycast::makeRayCaster(config.ray_caster, world);
    sensors::SensorSuite suite(world, world.robot(0), caster.get(), registry.models());
    auto* msis = dynamic_cast<sensors::sonar::MsisSensor*>(suite.find("msis"));
    if (!msis) {
      std::fprintf(stderr, "the robot has no MSIS named 'msis'\n");
      return 1;
    }
    const Eigen::Isometry3d pose =
        sim::poseFromXyzRpy(Eigen::Vector3d(-place.distance, 0.0, -2.4), Eigen::Vector3d::Zero());
    const int pings = static_cast<int>(std::lround(2.0 * M_PI / msis->step()));
    const double range = msis->echo().params().range_max;
    const int size = static_cast<int>(2.0 * range * 100.0);  // 1 cm per pixel
    std::vector<std::vector<float>> lines(pings);
    std::vector<double> angles(pings);
    int k = 0;
    while (k < pings) {
      world.robot(0).setPose(pose);
      world.step();
      caster->update();
      suite.update();
      if (msis->sampleTime() != world.time())
        continue;
      lines[k] = msis->last().intensity;
      angles[k] = msis->last().angle;
      ++k;
    }
    // Each pixel: the ping whose angle is nearest its bearing (in the head frame, x up), the bin of its range.
    Image px(static_cast<std::size_t>(size) * size, {0, 0, 0});
    const double head_yaw = 0.0;  // the robot faces +x
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const double fx = (size / 2.0 - y) / 100.0, fy = (size / 2.0 - x) / 100.0;  // x up, y left
        const double r = std::hypot(fx, fy);
        if (r >= range)
          continue;
        const double bearing = std::atan2(fy, fx) - head_yaw;
        int best = 0;
        double best_d = 1e9;
        for (int p = 0; p < pings; ++p) {
          const double dd = std::abs(std::remainder(angles[p] - bearing, 2.0 * M_PI));
          if (dd < best_d)
            best_d = dd, best = p;
        }
        const int b = msis->echo().bin(r);
        if (b >= 0)
          px[static_cast<std::size_t>(y) * size + x] = palette(lines[best][b]);
      }
    }
    const std::string path = out_dir + "/msis_" + place.name + ".png";
    writePng(path, size, size, px);
    std::printf("%s: %d pings from %.1f m\n", path.c_str(), pings, place.distance);
  }

  // M3 scans: 40 pings (1 s) of first returns accumulated, the robot held at `pose`.
  const auto m3Scan = [&](const Eigen::Isometry3d& pose, const std::string& file) {
    sim::World world(config, d, 1, 0.002, 7);
    const auto caster = raycast::makeRayCaster(config.ray_caster, world);
    sensors::SensorSuite suite(world, world.robot(0), caster.get(), registry.models());
    auto* m3 = dynamic_cast<sensors::sonar::M3Sensor*>(suite.find("m3"));
    if (!m3) {
      std::fprintf(stderr, "the robot has no M3 named 'm3'\n");
      return false;
    }
    const int size = 600;  // 1 px = 1 cm: 6 m square, sonar at the bottom centre, x up
    Image px(static_cast<std::size_t>(size) * size, {0, 0, 0});
    for (int ring = 1; ring <= 5; ++ring) {  // range rings every metre
      for (int a = 0; a < 2000; ++a) {
        const double t = -M_PI / 3 + a * (2 * M_PI / 3) / 2000.0;
        const int x = static_cast<int>(size / 2 - ring * 100 * std::sin(t)),
                  y = static_cast<int>(size - 1 - ring * 100 * std::cos(t));
        if (x >= 0 && x < size && y >= 0 && y < size)
          px[static_cast<std::size_t>(y) * size + x] = {60, 60, 60};
      }
    }
    int k = 0;
    while (k < 40) {
      world.robot(0).setPose(pose);
      world.step();
      caster->update();
      suite.update();
      if (m3->sampleTime() != world.time())
        continue;
      ++k;
      for (std::size_t b = 0; b < m3->beams(); ++b) {
        const float r = m3->last().ranges[b];
        if (!std::isfinite(r))
          continue;
        const double a = m3->beamAngle(b);
        const int x = static_cast<int>(size / 2 - r * 100 * std::sin(a)),
                  y = static_cast<int>(size - 1 - r * 100 * std::cos(a));
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            if (x + dx >= 0 && x + dx < size && y + dy >= 0 && y + dy < size)
              px[static_cast<std::size_t>(y + dy) * size + x + dx] = palette(0.25f + 0.75f * m3->last().intensities[b]);
      }
    }
    writePng(out_dir + "/" + file, size, size, px);
    const Eigen::Vector3d link = world.robot(0).state().pose * suite.find("m3")->spec().pose.translation();
    std::printf("%s/%s: 40 pings, the M3 %.2f m deep\n", out_dir.c_str(), file.c_str(), -link.z());
    return true;
  };
  // The robot 2.2 m deep (the fan 2.33 m), 2 m from the anchor, the fan as mounted.
  if (!m3Scan(sim::poseFromXyzRpy(Eigen::Vector3d(-2.0, 0.0, -2.2), Eigen::Vector3d::Zero()), "m3_anchor.png"))
    return 1;
  // Surface multipath: the robot pitched 5 deg up, 2 m from the anchor, with the fan about 0.4 m deep and 2 m deep.
  for (const auto& [depth, file] : {std::pair<double, const char*>{0.30, "m3_surface_shallow.png"},
                                    std::pair<double, const char*>{1.90, "m3_surface_deep.png"}}) {
    if (!m3Scan(sim::poseFromXyzRpy(Eigen::Vector3d(-2.0, 0.0, -depth), Eigen::Vector3d(0.0, -5.0 * M_PI / 180.0, 0.0)),
                file))
      return 1;
  }
  return 0;
}

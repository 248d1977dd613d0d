#include <unexmin/sensors/sonar/side_scan_sensor.h>

#include <unexmin/sensors/sensor_params.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <utility>

namespace unexmin {
namespace sensors {
namespace sonar {

SideScanSensor::SideScanSensor(const sim::SensorSpec& spec, const SensorSetup& setup) : Sensor(spec, setup) {
  constexpr double kDeg = M_PI / 180.0;
  SensorParams p(spec, setup.robot);
  const double fov_v = p.number("fov_v", 60.0 * kDeg, 1e-6, M_PI, "rad");
  const double width = p.number("beam_width", 0.5 * kDeg, 1e-6, M_PI / 2.0, "rad");
  tilt_ = p.number("tilt", 30.0 * kDeg, -M_PI / 2.0, M_PI / 2.0, "rad (below the horizontal)");
  const int rays = wholeNumber(p, "rays", 256.0, 1.0, 4096.0);
  std::vector<BeamFan> fans;
  for (const double side : {1.0, -1.0}) {  // port (+y), starboard (-y): across-track, tilt down
    const Eigen::Matrix3d axis = (Eigen::AngleAxisd(side * M_PI / 2.0, Eigen::Vector3d::UnitZ()) *
                                  Eigen::AngleAxisd(tilt_, Eigen::Vector3d::UnitY()))
                                     .toRotationMatrix();
    fans.emplace_back(axis, fov_v, width, rays);
  }
  BeamReceiver receiver =
      BeamReceiver::read(p, ReceiverDefaults{50.0, 1000.0, 215.0, 75.0}, rate(), fans.front().solidAngle());
  const int lines = wholeNumber(p, "waterfall_lines", 400.0, 1.0, 10000.0);
  p.finish();
  beams_ = BeamSet(std::move(fans), std::move(receiver));
  waterfall_ = Waterfall(static_cast<std::size_t>(lines), bins());
}

void SideScanSensor::onReset() {
  last_ = SideScanPing();
  waterfall_.clear();
}

void SideScanSensor::sample(const SensorContext& ctx) {
  last_.time = ctx.world.time();
  last_.built = false;
  const std::uint64_t seed = random().bits();  // one draw per ping, built or not
  if (demand_ && !demand_()) {
    waterfall_.addBlank();
    return;
  }
  const Eigen::Isometry3d pose = ctx.state.pose * spec().pose;
  // echoes timed at the water's sound speed, turned into ranges with the receiver's sound_speed
  const double scale = beams_.receiver().soundSpeed().rangeFactor(ctx.world, pose.translation());
  const auto& rays = beams_.aim(pose, ctx.world.water().surface_z, scale);
  castRays(ctx, rays, hits_, raycast::Incidence::skip);  // the incidence comes from the normals

  const CounterRandom ping(seed);  // side s draws from its stream s
  for (std::size_t s = 0; s < 2; ++s) {
    std::vector<std::uint8_t>& line = s == 0 ? last_.port : last_.starboard;
    line.resize(bins());
    beams_.listen(s, pose, hits_, ping.stream(s), line.data(), 1);
  }
  waterfall_.add(last_.port.data(), last_.starboard.data());
  last_.built = true;
}

void SideScanSensor::describeSample(SampleWriter& out) const {
  out.flag("built", last_.built);
  out.array("port", "-", last_.port);
  out.array("starboard", "-", last_.starboard);
  std::vector<std::uint8_t> image;
  waterfall_.image(image);
  out.array("waterfall", "-", image, {waterfall_.lines(), waterfall_.width()});
  std::vector<double> ranges(last_.port.size());
  for (std::size_t i = 0; i < ranges.size(); ++i)
    ranges[i] = binCenter(i);
  out.array("bin_ranges", "m", ranges);
}

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

#include <unexmin/sensors/sonar/imaging_sonar_sensor.h>

#include <unexmin/sensors/sensor_params.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <utility>

namespace unexmin {
namespace sensors {
namespace sonar {
namespace {

constexpr double kDeg = M_PI / 180.0;

}  // namespace

ImagingSonarSensor::ImagingSonarSensor(const sim::SensorSpec& spec, const SensorSetup& setup) : Sensor(spec, setup) {
  SensorParams p(spec, setup.robot);
  beam_count_ = wholeNumber(p, "beams", 512.0, 1.0, 4096.0);
  fov_h_ = p.number("fov_h", 130.0 * kDeg, 1e-6, M_PI, "rad");
  fov_v_ = p.number("fov_v", 20.0 * kDeg, 1e-6, M_PI, "rad");
  const int rays = wholeNumber(p, "rays_per_beam", 16.0, 1.0, 256.0);
  const double width = fov_h_ / beam_count_;
  std::vector<BeamFan> fans;
  for (int k = 0; k < beam_count_; ++k)
    fans.emplace_back(Eigen::AngleAxisd(azimuth(k), Eigen::Vector3d::UnitZ()).toRotationMatrix(), fov_v_, width, rays);
  BeamReceiver receiver =
      BeamReceiver::read(p, ReceiverDefaults{30.0, 500.0, 210.0, 85.0}, rate(), fans.front().solidAngle());
  fan_height_ = wholeNumber(p, "fan_height", 500.0, 16.0, 4096.0);
  p.finish();

  beams_ = BeamSet(std::move(fans), std::move(receiver));
}

double ImagingSonarSensor::azimuth(std::size_t k) const {
  return fov_h_ / 2.0 - (static_cast<double>(k) + 0.5) * fov_h_ / beam_count_;
}

void ImagingSonarSensor::onReset() {
  last_ = PolarImage();
}

void ImagingSonarSensor::sample(const SensorContext& ctx) {
  PolarImage& out = last_;
  out.time = ctx.world.time();
  out.built = false;
  const std::uint64_t seed = random().bits();  // one draw per ping, built or not
  if (demand_ && !demand_())
    return;
  const Eigen::Isometry3d pose = ctx.state.pose * spec().pose;
  // echoes timed at the water's sound speed, turned into ranges with the receiver's sound_speed
  const double scale = beams_.receiver().soundSpeed().rangeFactor(ctx.world, pose.translation());
  const auto& rays = beams_.aim(pose, ctx.world.water().surface_z, scale);
  castRays(ctx, rays, hits_, raycast::Incidence::skip);  // the incidence comes from the normals

  out.beams = beams();
  out.bins = bins();
  out.codes.resize(out.beams * out.bins);
  // Beam k draws from stream k of the ping: the beams' groups may run on the caster's threads in any order.
  beams_.listenAll(pose, hits_, CounterRandom(seed), out.codes.data(), ctx.rays);
  out.built = true;
}

void ImagingSonarSensor::describeSample(SampleWriter& out) const {
  out.flag("built", last_.built);
  out.array("polar", "-", last_.codes, {last_.bins, last_.beams});
  std::vector<double> azimuths(beams()), ranges(bins());
  for (std::size_t k = 0; k < azimuths.size(); ++k)
    azimuths[k] = azimuth(k);
  for (std::size_t i = 0; i < ranges.size(); ++i)
    ranges[i] = binCenter(i);
  out.array("beam_azimuths", "rad", azimuths);
  out.array("bin_ranges", "m", ranges);
}

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

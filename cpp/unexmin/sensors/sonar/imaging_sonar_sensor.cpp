#include <unexmin/sensors/sonar/imaging_sonar_sensor.h>

#include <unexmin/sensors/sensor_params.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace sensors {
namespace sonar {
namespace {

constexpr double kDeg = M_PI / 180.0;

}  // namespace

ImagingSonarSensor::ImagingSonarSensor(const sim::SensorSpec& spec, const SensorSetup& setup) : Sensor(spec, setup)
{
  SensorParams p(spec, setup.robot);
  beams_ = wholeNumber(p, "beams", 512.0, 1.0, 4096.0);
  fov_h_ = p.number("fov_h", 130.0 * kDeg, 1e-6, M_PI, "rad");
  fov_v_ = p.number("fov_v", 20.0 * kDeg, 1e-6, M_PI, "rad");
  const int rays = wholeNumber(p, "rays_per_beam", 16.0, 1.0, 256.0);
  const double width = fov_h_ / beams_;
  for (int k = 0; k < beams_; ++k)
    fans_.emplace_back(Eigen::AngleAxisd(azimuth(k), Eigen::Vector3d::UnitZ()).toRotationMatrix(), fov_v_, width, rays);
  receiver_ = BeamReceiver::read(p, ReceiverDefaults{30.0, 500.0, 210.0, 85.0}, rate(), fans_.front().solidAngle());
  fan_height_ = wholeNumber(p, "fan_height", 500.0, 16.0, 4096.0);
  p.finish();

  rays_.resize(static_cast<std::size_t>(beams_) * rays);
  energy_.resize(bins());
}

double ImagingSonarSensor::azimuth(std::size_t k) const
{
  return fov_h_ / 2.0 - (static_cast<double>(k) + 0.5) * fov_h_ / beams_;
}

void ImagingSonarSensor::onReset() { last_ = PolarImage(); }

void ImagingSonarSensor::sample(const SensorContext& ctx)
{
  const Eigen::Isometry3d pose = ctx.state.pose * spec().pose;
  const double surface_z = ctx.world.water().surface_z;
  const std::size_t n = fans_.front().size();
  for (std::size_t k = 0; k < fans_.size(); ++k) fans_[k].aim(pose, rangeMax(), surface_z, &rays_[k * n]);
  castRays(ctx, rays_, hits_, raycast::Incidence::skip);  // the incidence comes from the normals

  PolarImage& out = last_;
  out.time = ctx.world.time();
  out.beams = fans_.size();
  out.bins = bins();
  out.codes.resize(out.beams * out.bins);
  for (std::size_t k = 0; k < fans_.size(); ++k) {
    std::fill(energy_.begin(), energy_.end(), 0.0);
    fans_[k].listen(pose.linear(), &hits_[k * n], receiver_, energy_);
    receiver_.receive(energy_, random(), &out.codes[k], out.beams);
  }
}

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

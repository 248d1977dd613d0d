#include <unexmin/sensors/sensor.h>

#include <unexmin/core/error.h>

#include <cmath>
#include <sstream>

namespace unexmin {
namespace sensors {

Sensor::Sensor(const sim::SensorSpec& spec, const SensorSetup& setup) : spec_(spec), robot_(setup.robot) {
  const double physics_rate = 1.0 / setup.physics_dt;
  if (!(spec.rate > 0.0) || spec.rate > physics_rate * (1.0 + 1e-9)) {
    throw ConfigError(setup.robot + ": sensor '" + spec.name + "' (type " + spec.type +
                      "): rate = " + formatNumber(spec.rate) + " Hz: expected (0, " + formatNumber(physics_rate) +
                      "] Hz (at most the physics rate)");
  }
  tolerance_ = 1e-6 * setup.physics_dt;
}

void Sensor::reset(std::uint64_t world_seed) {
  random_.seed(Random::streamSeed(world_seed, robot_, spec_.name));
  next_ = 1;
  samples_ = 0;
  sample_time_ = -1.0;
  onReset();
}

bool Sensor::update(const SensorContext& ctx) {
  track(ctx);
  const double t = ctx.world.time();
  if (t + tolerance_ < static_cast<double>(next_) / spec_.rate)
    return false;
  sample(ctx);
  sample_time_ = t;
  ++samples_;
  // Next sample time after t (never two samples in one step; none is skipped when rate <= physics rate).
  next_ = static_cast<std::uint64_t>(std::floor((t + tolerance_) * spec_.rate)) + 1;
  return true;
}

void Sensor::describe(SampleWriter& out) const {
  out.scalar("time", "s", sample_time_);
  out.count("count", samples_);
  describeSample(out);
}

double apparentRangeFactor(const sim::World& world, const Eigen::Vector3d& point, double configured) {
  const auto& column = world.config().water_column;
  return column ? configured / column->soundSpeedAt(point, world.time()) : 1.0;
}

SoundSpeed SoundSpeed::read(SensorParams& p) {
  SoundSpeed s;
  if (p.text("sound_speed", "1500") == "probe") {
    s.probe = true;
    return s;
  }
  s.configured = p.number("sound_speed", 1500.0, 1300.0, 1700.0, "m/s (or probe)");
  return s;
}

void Sensor::setRendering(bool /*on*/) {
  throw ParameterError(robot_ + "/" + name() + " (family " + type() +
                       ") renders no images: expected a sensor that renders images (a camera)");
}

std::string Sensor::fire() {
  throw ParameterError(robot_ + "/" + name() + " (family " + type() +
                       ") has nothing to fire: expected a sensor that fires (a water_sampler)");
}

void Sensor::castRays(const SensorContext& ctx, const std::vector<raycast::Ray>& rays, std::vector<raycast::Hit>& hits,
                      raycast::Incidence incidence, raycast::SeenBy seen_by) {
  if (ctx.rays)
    ctx.rays->cast(rays, hits, ctx.robot_index, incidence, seen_by);
  else
    hits.assign(rays.size(), raycast::Hit());
}

}  // namespace sensors
}  // namespace unexmin

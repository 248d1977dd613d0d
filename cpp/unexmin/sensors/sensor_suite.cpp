#include <unexmin/sensors/sensor_suite.h>

namespace unexmin {
namespace sensors {

SensorSuite::SensorSuite(const sim::World& world, sim::Robot& robot, const raycast::RayCaster* rays,
                         const SensorFactory& factory, const SensorSelection& selection, bool visual)
    : world_(world), robot_(robot), rays_(rays) {
  for (std::size_t i = 0; i < world.robotCount(); ++i)
    if (&world.robot(i) == &robot)
      robot_index_ = static_cast<int>(i);
  if (robot_index_ < 0)
    throw ConfigError("sensors: robot '" + robot.name() + "' is not in world '" + world.config().name + "'");
  const SensorSetup setup{robot.name(), robot.description(), world.dt(), visual};
  for (const auto& spec : robot.description().sensors) {
    if (!factory.has(spec.type))
      factory.create(spec, setup);  // throws: unknown type
    if (!selection.selected(spec.type)) {
      skipped_.push_back(spec.name);
      continue;
    }
    sensors_.push_back(factory.create(spec, setup));
  }
  fresh_.assign(sensors_.size(), 0);
  reset(world.seed());
}

void SensorSuite::reset(std::uint64_t seed) {
  for (auto& s : sensors_)
    s->reset(seed);
  fresh_.assign(sensors_.size(), 0);
  applyCarriedMass();
}

void SensorSuite::update() {
  const sim::RobotState state = robot_.state();
  const SensorContext ctx{world_, robot_, state, rays_, robot_index_};
  for (std::size_t i = 0; i < sensors_.size(); ++i)
    fresh_[i] = sensors_[i]->update(ctx) ? 1 : 0;
  applyCarriedMass();
}

void SensorSuite::applyCarriedMass() {
  double mass = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (const auto& s : sensors_) {
    const double m = s->carriedMass();
    mass += m;
    moment += m * s->spec().pose.translation();
  }
  robot_.setPayloadMass(mass, mass > 0.0 ? Eigen::Vector3d(moment / mass) : Eigen::Vector3d::Zero());
}

Sensor* SensorSuite::find(const std::string& name) {
  for (auto& s : sensors_)
    if (s->name() == name)
      return s.get();
  return nullptr;
}

std::vector<MovedJoint> SensorSuite::movedJoints() const {
  std::vector<MovedJoint> out;
  for (const auto& s : sensors_)
    s->movedJoints(out);
  return out;
}

}  // namespace sensors
}  // namespace unexmin

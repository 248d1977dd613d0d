#include "sonar/sensor_rays.h"

#include "sim/world.h"

#include <map>
#include <utility>

namespace unexmin {
namespace sonar {
namespace {

/// update() and cast() of a shared caster must not overlap: one lock per caster.
std::mutex& casterMutex(const sonar::RayCaster* caster)
{
  static std::mutex table_mutex;
  static std::map<const sonar::RayCaster*, std::unique_ptr<std::mutex>> table;
  std::lock_guard<std::mutex> lock(table_mutex);
  auto& m = table[caster];
  if (!m) m = std::make_unique<std::mutex>();
  return *m;
}

}  // namespace

SensorRays::SensorRays(std::shared_ptr<sonar::RayCaster> caster, int exclude_robot)
    : caster_(std::move(caster)), exclude_(exclude_robot)
{
  if (!caster_) throw RayCasterError("sensor rays: no ray caster");
}

std::shared_ptr<SensorRays> SensorRays::forRobot(sim::World& world, const sim::Robot& robot, const std::string& backend)
{
  int index = -1;
  for (std::size_t i = 0; i < world.robotCount(); ++i)
    if (&world.robot(i) == &robot) index = static_cast<int>(i);
  if (index < 0) throw sim::ConfigError("sensor rays: robot '" + robot.name() + "' is not in world '" +
                                        world.config().name + "'");
  // One caster per (world, back end); a new world at a freed address finds the old entry expired.
  static std::mutex mutex;
  static std::map<std::pair<const sim::World*, std::string>, std::weak_ptr<sonar::RayCaster>> shared;
  std::lock_guard<std::mutex> lock(mutex);
  const std::string name = backend.empty() ? "embree" : backend;
  auto& slot = shared[{&world, name}];
  std::shared_ptr<sonar::RayCaster> caster = slot.lock();
  if (!caster) {
    caster = std::shared_ptr<sonar::RayCaster>(makeRayCaster(name, world));
    slot = caster;
  }
  return std::make_shared<SensorRays>(caster, index);
}

void SensorRays::cast(const std::vector<sensors::Ray>& rays, std::vector<sensors::RayHit>& hits) const
{
  std::lock_guard<std::mutex> own(mutex_);
  rays_.resize(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    rays_[i].origin = rays[i].origin.cast<float>();
    rays_[i].direction = rays[i].direction.cast<float>();
    rays_[i].max_range = static_cast<float>(rays[i].max_range);
  }
  {
    std::lock_guard<std::mutex> lock(casterMutex(caster_.get()));
    caster_->update();
    caster_->cast(rays_, hits_, exclude_);
  }
  hits.assign(rays.size(), sensors::RayHit());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Hit& h = hits_[i];
    if (!h.hit()) continue;
    hits[i].hit = true;
    hits[i].range = h.range;
    hits[i].normal = h.normal.cast<double>();
  }
}

}  // namespace sonar
}  // namespace unexmin

// The sensors' RayCaster interface (cpp/sensors/ray_caster.h, what SensorSuite hands to every ray-cast
// sensor: DVL, MSIS, M3) answered by the sonar ray caster (cpp/sonar/ray_caster.h: Embree by default,
// Bullet as fallback). One sonar caster is built per world and back end and shared by every robot's
// sensors (one BVH, one worker pool); each robot's adapter hides that robot's own hull. Knows no ROS.
#pragma once

#include "sensors/ray_caster.h"
#include "sonar/ray_caster.h"

#include <memory>
#include <mutex>
#include <string>

namespace unexmin {
namespace sim {
class Robot;
class World;
}  // namespace sim

namespace sonar {

class SensorRays : public sensors::RayCaster
{
public:
  /// Casts through `caster`, robot index `exclude_robot` (-1: none) invisible. The caster's robot spheres are
  /// refreshed (RayCaster::update) before every batch, so a batch sees the robots as they are now.
  SensorRays(std::shared_ptr<sonar::RayCaster> caster, int exclude_robot);

  /// The adapter for `robot`'s sensors in `world`, over the world's shared caster of back end `backend`
  /// ("embree" | "bullet"; built on first use, kept while an adapter holds it). Throws RayCasterError on an
  /// unknown back end, sim::ConfigError when `robot` is not in `world`. The world must outlive the adapter.
  static std::shared_ptr<SensorRays> forRobot(sim::World& world, const sim::Robot& robot,
                                              const std::string& backend = "embree");

  /// Ranges in double precision of the caster's single-precision ones; RayHit::normal faces the ray.
  void cast(const std::vector<sensors::Ray>& rays, std::vector<sensors::RayHit>& hits) const override;

  const sonar::RayCaster& caster() const { return *caster_; }
  int excludedRobot() const { return exclude_; }

private:
  std::shared_ptr<sonar::RayCaster> caster_;
  int exclude_;
  mutable std::vector<Ray> rays_;
  mutable std::vector<Hit> hits_;
  mutable std::mutex mutex_;  ///< the scratch buffers
};

}  // namespace sonar
}  // namespace unexmin

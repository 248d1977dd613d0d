// The world's ray caster by back-end name, the world file's `ray_caster:` (docs/ray_casting.md): Embree or Bullet,
// each behind the RayCaster interface (raycast/ray_caster.h). Knows no ROS.
#pragma once

#include <unexmin/raycast/ray_caster.h>

#include <memory>
#include <string>
#include <vector>

namespace unexmin {
namespace raycast {

/// Back ends makeRayCaster() accepts: {"embree", "bullet"}.
const std::vector<std::string>& rayCasterBackends();

/// Builds the back end named `backend` ("" = "embree") on `world`: its meshes, each seen by the sensors its world
/// file's `seen_by:` names (MeshEntry), and its robots' spheres. The world must outlive the caster. Throws
/// RayCasterError on an unknown name, listing the accepted ones.
std::unique_ptr<RayCaster> makeRayCaster(const std::string& backend, sim::World& world,
                                         const RayCasterOptions& options = RayCasterOptions());

}  // namespace raycast
}  // namespace unexmin

#include <unexmin/raycast/ray_caster_factory.h>

#include <unexmin/raycast/bullet_ray_caster.h>
#include <unexmin/raycast/embree_ray_caster.h>

namespace unexmin {
namespace raycast {

const std::vector<std::string>& rayCasterBackends() {
  static const std::vector<std::string> names = {"embree", "bullet"};
  return names;
}

std::unique_ptr<RayCaster> makeRayCaster(const std::string& backend, sim::World& world,
                                         const RayCasterOptions& options) {
  if (backend.empty() || backend == "embree")
    return std::make_unique<EmbreeRayCaster>(world, options);
  if (backend == "bullet")
    return std::make_unique<BulletRayCaster>(world, options);
  std::string accepted;
  for (const auto& name : rayCasterBackends())
    accepted += (accepted.empty() ? "" : ", ") + name;
  throw RayCasterError("ray caster: unknown back end '" + backend + "' (accepted: " + accepted + ")");
}

}  // namespace raycast
}  // namespace unexmin

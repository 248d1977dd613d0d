#include <unexmin/sensors/sonar/beam_set.h>

#include <algorithm>
#include <utility>

namespace unexmin {
namespace sensors {
namespace sonar {

BeamSet::BeamSet(std::vector<BeamFan> fans, BeamReceiver receiver)
    : fans_(std::move(fans)),
      receiver_(std::move(receiver)),
      rays_(fans_.size() * (fans_.empty() ? 0 : fans_.front().size())),
      energy_(static_cast<std::size_t>(receiver_.echo().params().nbins), 0.0) {}

const std::vector<raycast::Ray>& BeamSet::aim(const Eigen::Isometry3d& pose, double surface_z, double scale) {
  const std::size_t n = fans_.front().size();
  scale_ = scale;
  const double reach = receiver_.echo().params().range_max / std::min(1.0, scale);  // range_max itself at scale >= 1
  for (std::size_t k = 0; k < fans_.size(); ++k)
    fans_[k].aim(pose, reach, surface_z, &rays_[k * n]);
  return rays_;
}

void BeamSet::listen(std::size_t k, const Eigen::Isometry3d& pose, const std::vector<raycast::Hit>& hits,
                     const CounterRandom& random, std::uint8_t* codes, std::size_t stride) {
  listen(k, pose, hits, random, codes, stride, energy_);
}

void BeamSet::listen(std::size_t k, const Eigen::Isometry3d& pose, const std::vector<raycast::Hit>& hits,
                     const CounterRandom& random, std::uint8_t* codes, std::size_t stride,
                     std::vector<double>& energy) const {
  fans_[k].listen(pose.linear(), &hits[k * fans_[k].size()], receiver_, scale_, energy);
  receiver_.receive(energy, random, codes, stride);
}

void BeamSet::listenAll(const Eigen::Isometry3d& pose, const std::vector<raycast::Hit>& hits, const CounterRandom& ping,
                        std::uint8_t* codes, const raycast::RayCaster* caster) {
  const std::size_t beams = fans_.size(), groups = (beams + kGroup - 1) / kGroup;
  energies_.resize(groups, energy_);
  const auto group = [&](std::size_t g) {
    for (std::size_t k = g * kGroup; k < std::min(beams, (g + 1) * kGroup); ++k)
      listen(k, pose, hits, ping.stream(k), codes + k, beams, energies_[g]);
  };
  if (caster)
    caster->parallelFor(groups, group);
  else
    for (std::size_t g = 0; g < groups; ++g)
      group(g);
}

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

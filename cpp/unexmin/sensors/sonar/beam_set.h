// The beams of one sonar (docs/sonars.md "Beams, rays and footprints"): its fans (beam_fan.h, one per beam, all of
// the same size), its receiver (beam_receiver.h), and the rays and echo energies of a ping. The imaging sonar has one
// fan per beam, the side-scan one per side. Knows no ROS.
#pragma once

#include <unexmin/raycast/ray_caster.h>
#include <unexmin/sensors/counter_random.h>
#include <unexmin/sensors/sonar/beam_fan.h>
#include <unexmin/sensors/sonar/beam_receiver.h>

#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace unexmin {
namespace sensors {
namespace sonar {

class BeamSet {
public:
  BeamSet() = default;
  /// `fans`: at least one, all with the same number of rays.
  BeamSet(std::vector<BeamFan> fans, BeamReceiver receiver);

  std::size_t size() const { return fans_.size(); }
  const BeamFan& fan(std::size_t k) const { return fans_[k]; }
  const BeamReceiver& receiver() const { return receiver_; }
  std::size_t raysPerPing() const { return rays_.size(); }
  /// The rays of every beam of a sensor at `pose` (world frame; beam k's at [k n, (k + 1) n), n rays per fan), up to
  /// range_max / min(1, scale) (the farthest path heard within range_max) or the free surface at height surface_z
  /// [m] (BeamFan::aim). `scale` [-]: the ping's timed range per metre of path, the receiver's sound speed over the
  /// water's at the sonar (sensors::apparentRangeFactor; 1 without a water column), used by the listen()s after it.
  const std::vector<raycast::Ray>& aim(const Eigen::Isometry3d& pose, double surface_z, double scale);
  /// Beam k's line from `hits` (the answers to aim()'s rays, the sensor at `pose`): echoes binned at the ranges the
  /// sonar times (path x aim()'s scale), receiver noise from `random` (the beam's stream of this ping), codes[i *
  /// stride] = the code of bin i.
  void listen(std::size_t k, const Eigen::Isometry3d& pose, const std::vector<raycast::Hit>& hits,
              const CounterRandom& random, std::uint8_t* codes, std::size_t stride);

  /// Every beam's line as listen() gives it, into a polar image: bin i of beam k to codes[i * size() + k], beam k's
  /// noise from ping.stream(k). Groups of kGroup beams run on the threads of `caster` (null: this thread); the image
  /// does not depend on which thread builds which group.
  void listenAll(const Eigen::Isometry3d& pose, const std::vector<raycast::Hit>& hits, const CounterRandom& ping,
                 std::uint8_t* codes, const raycast::RayCaster* caster);

  static constexpr std::size_t kGroup = 64;  ///< beams per group of listenAll() (a cache line of the image's row)

private:
  /// Beam k's line with `energy` (nbins) as its scratch.
  void listen(std::size_t k, const Eigen::Isometry3d& pose, const std::vector<raycast::Hit>& hits,
              const CounterRandom& random, std::uint8_t* codes, std::size_t stride, std::vector<double>& energy) const;

  std::vector<BeamFan> fans_;
  BeamReceiver receiver_{EchoParams(), ReceiverNoise()};
  std::vector<raycast::Ray> rays_;
  double scale_ = 1.0;                         ///< aim()'s scale [-]
  std::vector<double> energy_;                 ///< listen()'s scratch
  std::vector<std::vector<double>> energies_;  ///< listenAll()'s scratch, one per group
};

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin

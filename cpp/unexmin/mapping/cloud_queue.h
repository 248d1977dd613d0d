// The clouds waiting for their tf, in arrival order, and the rules that decide each one's fate: a cloud goes into
// the map once the tf history can place its sensor frame in the map frame at its stamp; it is dropped when that
// time is older than the history kept, when its tf has not come after tf_timeout wall seconds, when its pose would
// be interpolated over a gap of more than tf_max_gap, or when tf jumped back in time after it was received (its
// tf is gone). Clouds and tf arrive in stamp order, so the clouds behind one that waits wait too. Knows no ROS.
#pragma once

#include <unexmin/mapping/tf_history.h>

#include <octomap/octomap_types.h>

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

namespace unexmin {
namespace mapping {

/// A cloud as received.
struct PendingCloud {
  std::string robot;
  std::string frame;                     ///< the sensor frame
  Stamp stamp = 0;                       ///< [ns]
  std::vector<octomap::point3d> points;  ///< [m, sensor frame]
  double received = 0.0;                 ///< [s, wall]
  double max_range = 0.0;                ///< [m] its source's range (OccupancyMap::insertCloud); <= 0: no limit
};

/// The fate of the front cloud.
struct CloudStep {
  enum class Kind {
    kWait,    ///< no cloud, or the front one waits for tf
    kInsert,  ///< cloud and sensor_in_map are set
    kDrop,    ///< cloud and why are set
  };
  Kind kind = Kind::kWait;
  PendingCloud cloud;
  RigidTransform sensor_in_map;  ///< the cloud's frame in the map frame at its stamp
  std::string why;
};

class CloudQueue {
public:
  /// map_frame: the frame clouds are placed in; tf_timeout [s, wall] > 0; tf_max_gap [s] > 0 (ParameterError
  /// otherwise).
  CloudQueue(std::string map_frame, double tf_timeout, double tf_max_gap);

  void push(PendingCloud&& cloud);
  /// First forgets the clouds received at or before tf's last jump back (once per jump), then takes the front
  /// cloud out of the queue with its fate, or leaves it there (kWait). now: wall time [s].
  CloudStep next(const TfHistory& tf, double now);

  std::size_t size() const { return pending_.size(); }
  /// Clouds pushed since construction.
  std::uint64_t received() const { return received_; }
  /// Clouds dropped since construction (by next(), or forgotten after a jump).
  std::uint64_t dropped() const { return dropped_; }

private:
  std::string map_frame_;
  double tf_timeout_, tf_max_gap_;
  std::deque<PendingCloud> pending_;
  std::uint64_t received_ = 0, dropped_ = 0, jumps_seen_ = 0;
};

}  // namespace mapping
}  // namespace unexmin

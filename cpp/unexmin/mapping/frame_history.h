// The samples of one frame's transform to its parent, as tf2's buffer keeps them: a static frame holds its last
// sample for all times; a dynamic frame holds its samples of the last cache_length seconds in stamp order and
// answers a time between two of them by interpolation (and says how far apart they are). Stamps are integer
// nanoseconds, compared exactly. Knows no ROS.
#pragma once

#include <unexmin/mapping/rigid_transform.h>

#include <cstdint>
#include <deque>
#include <string>

namespace unexmin {
namespace mapping {

/// A stamp [ns] (ros::Time::toNSec()).
using Stamp = std::int64_t;

/// [s] of a stamp difference [ns], rounded as ros::Duration::toSec() does (whole seconds + 1e-9 * rest).
double toSeconds(Stamp ns);

/// One transform sample: child frame in parent frame at stamp.
struct FrameSample {
  Stamp stamp = 0;     ///< [ns]
  std::string parent;  ///< the parent frame
  RigidTransform transform;
};

/// What a frame answers for a time.
struct FrameAnswer {
  enum class Status {
    kOk,
    kTooOld,  ///< before the oldest sample kept: that time will never be answered
    kTooNew,  ///< after the newest sample: a later sample may answer it
    kEmpty,   ///< no sample (never received, or cleared)
  };
  Status status = Status::kEmpty;
  std::string parent;        ///< kOk: the parent frame at that time
  RigidTransform transform;  ///< kOk: child in parent
  double gap = 0.0;          ///< kOk: [s] between the two samples interpolated (0: a sample at that very time)
};

class FrameHistory {
public:
  /// What insert() did with a sample.
  enum class Insert {
    kStored,
    kRepeated,  ///< a sample of that stamp is kept already: ignored (tf2's TF_REPEATED_DATA)
    kTooOld,    ///< older than the newest by more than the cache length: ignored (tf2's TF_OLD_DATA)
  };

  /// is_static: the frame keeps one sample for all times; cache_length [ns]: how far back a dynamic frame keeps
  /// samples before its newest.
  FrameHistory(bool is_static, Stamp cache_length);

  /// Stores a sample (a static frame replaces its sample); drops the samples older than the newest by more than
  /// the cache length.
  Insert insert(const FrameSample& sample);
  /// Forgets the samples of a dynamic frame (a static frame keeps its sample).
  void clear();
  /// The transform at a time (a static frame: its sample, whatever the time). Time 0 is the newest sample.
  FrameAnswer at(Stamp time) const;

  bool isStatic() const { return is_static_; }
  bool empty() const { return samples_.empty(); }
  /// The newest stamp kept [ns] (0 when empty or static).
  Stamp newest() const { return is_static_ || samples_.empty() ? 0 : samples_.back().stamp; }
  /// The oldest stamp kept [ns] (0 when empty or static).
  Stamp oldest() const { return is_static_ || samples_.empty() ? 0 : samples_.front().stamp; }
  std::size_t size() const { return samples_.size(); }

private:
  bool is_static_;
  Stamp cache_length_;
  std::deque<FrameSample> samples_;  ///< oldest first
};

}  // namespace mapping
}  // namespace unexmin

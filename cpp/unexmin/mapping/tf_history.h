// The mapper's tf: every frame's transform history, fed with the samples of /tf and /tf_static, answering "where
// was frame F in the target frame at time t" with typed results. On top of tf2's buffer rules (interpolation,
// cache length, static frames) it keeps the mapper's own:
// - one owner per dynamic frame: the first publisher heard, until it has been silent for handover_silence wall
//   seconds (then a new one, e.g. a second `rosbag play`, takes over); samples from a second live publisher (a
//   leftover process, a second simulator) are ignored, or the history would mix two different poses;
// - a dynamic frame's stamps going back (a simulation reset, a bag looping) or a hand-over start a new history:
//   every dynamic frame's samples are forgotten (static ones stay) and the jump is counted;
// - a lookup reports the largest gap between the two samples it interpolated on any frame of the chain.
// Not thread-safe: the caller locks. Knows no ROS.
#pragma once

#include <unexmin/mapping/frame_history.h>

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace unexmin {
namespace mapping {

/// One sample as /tf carries it (frame names with or without a leading '/').
struct TfSample {
  std::string parent, child;
  Stamp stamp = 0;           ///< [ns]
  RigidTransform transform;  ///< child in parent
};

/// What TfHistory::add() did with one message.
struct TfUpdate {
  /// Why the dynamic history was cleared (empty: it was not).
  std::string jump;
  /// "frame from publisher (it comes from owner)" for each frame and second publisher ignored for the first time.
  std::vector<std::string> newly_ignored;
  /// Samples refused: the reason for each (bad frame names, NaN, a quaternion not of unit length, too old).
  std::vector<std::string> refused;
};

/// The answer of TfHistory::lookup().
struct TfLookup {
  enum class Status {
    kOk,
    kTooOld,   ///< before the oldest sample kept of a frame of the chain: it will never be answered
    kTooNew,   ///< after the newest sample of a frame of the chain: wait for tf
    kNoChain,  ///< a frame unknown, without samples, or not connected to the target: wait for tf
  };
  Status status = Status::kNoChain;
  RigidTransform transform;  ///< kOk: source frame in target frame
  double gap = 0.0;          ///< kOk: the largest gap [s] between two interpolated samples along the chain
  std::string frame;         ///< kOk: the frame with that gap (empty when 0); otherwise the frame that failed
};

class TfHistory {
public:
  /// cache_length [s]: how long a dynamic frame's samples are kept behind its newest; handover_silence [s, wall]:
  /// how long an owner must have been silent before another publisher takes its frame over. ParameterError when
  /// cache_length is not in (0, 1e9) or handover_silence is negative or not finite.
  explicit TfHistory(double cache_length = 120.0, double handover_silence = 1.0);

  /// Stores one /tf (is_static false) or /tf_static (true) message's samples from publisher, received at wall
  /// time now [s]. Static samples replace the frame's sample whoever sends them.
  TfUpdate add(const std::vector<TfSample>& samples, const std::string& publisher, double now, bool is_static);
  /// source frame in target frame at time [ns] (0: the newest time all the chain's dynamic frames share).
  TfLookup lookup(const std::string& target, const std::string& source, Stamp time) const;

  /// Jumps back in time (and hand-overs) seen so far.
  std::uint64_t jumps() const { return jumps_; }
  /// Wall time [s] of the last jump (0: none).
  double lastJump() const { return last_jump_; }
  /// Samples ignored because another publisher owns their frame.
  std::uint64_t ignored() const { return ignored_; }

private:
  struct Owner {
    std::string node;
    double last = 0.0;  ///< [s, wall] its last sample of the frame
  };
  /// The history of a frame, created on its first sample (static or dynamic by that first sample, as tf2).
  FrameHistory& frame(const std::string& child, bool is_static);
  void clearDynamic();
  /// The frame's answer at time (kEmpty when the frame has no history).
  FrameAnswer at(const std::string& frame, Stamp time) const;
  /// The newest time every dynamic frame above target and source has a sample of (0: none).
  Stamp commonTime(const std::string& target, const std::string& source) const;

  Stamp cache_length_;
  double handover_silence_;
  std::map<std::string, FrameHistory> frames_;
  std::map<std::string, Owner> owners_;
  std::set<std::string> warned_;
  std::uint64_t jumps_ = 0, ignored_ = 0;
  double last_jump_ = 0.0;
};

}  // namespace mapping
}  // namespace unexmin

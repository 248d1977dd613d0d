#include <unexmin/mapping/cloud_queue.h>

#include <unexmin/core/error.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace mapping {

CloudQueue::CloudQueue(std::string map_frame, double tf_timeout, double tf_max_gap)
    : map_frame_(std::move(map_frame)), tf_timeout_(tf_timeout), tf_max_gap_(tf_max_gap) {
  if (map_frame_.empty())
    throw ParameterError("CloudQueue: map frame is empty: expected a frame");
  if (!(tf_timeout > 0.0) || !std::isfinite(tf_timeout)) {
    throw ParameterError("CloudQueue: tf_timeout = " + formatNumber(tf_timeout) + ": expected > 0 s");
  }
  if (!(tf_max_gap > 0.0) || !std::isfinite(tf_max_gap)) {
    throw ParameterError("CloudQueue: tf_max_gap = " + formatNumber(tf_max_gap) + ": expected > 0 s");
  }
}

void CloudQueue::push(PendingCloud&& cloud) {
  ++received_;
  pending_.push_back(std::move(cloud));
}

CloudStep CloudQueue::next(const TfHistory& tf, double now) {
  if (tf.jumps() != jumps_seen_) {
    jumps_seen_ = tf.jumps();
    const double jump = tf.lastJump();
    const std::size_t before = pending_.size();
    pending_.erase(
        std::remove_if(pending_.begin(), pending_.end(), [jump](const PendingCloud& c) { return c.received <= jump; }),
        pending_.end());
    dropped_ += before - pending_.size();
  }
  CloudStep step;
  if (pending_.empty())
    return step;
  const PendingCloud& front = pending_.front();
  const TfLookup tf_at = tf.lookup(map_frame_, front.frame, front.stamp);
  switch (tf_at.status) {
    case TfLookup::Status::kOk:
      if (tf_at.gap > tf_max_gap_) {
        step.kind = CloudStep::Kind::kDrop;
        step.why = "the tf of '" + tf_at.frame + "' has a gap of " + formatNumber(tf_at.gap) +
                   " s there (~tf_max_gap " + formatNumber(tf_max_gap_) + " s)";
      } else {
        step.kind = CloudStep::Kind::kInsert;
        step.sensor_in_map = tf_at.transform;
      }
      break;
    case TfLookup::Status::kTooOld:
      step.kind = CloudStep::Kind::kDrop;
      step.why = "older than the tf kept of '" + tf_at.frame + "'";
      break;
    case TfLookup::Status::kTooNew:
    case TfLookup::Status::kNoChain:
      if (now - front.received > tf_timeout_) {
        step.kind = CloudStep::Kind::kDrop;
        step.why = "no tf from '" + front.frame + "' to '" + map_frame_ + "' after " + formatNumber(tf_timeout_) +
                   " s (~tf_timeout): " +
                   (tf_at.status == TfLookup::Status::kTooNew ? "newer than the tf of '" : "no chain at '") +
                   tf_at.frame + "'";
      }
      break;
  }
  if (step.kind == CloudStep::Kind::kWait)
    return step;
  step.cloud = std::move(pending_.front());
  pending_.pop_front();
  if (step.kind == CloudStep::Kind::kDrop)
    ++dropped_;
  return step;
}

}  // namespace mapping
}  // namespace unexmin

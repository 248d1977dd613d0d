// One outgoing topic of the simulator: its ros::Publisher and roscpp's publication behind it, so that the
// subscriber count is read directly (RoscppPublication, roscpp_internals.h, says why).
#pragma once

#include <unexmin/ros_layer/roscpp_internals.h>

#include <ros/ros.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <string>

namespace unexmin {
namespace ros_layer {

/// Physics steps between two messages of a stream published at `rate` [Hz of sim time] by a simulator stepping at
/// `physics_rate` [Hz]: at least 1; 0 (never) when `rate` is 0.
inline std::uint64_t every(double physics_rate, double rate) {
  return rate > 0.0 ? std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(physics_rate / rate))) : 0;
}

/// Outgoing queue per subscriber of a stream published at `rate` [Hz of sim time] (a sensor topic, odometry,
/// joint states, thrust): 20 s of sim time, at least 1000 messages, so that a subscriber (a rosbag recorder) can
/// stall for 0.4 s of wall time at a real-time factor of 50, or a script step the world in bursts
/// (python/unexmin/scripting/simulation.py), without a message being dropped here.
inline int queueSize(double rate) {
  return static_cast<int>(std::max(1000.0, 20.0 * rate));
}

class Stream {
public:
  Stream() = default;
  /// Implicit, so that `stream = nh.advertise<M>(topic, queue)` reads as for a ros::Publisher.
  Stream(ros::Publisher pub)
      : pub_(std::move(pub))  // NOLINT(google-explicit-constructor)
  {
    if (!pub_)
      return;
    topic_ = pub_.getTopic();
    publication_ = RoscppPublication(topic_);
  }

  /// Subscribers now: what ros::Publisher::getNumSubscribers() answers (0 for an empty stream).
  std::uint32_t subscribers() const {
    if (publication_)
      return publication_.subscribers();
    return pub_ ? pub_.getNumSubscribers() : 0;
  }
  /// Resolved topic name ("" for an empty stream).
  const std::string& topic() const { return topic_; }
  const ros::Publisher& publisher() const { return pub_; }
  /// Publishes `m` to the subscribers there are now, and counts it in sent().
  template <class M>
  void publish(const M& m) const {
    pub_.publish(m);
    sent_.fetch_add(1, std::memory_order_relaxed);
  }
  /// Messages published through every Stream of this process so far (SubscriberPacer: has anything gone out).
  static std::uint64_t sent() { return sent_.load(std::memory_order_relaxed); }
  /// Whether it was advertised.
  explicit operator bool() const { return static_cast<bool>(pub_); }

private:
  ros::Publisher pub_;
  std::string topic_;
  RoscppPublication publication_;
  static inline std::atomic<std::uint64_t> sent_{0};
};

}  // namespace ros_layer
}  // namespace unexmin

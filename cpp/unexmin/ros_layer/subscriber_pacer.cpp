#include <unexmin/ros_layer/roscpp_internals.h>
#include <unexmin/ros_layer/stream.h>
#include <unexmin/ros_layer/subscriber_pacer.h>

#include <ros/ros.h>

#include <chrono>

namespace unexmin {
namespace ros_layer {
SubscriberPacer::~SubscriberPacer() {
  // Once this returns, the listener is not running and will not run again.
  if (listener_.connected())
    removePollTurnListener(listener_);
}

void SubscriberPacer::refresh() {
  publications_ = advertisedPublications();
}

bool SubscriberPacer::anySubscriber() const {
  for (const auto& p : publications_)
    if (p.subscribers() > 0)
      return true;
  return false;
}

void SubscriberPacer::finish(State state) {
  state_ = state;
  done_.notify_all();
}

// A wait, turn by turn of the poll thread (this listener runs after roscpp's own, which hands every publication's
// queue to its connections; the turn's writes follow it):
//  1. the turn may have begun before the messages were published: nothing to conclude;
//  2. every message published before the wait is in a connection's queue or written: the kernel's first view;
//  3. and on: drained when this view and the last one, a whole turn apart, find nothing unacknowledged, nothing
//     unread and not one byte more written (a connection still holding a message would have written it).
void SubscriberPacer::onPollTurn() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (state_ != State::kWaiting)
    return;
  ++turn_;
  if (turn_ == 1) {
    wakePollThread();
    return;
  }
  if (turn_ == 2) {
    if (!kernel_ok_)
      return finish(State::kNoKernel);
    ++waits_;
    before_ = viewTcpPort(port_);
    if (!before_.ok)
      return finish(State::kNoKernel);
    wakePollThread();
    return;
  }
  TcpPortView now = viewTcpPort(port_);
  if (!now.ok)
    return finish(State::kNoKernel);
  if (before_.unsettled == 0 && now.unsettled == 0 && before_.written == now.written) {
    return finish(State::kDrained);
  }
  if (now.moved != before_.moved)
    progress_ = ros::WallTime::now();
  const bool settled = now.unsettled == 0;
  before_ = std::move(now);
  if (settled)
    wakePollThread();  // one more whole turn to confirm; else the subscribers are reading (poked below)
}

bool SubscriberPacer::waitDrained(double stall_timeout) {
  if (calls_++ % 1000 == 0)
    refresh();  // topics advertised later (and none go away while the simulator runs)
  if (!anySubscriber()) {
    drained_ = false;
    return true;
  }
  // Nothing published by the simulator's streams since everything was last found taken: nothing to wait for, and
  // no need to wake the poll thread.
  const std::uint64_t sent = Stream::sent();
  if (drained_ && sent == drained_at_)
    return true;
  if (!listener_.connected()) {
    port_ = tcprosPort();
    listener_ = addPollTurnListener([this] { onPollTurn(); });
  }
  std::unique_lock<std::mutex> lock(mutex_);
  state_ = State::kWaiting;
  turn_ = 0;
  progress_ = ros::WallTime::now();
  while (state_ == State::kWaiting) {
    lock.unlock();
    wakePollThread();  // also every 0.1 ms while the subscribers read: the poll thread has no event to wake it
    lock.lock();
    if (done_.wait_for(lock, std::chrono::microseconds(100), [this] { return state_ != State::kWaiting; }))
      break;
    if (!ros::ok())
      break;
    if ((ros::WallTime::now() - progress_).toSec() > stall_timeout) {
      ROS_WARN_STREAM_THROTTLE(10.0, "lockstep_wait_subscribers: a subscriber has taken nothing for "
                                         << stall_timeout << " s (" << before_.unsettled
                                         << " bytes unread); stepping on");
      break;
    }
  }
  const State state = state_;
  state_ = State::kIdle;
  drained_ = state == State::kDrained;
  drained_at_ = sent;
  if (state == State::kNoKernel && kernel_ok_) {
    kernel_ok_ = false;
    ROS_WARN(
        "lockstep_wait_subscribers: the kernel's socket queues cannot be read (sock_diag with tcp_info); "
        "waiting only until roscpp has handed the messages to its connections");
  }
  return state == State::kDrained || state == State::kNoKernel;
}

}  // namespace ros_layer
}  // namespace unexmin

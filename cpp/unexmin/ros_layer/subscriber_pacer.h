// lockstep_wait_subscribers (docs/recording.md): before a lockstep step's messages go out, wait until every TCP
// subscriber connection of every topic this process publishes has taken the messages sent before, so that a stock
// `rosbag record` or a user's node receives everything (at the speed it can take).
//
// roscpp's user API cannot tell that a message has left: ros::Publisher counts subscribers, a
// SubscriberStatusCallback sees connects and disconnects, and a subscriber link's statistics count messages queued,
// not written. This class (with the kernel's side in tcp_port_view.h) works around it through roscpp's poll thread
// and managers, reached only through roscpp_internals.h (which lists the calls, why, and the roscpp versions they
// were checked against), and relies on two behaviours, which test/rostest/subscriber_pacer.cpp checks against the
// installed roscpp and kernel:
//  * roscpp's poll thread does the I/O of every TCPROS connection: at each turn it first calls its listeners
//    (addPollTurnListener; roscpp's own hands every publication's queue to its connections), then
//    writes what the connections hold while their sockets take it. Two turns after publish() returned, a message is
//    in a connection's queue or written; a whole turn that writes nothing into sockets that hold nothing means the
//    connections' queues are empty. The pacer's own listener does the looking, in that thread, between its turns.
//  * Linux's sock_diag reports each TCP socket's queues and byte counters: on this process's TCPROS port, bytes
//    written and not yet acknowledged, and on a subscriber's end of the same connection (subscribers on this machine,
//    IPv4), bytes received and not yet read by it.
#pragma once

#include <unexmin/ros_layer/roscpp_internals.h>
#include <unexmin/ros_layer/tcp_port_view.h>

#include <ros/time.h>

#include <boost/signals2/connection.hpp>

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <vector>

namespace unexmin {
namespace ros_layer {

class SubscriberPacer {
public:
  SubscriberPacer() = default;
  SubscriberPacer(const SubscriberPacer&) = delete;
  SubscriberPacer& operator=(const SubscriberPacer&) = delete;
  ~SubscriberPacer();

  /// Blocks until every message published before the call has been written to its TCP subscribers and read by
  /// them (those on this machine; acknowledged by those elsewhere), or ros::ok() turns false, or the subscribers have
  /// taken nothing for `stall_timeout` [s of wall time] (then warns, throttled, and returns false: a dead subscriber
  /// does not stop the simulation). Returns true when drained. Returns at once when no topic of this process has a
  /// subscriber, or when nothing was published through a Stream since the last wait found everything taken.
  bool waitDrained(double stall_timeout = 5.0);

  /// Waits so far that had something to wait for (the kernel was asked).
  std::size_t waits() const { return waits_; }

private:
  enum class State { kIdle, kWaiting, kDrained, kNoKernel };

  void refresh();
  /// Whether a topic of this process has a subscriber.
  bool anySubscriber() const;
  /// roscpp's poll thread, at each of its turns: one step of the wait in progress, if any.
  void onPollTurn();
  void finish(State state);

  std::vector<RoscppPublication> publications_;
  std::size_t calls_ = 0;
  boost::signals2::connection listener_;
  std::uint16_t port_ = 0;        ///< this process's TCPROS port
  bool drained_ = false;          ///< the last wait found everything taken ...
  std::uint64_t drained_at_ = 0;  ///< ... when Stream::sent() was this

  // Shared with the poll thread, under mutex_.
  std::mutex mutex_;
  std::condition_variable done_;
  State state_ = State::kIdle;
  int turn_ = 0;            ///< turns of the poll thread since the wait began
  TcpPortView before_;      ///< the kernel's view at the last turn
  ros::WallTime progress_;  ///< when bytes last moved
  bool kernel_ok_ = true;
  std::size_t waits_ = 0;
};

}  // namespace ros_layer
}  // namespace unexmin

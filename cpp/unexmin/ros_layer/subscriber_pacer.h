// lockstep_wait_subscribers (docs/recording.md): lockstep waits, before a step's messages go out, until every TCP
// subscriber connection of every topic this process publishes has taken its queued messages, so a stock
// `rosbag record` or a user's node receives everything (at the speed it can take).
//
// roscpp 1.15/1.16 has no public call for a subscriber connection's outgoing queue: ros::Publisher only
// counts subscribers, and a SubscriberStatusCallback sees connects and disconnects. Each connection's queue
// is TransportSubscriberLink::outbox_ (its messages_sent statistic counts messages queued, not written),
// and before it Publication::publish_queue_ (publish() only appends there; roscpp's poll thread moves it on),
// which this class reads under their own mutexes through the standard explicit-instantiation access rule;
// it depends on roscpp's member names, which have not changed since 2010 (checked against the headers at build time).
// An empty outbox is not enough: the kernel buffers megabytes between two processes, and a subscriber that
// reads them in a burst overflows its own queue (rosbag record: 100 messages per topic) and drops silently. So
// the pacer also waits until the kernel holds nothing for this process's TCPROS connections: nothing unacknowledged
// on our side and nothing unread on a subscriber's side (sock_diag; subscribers on this machine, IPv4).
#pragma once

#include <ros/publication.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace unexmin {
namespace ros_layer {

class SubscriberPacer
{
public:
  /// Messages queued for subscribers of every topic this process publishes (TCP connections), and whether
  /// one is being written right now.
  struct Backlog
  {
    std::size_t queued = 0;
    std::size_t writing = 0;  ///< connections in the middle of writing a message
    std::size_t in_kernel = 0;  ///< [bytes] written, not yet read by the subscriber (same machine) or acknowledged
    bool empty() const { return queued == 0 && writing == 0 && in_kernel == 0; }
  };
  Backlog backlog();

  /// Blocks until backlog() is empty, or ros::ok() turns false, or a subscriber has not taken a message for
  /// `stall_timeout` [s of wall time] (then warns, throttled, and returns false: a dead subscriber does not
  /// stop the simulation). Returns true when drained.
  bool waitDrained(double stall_timeout = 5.0);

  /// Wall time spent waiting so far [s], and how many waits had something to wait for.
  double waitedSeconds() const { return waited_; }
  std::size_t waits() const { return waits_; }

private:
  void refresh();

  std::vector<ros::PublicationPtr> publications_;
  std::size_t calls_ = 0;
  double waited_ = 0.0;
  std::size_t waits_ = 0;
  bool kernel_ok_ = true;
  bool drained_ = false;          ///< the last backlog() found everything taken ...
  std::uint64_t drained_at_ = 0;  ///< ... when this many messages had been handed to the open links
};

}  // namespace ros_layer
}  // namespace unexmin

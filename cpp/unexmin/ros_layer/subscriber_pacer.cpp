#include <unexmin/ros_layer/subscriber_pacer.h>
#include <unexmin/ros_layer/tcp_port_view.h>

#include <ros/connection_manager.h>
#include <ros/poll_manager.h>
#include <ros/ros.h>
#include <ros/topic_manager.h>
#include <xmlrpcpp/XmlRpcValue.h>


#include <chrono>
#include <thread>

namespace unexmin {
namespace ros_layer {

SubscriberPacer::~SubscriberPacer()
{
  // Under the poll manager's lock: once this returns, the listener is not running and will not run again.
  if (listener_.connected()) ros::PollManager::instance()->removePollThreadListener(listener_);
}

void SubscriberPacer::refresh()
{
  publications_.clear();
  std::vector<std::string> topics;
  ros::TopicManager::instance()->getAdvertisedTopics(topics);
  for (const auto& t : topics)
    if (ros::PublicationPtr p = ros::TopicManager::instance()->lookupPublication(t)) publications_.push_back(p);
}

bool SubscriberPacer::awaitPollTurns(int turns)
{
  if (!listener_.connected())
    listener_ = ros::PollManager::instance()->addPollThreadListener([this] {
      {
        std::lock_guard<std::mutex> lock(turn_mutex_);
        ++turns_;
      }
      turn_cv_.notify_all();
    });
  std::unique_lock<std::mutex> lock(turn_mutex_);
  const std::uint64_t target = turns_ + static_cast<std::uint64_t>(turns);
  while (turns_ < target) {
    if (!ros::ok()) return false;
    const std::uint64_t seen = turns_;
    lock.unlock();
    ros::PollManager::instance()->getPollSet().signal();  // the poll thread otherwise sleeps up to 100 ms
    lock.lock();
    turn_cv_.wait_for(lock, std::chrono::milliseconds(100), [&] { return turns_ > seen; });
  }
  return true;
}

bool SubscriberPacer::anySubscriber() const
{
  for (const auto& p : publications_)
    if (p->getNumSubscribers() > 0) return true;
  return false;
}

std::uint64_t SubscriberPacer::handedToConnections() const
{
  std::uint64_t handed = 0;
  for (const auto& p : publications_) {
    if (p->getNumSubscribers() == 0) continue;
    // [topic, [[connection id, bytes, data bytes, messages, connected], ...]]: messages counted when handed over.
    XmlRpc::XmlRpcValue stats = p->getStats();
    XmlRpc::XmlRpcValue& links = stats[1];
    for (int i = 0; i < links.size(); ++i) handed += static_cast<std::uint32_t>(static_cast<int>(links[i][3]));
  }
  return handed;
}

bool SubscriberPacer::waitDrained(double stall_timeout)
{
  if (calls_++ % 1000 == 0) refresh();  // topics advertised later (and none go away while the simulator runs)
  if (!anySubscriber()) {
    drained_ = false;
    return true;
  }
  // Two turns of the poll thread: every publication's queue has been handed to its connections.
  if (!awaitPollTurns(2)) return false;
  const std::uint64_t handed = handedToConnections();
  // Nothing handed to any connection since everything was last found taken: the kernel is not asked (a dump of
  // the TCP sockets walks the kernel's whole connection table, about 0.25 ms here).
  if (drained_ && handed == drained_at_) return true;
  drained_ = false;
  if (!kernel_ok_) return true;

  ++waits_;
  const auto port = static_cast<std::uint16_t>(ros::ConnectionManager::instance()->getTCPPort());
  const ros::WallTime start = ros::WallTime::now();
  ros::WallTime progress = start;
  TcpPortView before = viewTcpPort(port);
  while (before.ok && ros::ok()) {
    // A whole turn of the poll thread after `before`: it wrote whatever its connections held, if anything.
    if (!awaitPollTurns(2)) break;
    TcpPortView now = viewTcpPort(port);
    if (!now.ok) {
      before = now;
      break;
    }
    if (before.unsettled == 0 && now.unsettled == 0 && before.written == now.written) {
      drained_ = true;
      drained_at_ = handed;
      break;
    }
    const ros::WallTime wall = ros::WallTime::now();
    if (now.moved != before.moved) progress = wall;
    if ((wall - progress).toSec() > stall_timeout) {
      ROS_WARN_STREAM_THROTTLE(10.0, "lockstep_wait_subscribers: a subscriber has taken nothing for "
                                         << stall_timeout << " s (" << now.unsettled << " bytes unread); stepping on");
      break;
    }
    if (now.unsettled > 0) std::this_thread::sleep_for(std::chrono::microseconds(50));
    before = std::move(now);
  }
  if (!before.ok) {
    kernel_ok_ = false;
    ROS_WARN("lockstep_wait_subscribers: the kernel's socket queues cannot be read (sock_diag with tcp_info); "
             "waiting only until roscpp has handed the messages to its connections");
  }
  waited_ += (ros::WallTime::now() - start).toSec();
  return drained_;
}

}  // namespace ros_layer
}  // namespace unexmin

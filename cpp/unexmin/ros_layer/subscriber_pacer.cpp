#include <unexmin/ros_layer/subscriber_pacer.h>

#include <ros/connection_manager.h>
#include <ros/ros.h>
#include <ros/topic_manager.h>
#include <ros/transport_subscriber_link.h>

#include <boost/thread/mutex.hpp>

#include <linux/inet_diag.h>
#include <linux/netlink.h>
#include <linux/sock_diag.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstring>
#include <queue>
#include <thread>

namespace unexmin {
namespace ros_layer {
namespace {

// Access to roscpp's private queue members: an explicit instantiation may name private members
// ([temp.explicit]), and the friend function defined in it hands the member pointer out.
template <class Tag, typename Tag::type Member>
struct Expose
{
  friend typename Tag::type member(Tag) { return Member; }
};
struct Links { using type = ros::V_SubscriberLink ros::Publication::*; friend type member(Links); };
struct LinksMutex { using type = boost::mutex ros::Publication::*; friend type member(LinksMutex); };
struct Outbox { using type = std::queue<ros::SerializedMessage> ros::TransportSubscriberLink::*; friend type member(Outbox); };
struct OutboxMutex { using type = boost::mutex ros::TransportSubscriberLink::*; friend type member(OutboxMutex); };
struct Writing { using type = bool ros::TransportSubscriberLink::*; friend type member(Writing); };
struct PublishQueue { using type = std::vector<ros::SerializedMessage> ros::Publication::*; friend type member(PublishQueue); };
struct PublishQueueMutex { using type = boost::mutex ros::Publication::*; friend type member(PublishQueueMutex); };
template struct Expose<Links, &ros::Publication::subscriber_links_>;
template struct Expose<LinksMutex, &ros::Publication::subscriber_links_mutex_>;
template struct Expose<Outbox, &ros::TransportSubscriberLink::outbox_>;
template struct Expose<OutboxMutex, &ros::TransportSubscriberLink::outbox_mutex_>;
template struct Expose<Writing, &ros::TransportSubscriberLink::writing_message_>;
template struct Expose<PublishQueue, &ros::Publication::publish_queue_>;
template struct Expose<PublishQueueMutex, &ros::Publication::publish_queue_mutex_>;

/// Bytes in flight on the TCP connections of this process's TCPROS port `port` (IPv4), from the kernel
/// (sock_diag): written by us but not yet acknowledged, and received by a peer process on this machine but
/// not yet read by it. Returns false when the kernel cannot be asked.
bool kernelBacklog(std::uint16_t port, std::size_t& bytes)
{
  const int fd = ::socket(AF_NETLINK, SOCK_DGRAM | SOCK_CLOEXEC, NETLINK_SOCK_DIAG);
  if (fd < 0) return false;
  struct
  {
    nlmsghdr nlh;
    inet_diag_req_v2 req;
  } request{};
  request.nlh.nlmsg_len = sizeof(request);
  request.nlh.nlmsg_type = SOCK_DIAG_BY_FAMILY;
  request.nlh.nlmsg_flags = NLM_F_REQUEST | NLM_F_DUMP;
  request.req.sdiag_family = AF_INET;
  request.req.sdiag_protocol = IPPROTO_TCP;
  request.req.idiag_states = 1u << TCP_ESTABLISHED;
  sockaddr_nl kernel{};
  kernel.nl_family = AF_NETLINK;
  bool ok = ::sendto(fd, &request, sizeof(request), 0, reinterpret_cast<sockaddr*>(&kernel), sizeof(kernel)) >= 0;
  bytes = 0;
  alignas(nlmsghdr) char buffer[32768];
  for (bool done = !ok; !done;) {
    const ssize_t n = ::recv(fd, buffer, sizeof(buffer), 0);
    if (n <= 0) {
      ok = false;
      break;
    }
    int left = static_cast<int>(n);
    for (auto* h = reinterpret_cast<nlmsghdr*>(buffer); NLMSG_OK(h, left); h = NLMSG_NEXT(h, left)) {
      if (h->nlmsg_type == NLMSG_DONE) {
        done = true;
        break;
      }
      if (h->nlmsg_type == NLMSG_ERROR) {
        ok = false;
        done = true;
        break;
      }
      const auto* m = static_cast<const inet_diag_msg*>(NLMSG_DATA(h));
      if (ntohs(m->id.idiag_sport) == port) bytes += m->idiag_wqueue;  // ours: sent, not acknowledged
      if (ntohs(m->id.idiag_dport) == port) bytes += m->idiag_rqueue;  // a subscriber's: received, not read
    }
  }
  ::close(fd);
  return ok;
}

}  // namespace

void SubscriberPacer::refresh()
{
  publications_.clear();
  std::vector<std::string> topics;
  ros::TopicManager::instance()->getAdvertisedTopics(topics);
  for (const auto& t : topics)
    if (ros::PublicationPtr p = ros::TopicManager::instance()->lookupPublication(t)) publications_.push_back(p);
}

SubscriberPacer::Backlog SubscriberPacer::backlog()
{
  if (calls_++ % 1000 == 0) refresh();  // topics advertised later (and none go away while the simulator runs)
  Backlog b;
  std::uint64_t queued_ever = 0;  // messages ever queued to the links now open
  for (const auto& p : publications_) {
    {
      // publish() only appends to the publication's queue; roscpp's poll thread hands it to the links later.
      boost::mutex::scoped_lock lock((*p).*member(PublishQueueMutex()));
      b.queued += ((*p).*member(PublishQueue())).size();
    }
    ros::V_SubscriberLink links;
    {
      boost::mutex::scoped_lock lock((*p).*member(LinksMutex()));
      links = (*p).*member(Links());
    }
    for (const auto& l : links) {
      auto* link = dynamic_cast<ros::TransportSubscriberLink*>(l.get());
      if (!link) continue;  // intra-process: delivered in the publish call
      boost::mutex::scoped_lock lock(link->*member(OutboxMutex()));
      b.queued += (link->*member(Outbox())).size();
      b.writing += (link->*member(Writing())) ? 1 : 0;
      queued_ever += link->getStats().messages_sent_;  // counted when handed to the link
    }
  }
  // Nothing handed to any link since everything was last found taken, and nothing waiting in a publication's
  // queue: the kernel holds nothing of ours either, and is not asked. (A dump of the TCP sockets walks the kernel's
  // whole connection table, about 0.25 ms here: every physics step would pay it.)
  if (b.queued == 0 && b.writing == 0 && drained_ && queued_ever == drained_at_) return b;
  if (b.queued == 0 && kernel_ok_) {
    std::size_t bytes = 0;
    kernel_ok_ = kernelBacklog(static_cast<std::uint16_t>(ros::ConnectionManager::instance()->getTCPPort()), bytes);
    if (!kernel_ok_) ROS_WARN("lockstep_wait_subscribers: the kernel's socket queues cannot be read (sock_diag); "
                              "waiting on roscpp's queues only");
    b.in_kernel = bytes;
  }
  drained_ = b.empty();
  drained_at_ = queued_ever;
  return b;
}

bool SubscriberPacer::waitDrained(double stall_timeout)
{
  Backlog b = backlog();
  if (b.empty()) return true;
  ++waits_;
  const ros::WallTime start = ros::WallTime::now();
  ros::WallTime progress = start;
  std::size_t last = b.queued + b.in_kernel;
  while (!b.empty() && ros::ok()) {
    std::this_thread::sleep_for(std::chrono::microseconds(50));
    b = backlog();
    const ros::WallTime now = ros::WallTime::now();
    if (b.queued + b.in_kernel < last) progress = now;
    last = b.queued + b.in_kernel;
    if ((now - progress).toSec() > stall_timeout) {
      ROS_WARN_STREAM_THROTTLE(10.0, "lockstep_wait_subscribers: a subscriber has taken nothing for " << stall_timeout
                                         << " s (" << b.queued << " messages queued); stepping on");
      break;
    }
  }
  waited_ += (ros::WallTime::now() - start).toSec();
  return b.empty();
}

}  // namespace ros_layer
}  // namespace unexmin

#include <unexmin/ros/subscriber_pacer.h>

#include <ros/ros.h>
#include <ros/topic_manager.h>
#include <ros/transport_subscriber_link.h>

#include <boost/thread/mutex.hpp>

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
template struct Expose<Links, &ros::Publication::subscriber_links_>;
template struct Expose<LinksMutex, &ros::Publication::subscriber_links_mutex_>;
template struct Expose<Outbox, &ros::TransportSubscriberLink::outbox_>;
template struct Expose<OutboxMutex, &ros::TransportSubscriberLink::outbox_mutex_>;
template struct Expose<Writing, &ros::TransportSubscriberLink::writing_message_>;

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
  for (const auto& p : publications_) {
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
    }
  }
  return b;
}

bool SubscriberPacer::waitDrained(double stall_timeout)
{
  Backlog b = backlog();
  if (b.empty()) return true;
  ++waits_;
  const ros::WallTime start = ros::WallTime::now();
  ros::WallTime progress = start;
  std::size_t last = b.queued;
  while (!b.empty() && ros::ok()) {
    std::this_thread::sleep_for(std::chrono::microseconds(50));
    b = backlog();
    const ros::WallTime now = ros::WallTime::now();
    if (b.queued < last) progress = now;
    last = b.queued;
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

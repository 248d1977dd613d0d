#include <unexmin/ros_layer/roscpp_internals.h>

#include <ros/connection_manager.h>
#include <ros/poll_manager.h>
#include <ros/publication.h>
#include <ros/topic_manager.h>

#include <utility>

namespace unexmin {
namespace ros_layer {

RoscppPublication::RoscppPublication(const std::string& topic)
    : publication_(ros::TopicManager::instance()->lookupPublication(topic)) {}

std::uint32_t RoscppPublication::subscribers() const {
  return publication_ ? publication_->getNumSubscribers() : 0;
}

std::vector<RoscppPublication> advertisedPublications() {
  std::vector<std::string> topics;
  ros::TopicManager::instance()->getAdvertisedTopics(topics);
  std::vector<RoscppPublication> out;
  for (const auto& t : topics) {
    RoscppPublication p(t);
    if (p)
      out.push_back(std::move(p));
  }
  return out;
}

std::uint16_t tcprosPort() {
  return static_cast<std::uint16_t>(ros::ConnectionManager::instance()->getTCPPort());
}

boost::signals2::connection addPollTurnListener(std::function<void()> listener) {
  return ros::PollManager::instance()->addPollThreadListener(std::move(listener));
}

void removePollTurnListener(const boost::signals2::connection& listener) {
  ros::PollManager::instance()->removePollThreadListener(listener);
}

void wakePollThread() {
  ros::PollManager::instance()->getPollSet().signal();
}

}  // namespace ros_layer
}  // namespace unexmin

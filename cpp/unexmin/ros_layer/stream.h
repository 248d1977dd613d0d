// One outgoing topic of the simulator: its ros::Publisher and roscpp's publication behind it, so that the
// subscriber count is read directly. ros::Publisher::getNumSubscribers() looks the topic up by name among every
// topic the node advertises (a lock and a string comparison per topic: about 130 topics with 3 robots), and the
// simulator asks before building each message of every stream, thousands of times per second of sim time.
#pragma once

#include <ros/publication.h>
#include <ros/ros.h>
#include <ros/topic_manager.h>

#include <cstdint>
#include <string>

namespace unexmin {
namespace ros_layer {

class Stream
{
public:
  Stream() = default;
  /// Implicit, so that `stream = nh.advertise<M>(topic, queue)` reads as for a ros::Publisher.
  Stream(ros::Publisher pub) : pub_(std::move(pub))  // NOLINT(google-explicit-constructor)
  {
    if (!pub_) return;
    topic_ = pub_.getTopic();
    publication_ = ros::TopicManager::instance()->lookupPublication(topic_);
  }

  /// Subscribers now: what ros::Publisher::getNumSubscribers() answers (0 for an empty stream).
  std::uint32_t subscribers() const
  {
    if (publication_) return publication_->getNumSubscribers();
    return pub_ ? pub_.getNumSubscribers() : 0;
  }
  /// Resolved topic name ("" for an empty stream).
  const std::string& topic() const { return topic_; }
  const ros::Publisher& publisher() const { return pub_; }
  /// Whether it was advertised.
  explicit operator bool() const { return static_cast<bool>(pub_); }

private:
  ros::Publisher pub_;
  std::string topic_;
  ros::PublicationPtr publication_;
};

}  // namespace ros_layer
}  // namespace unexmin

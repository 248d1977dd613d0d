// The one place the simulator reaches past roscpp's user API (ros::NodeHandle, ros::Publisher): roscpp's managers
// and publications, which roscpp installs as headers but does not document as API. Every other file of the project
// goes through the functions below; test/pytest/test_layout.py checks that no other file includes those headers.
//
// What is used, and why:
//  * ros::TopicManager::lookupPublication, getAdvertisedTopics, and ros::Publication::getNumSubscribers: the
//    subscriber count of a topic this process advertises, read from its publication directly
//    (RoscppPublication). ros::Publisher::getNumSubscribers() looks the topic up by name among every topic the node
//    advertises (a lock and a string comparison per topic: about 130 topics with 3 robots), and the simulator asks
//    before building each message of every stream, thousands of times per second of sim time (Stream, stream.h);
//    the lockstep pacer asks it of every advertised topic (SubscriberPacer, subscriber_pacer.h).
//  * ros::ConnectionManager::getTCPPort: this process's TCPROS server port, where the kernel is asked what the
//    subscribers have not yet taken (tcp_port_view.h). The user API does not say which port roscpp listens on.
//  * ros::PollManager::addPollThreadListener, removePollThreadListener, getPollSet().signal(): a callback in
//    roscpp's poll thread at each of its turns, and a wake-up of that thread. roscpp writes every TCPROS connection
//    in that thread, and the user API cannot tell that a message has left (SubscriberPacer).
// Only these calls, no private member and no dependence on roscpp's object layout. Checked against roscpp 1.15.15
// (Debian 12's libroscpp-dev 1.15.15+ds-2, ROS Noetic's roscpp 1.15.x); test/rostest/subscriber_pacer.test checks
// the behaviours the pacer relies on against the installed roscpp.
#pragma once

#include <boost/shared_ptr.hpp>
#include <boost/signals2/connection.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace ros {
class Publication;
}  // namespace ros

namespace unexmin {
namespace ros_layer {

/// roscpp's publication of one topic this process advertises.
class RoscppPublication {
public:
  RoscppPublication() = default;
  /// The publication of the resolved `topic`; empty when this process does not advertise it.
  explicit RoscppPublication(const std::string& topic);

  /// Subscribers now (0 when empty): what ros::Publisher::getNumSubscribers() answers, without its lookup by name.
  std::uint32_t subscribers() const;
  explicit operator bool() const { return static_cast<bool>(publication_); }

private:
  boost::shared_ptr<ros::Publication> publication_;
};

/// The publications of every topic this process advertises now.
std::vector<RoscppPublication> advertisedPublications();

/// This process's TCPROS server port (the node must be started).
std::uint16_t tcprosPort();

/// Calls `listener` in roscpp's poll thread at each of its turns, after roscpp's own listeners (which hand every
/// publication's queue to its connections) and before the turn's socket writes. Disconnect with
/// removePollTurnListener.
boost::signals2::connection addPollTurnListener(std::function<void()> listener);
/// Removes a listener under the poll manager's lock: once this returns, it is not running and will not run again.
void removePollTurnListener(const boost::signals2::connection& listener);
/// Wakes roscpp's poll thread for a turn now (else it sleeps up to 100 ms without an event).
void wakePollThread();

}  // namespace ros_layer
}  // namespace unexmin

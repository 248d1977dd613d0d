// SubscriberPacer (lockstep_wait_subscribers, docs/recording.md) against the installed roscpp and kernel: it relies
// on how roscpp's poll thread moves messages and on sock_diag's byte counters, and these tests fail (they never
// skip) when either behaves otherwise. The subscriber is a raw TCPROS client in this process that reads exactly
// when the test tells it to, so what "taken" means is known to the byte.
#include <unexmin/ros_layer/roscpp_internals.h>
#include <unexmin/ros_layer/stream.h>
#include <unexmin/ros_layer/subscriber_pacer.h>
#include <unexmin/ros_layer/tcp_port_view.h>

#include <ros/ros.h>
#include <std_msgs/String.h>

#include "ros_test_main.h"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace unexmin {
namespace {

using ros_layer::SubscriberPacer;

/// A TCPROS subscriber of a std_msgs/String topic of this process, speaking the protocol on a plain socket.
class RawSubscriber {
public:
  explicit RawSubscriber(const std::string& topic) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(ros_layer::tcprosPort());
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (fd_ < 0 || ::connect(fd_, reinterpret_cast<sockaddr*>(&to), sizeof(to)) != 0)
      throw std::runtime_error("cannot connect to this process's TCPROS port: " + std::string(std::strerror(errno)));
    std::string header;
    const std::map<std::string, std::string> fields{{"callerid", "/raw_subscriber"},
                                                    {"topic", topic},
                                                    {"md5sum", ros::message_traits::md5sum<std_msgs::String>()},
                                                    {"type", ros::message_traits::datatype<std_msgs::String>()},
                                                    {"tcp_nodelay", "1"}};
    for (const auto& f : fields)
      header += length(f.first.size() + 1 + f.second.size()) + f.first + "=" + f.second;
    const std::string packet = length(header.size()) + header;
    if (::send(fd_, packet.data(), packet.size(), 0) != static_cast<ssize_t>(packet.size()))
      throw std::runtime_error("cannot send the connection header");
    std::uint32_t reply = 0;
    readExactly(reinterpret_cast<char*>(&reply), 4);
    std::vector<char> rest(reply);
    readExactly(rest.data(), rest.size());
    const std::string text(rest.begin(), rest.end());
    if (text.find("error=") != std::string::npos)
      throw std::runtime_error("the publisher refused: " + text);
  }
  ~RawSubscriber() { ::close(fd_); }

  /// Local port of the connection (the publisher sees it as the subscriber's).
  std::uint16_t port() const {
    sockaddr_in self{};
    socklen_t size = sizeof(self);
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&self), &size);
    return ntohs(self.sin_port);
  }
  /// Bytes received by the kernel and not read yet.
  std::size_t unread() const {
    int n = 0;
    ::ioctl(fd_, FIONREAD, &n);
    return static_cast<std::size_t>(n);
  }
  /// Reads exactly `size` bytes (blocking).
  void readExactly(char* out, std::size_t size) {
    for (std::size_t got = 0; got < size;) {
      const ssize_t n = ::recv(fd_, out + got, size - got, 0);
      if (n <= 0)
        throw std::runtime_error("the publisher closed the connection");
      got += static_cast<std::size_t>(n);
      read_ += static_cast<std::size_t>(n);
    }
  }
  void skip(std::size_t size) {
    std::vector<char> sink(size);
    readExactly(sink.data(), size);
  }
  /// Message bytes read so far (after the connection header).
  std::size_t read() const { return read_ - header_; }
  void startCounting() { header_ = read_; }

private:
  static std::string length(std::size_t n) {
    const auto v = static_cast<std::uint32_t>(n);  // little-endian, as TCPROS
    return std::string(reinterpret_cast<const char*>(&v), 4);
  }

  int fd_ = -1;
  std::size_t read_ = 0;
  std::size_t header_ = 0;
};

/// Advertises `topic` and connects a RawSubscriber to it; returns once roscpp counts it.
struct Connected {
  explicit Connected(const std::string& topic)
      : pub(ros::NodeHandle().advertise<std_msgs::String>(topic, 1000)), subscriber(topic) {
    subscriber.startCounting();
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(10.0);
    while (pub.subscribers() == 0 && ros::WallTime::now() < deadline)
      ros::WallDuration(0.001).sleep();
    if (pub.subscribers() == 0)
      throw std::runtime_error(topic + ": roscpp never counted the raw subscriber");
  }
  /// Publishes a message of `size` characters; returns its bytes on the wire.
  std::size_t publish(std::size_t size) {
    std_msgs::String m;
    m.data.assign(size, 'x');
    pub.publish(m);
    return 4 + 4 + size;  // TCPROS length, then the string's length and characters
  }
  ros_layer::Stream pub;  // the simulator's way to publish (the pacer counts what goes out through it)
  RawSubscriber subscriber;
};

TEST(SubscriberPacer, KernelReportsThisProcesssConnectionsWithTheirByteCounters) {
  const std::uint16_t port = ros_layer::tcprosPort();
  ASSERT_TRUE(ros_layer::viewTcpPort(port).ok)
      << "sock_diag with tcp_info cannot be read: lockstep_wait_subscribers cannot work here";
  Connected c("/pacer_test/kernel");
  const std::size_t bytes = c.publish(1000);
  std::vector<char> message(bytes);
  c.subscriber.readExactly(message.data(), bytes);
  const ros_layer::TcpPortView view = ros_layer::viewTcpPort(port);
  ASSERT_TRUE(view.ok);
  const std::uint32_t loopback = htonl(INADDR_LOOPBACK);
  const auto it = view.written.find(std::make_tuple(port, c.subscriber.port(), loopback, loopback));
  ASSERT_NE(it, view.written.end()) << "the raw subscriber's connection is not among this process's";
  // Written on it: the connection header, then this message (read, so acknowledged or about to be).
  EXPECT_GT(it->second, bytes);
}

TEST(SubscriberPacer, ReturnsAtOnceWithoutSubscribers) {
  ros::Publisher pub = ros::NodeHandle().advertise<std_msgs::String>("/pacer_test/alone", 10);
  std_msgs::String m;
  m.data = "nobody listens";
  pub.publish(m);
  SubscriberPacer pacer;
  EXPECT_TRUE(pacer.waitDrained(0.5));
  EXPECT_EQ(pacer.waits(), 0u);
}

// More than the kernel buffers between two sockets: while the subscriber reads, part of it is still in roscpp's own
// queues. After every partial read (all the kernel had for it), the pacer must see that something is left; after
// the last byte, that nothing is.
TEST(SubscriberPacer, WaitsUntilTheSubscriberHasReadEveryByte) {
  Connected c("/pacer_test/bulk");
  std::size_t total = 0;
  for (int i = 0; i < 8; ++i)
    total += c.publish(1000000);
  SubscriberPacer pacer;
  int rounds = 0;
  while (c.subscriber.read() < total) {
    ASSERT_FALSE(pacer.waitDrained(0.3)) << "drained with " << total - c.subscriber.read() << " bytes not read";
    const std::size_t n = std::min(c.subscriber.unread(), total - c.subscriber.read());
    ASSERT_GT(n, 0u) << "nothing arrived for the subscriber, " << total - c.subscriber.read() << " bytes missing";
    c.subscriber.skip(n);
    ASSERT_LT(++rounds, 500);
  }
  EXPECT_GT(rounds, 1) << "the kernel took all of it at once: the test no longer reaches roscpp's queues";
  EXPECT_TRUE(pacer.waitDrained(5.0));
  EXPECT_EQ(c.subscriber.unread(), 0u);
  EXPECT_GE(pacer.waits(), 1u);
}

// A message published just before the wait is still in roscpp's publication queue (its poll thread hands it to the
// connections later) while the kernel holds nothing: the pacer must wait for it all the same.
TEST(SubscriberPacer, WaitsForAMessageStillInRoscppsQueue) {
  Connected c("/pacer_test/fresh");
  SubscriberPacer pacer;
  EXPECT_TRUE(pacer.waitDrained(5.0));  // nothing sent yet
  for (int i = 0; i < 20; ++i) {
    const std::size_t bytes = c.publish(100);
    EXPECT_FALSE(pacer.waitDrained(0.2)) << "message " << i << " not read, the pacer found everything taken";
    c.subscriber.skip(bytes);
    EXPECT_TRUE(pacer.waitDrained(5.0)) << "message " << i << " read, the pacer still waits";
    EXPECT_EQ(c.subscriber.unread(), 0u);
  }
}

}  // namespace
}  // namespace unexmin

int main(int argc, char** argv) {
  return unexmin::test::runRosTests(argc, argv, "subscriber_pacer_test");
}

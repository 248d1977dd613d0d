// The kernel's view of the TCP connections of one local port, for SubscriberPacer (lockstep_wait_subscribers,
// docs/recording.md): Linux's sock_diag with tcp_info, IPv4. ROS-free, and apart from the pacer because roscpp's
// headers bring glibc's <netinet/tcp.h>, whose tcp_info lacks the byte counters of the kernel's <linux/tcp.h>.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <tuple>

namespace unexmin {
namespace ros_layer {

struct TcpPortView {
  bool ok = false;            ///< the kernel answered, with the byte counters (Linux >= 4.1)
  std::size_t unsettled = 0;  ///< [bytes] written on the port's connections and not acknowledged, or received by a
                              ///< peer on this machine and not read by it
  std::uint64_t moved = 0;    ///< [bytes] written on the port's connections plus read by their peers on this machine
  /// Per established connection (the port, the peer's port, our IPv4 address, the peer's, in network byte order):
  /// bytes written on it so far.
  std::map<std::tuple<std::uint16_t, std::uint16_t, std::uint32_t, std::uint32_t>, std::uint64_t> written;
};

/// The established TCP connections of local port `port` (the connections peers opened to it) now.
TcpPortView viewTcpPort(std::uint16_t port);

}  // namespace ros_layer
}  // namespace unexmin

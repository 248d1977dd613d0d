#include <unexmin/ros_layer/tcp_port_view.h>

#include <linux/inet_diag.h>
#include <linux/netlink.h>
#include <linux/rtnetlink.h>
#include <linux/sock_diag.h>
#include <linux/tcp.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <vector>

namespace unexmin {
namespace ros_layer {
namespace {

constexpr unsigned kTcpEstablished = 1;  // the kernel's TCP_ESTABLISHED state (<netinet/tcp.h> names it too)

}  // namespace

TcpPortView viewTcpPort(std::uint16_t port) {
  TcpPortView view;
  const int fd = ::socket(AF_NETLINK, SOCK_DGRAM | SOCK_CLOEXEC, NETLINK_SOCK_DIAG);
  if (fd < 0)
    return view;
  // The request, and a filter so that the kernel describes only the port's sockets (sport == port or dport ==
  // port; inet_diag's bytecode: each test jumps `yes` bytes on, or `no` bytes, past the end to reject).
  struct {
    nlmsghdr nlh;
    inet_diag_req_v2 req;
    rtattr filter;
    inet_diag_bc_op ops[5];
  } request{};
  request.nlh.nlmsg_len = sizeof(request);
  request.nlh.nlmsg_type = SOCK_DIAG_BY_FAMILY;
  request.nlh.nlmsg_flags = NLM_F_REQUEST | NLM_F_DUMP;
  request.req.sdiag_family = AF_INET;
  request.req.sdiag_protocol = IPPROTO_TCP;
  request.req.idiag_states = 1u << kTcpEstablished;
  request.req.idiag_ext = 1u << (INET_DIAG_INFO - 1);  // tcp_info: the byte counters
  request.filter.rta_type = INET_DIAG_REQ_BYTECODE;
  request.filter.rta_len = RTA_LENGTH(sizeof(request.ops));
  request.ops[0] = {INET_DIAG_BC_S_EQ, 8, 12};  // source port: accepted through the jump at 8, else on to 12
  request.ops[1] = {0, 0, port};
  request.ops[2] = {INET_DIAG_BC_JMP, 4, 12};   // to the end (20): accepted
  request.ops[3] = {INET_DIAG_BC_D_EQ, 8, 12};  // destination port: to the end (20), or past it (24): rejected
  request.ops[4] = {0, 0, port};
  sockaddr_nl kernel{};
  kernel.nl_family = AF_NETLINK;
  bool ok = ::sendto(fd, &request, sizeof(request), 0, reinterpret_cast<sockaddr*>(&kernel), sizeof(kernel)) >= 0;

  // A subscriber's end of a connection is matched to ours by its address and port pair, read the other way round.
  using Key = std::tuple<std::uint16_t, std::uint16_t, std::uint32_t, std::uint32_t>;
  struct PeerEnd {
    Key ours;
    std::uint64_t unread = 0;  ///< [bytes] received, not read by the subscriber
    std::uint64_t read = 0;    ///< [bytes] read by the subscriber so far
  };
  std::vector<PeerEnd> peers;
  constexpr std::size_t kCountersEnd = offsetof(tcp_info, tcpi_bytes_received) + sizeof(tcp_info::tcpi_bytes_received);
  alignas(nlmsghdr) char buffer[32768];
  for (bool done = !ok; !done;) {
    const ssize_t n = ::recv(fd, buffer, sizeof(buffer), 0);
    if (n <= 0) {
      ok = false;
      break;
    }
    int left = static_cast<int>(n);
    for (auto* h = reinterpret_cast<nlmsghdr*>(buffer); NLMSG_OK(h, left); h = NLMSG_NEXT(h, left)) {
      if (h->nlmsg_type == NLMSG_DONE || h->nlmsg_type == NLMSG_ERROR) {
        ok = ok && h->nlmsg_type == NLMSG_DONE;
        done = true;
        break;
      }
      const auto* m = static_cast<const inet_diag_msg*>(NLMSG_DATA(h));
      const std::uint16_t sport = ntohs(m->id.idiag_sport), dport = ntohs(m->id.idiag_dport);
      if (sport != port && dport != port)
        continue;
      tcp_info info{};
      bool has_info = false;
      int attr_left = static_cast<int>(h->nlmsg_len - NLMSG_LENGTH(sizeof(*m)));
      for (auto* a = reinterpret_cast<const rtattr*>(m + 1); RTA_OK(a, attr_left); a = RTA_NEXT(a, attr_left)) {
        if (a->rta_type != INET_DIAG_INFO || RTA_PAYLOAD(a) < kCountersEnd)
          continue;
        std::memcpy(&info, RTA_DATA(a), std::min<std::size_t>(RTA_PAYLOAD(a), sizeof(info)));
        has_info = true;
      }
      if (!has_info) {  // a kernel without the byte counters (Linux < 4.1)
        ok = false;
        continue;
      }
      if (sport == port) {  // ours: written = acknowledged + in flight
        view.written[Key{sport, dport, m->id.idiag_src[0], m->id.idiag_dst[0]}] =
            info.tcpi_bytes_acked + m->idiag_wqueue;
        view.unsettled += m->idiag_wqueue;
        view.moved += info.tcpi_bytes_acked + m->idiag_wqueue;
      } else {
        peers.push_back({Key{dport, sport, m->id.idiag_dst[0], m->id.idiag_src[0]}, m->idiag_rqueue,
                         info.tcpi_bytes_received - m->idiag_rqueue});
      }
    }
  }
  ::close(fd);
  for (const auto& p : peers) {
    if (!view.written.count(p.ours))
      continue;  // another host's connection to a port of the same number
    view.unsettled += p.unread;
    view.moved += p.read;
  }
  view.ok = ok;
  return view;
}

}  // namespace ros_layer
}  // namespace unexmin

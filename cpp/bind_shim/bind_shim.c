/* Preload library (LD_PRELOAD) that keeps every server socket of a ROS process on one address.
 *
 * A bind() of a TCP or UDP socket to the wildcard address (IPv4 0.0.0.0 or IPv6 ::) is turned into a bind() to
 * the address ROS nodes advertise: ROS_IP, else ROS_HOSTNAME, else 127.0.0.1 (the loopback). Any other bind()
 * (a given address, another socket family or type) is passed through unchanged; a listen() on a socket that was
 * never bound (which the kernel would bind to the wildcard) binds it to that address first. roscpp 1.15's XML-RPC
 * server binds the wildcard whatever ROS_IP says, and roscpp, rospy and rosmaster bind it too when ROS_IP is not a
 * loopback address; with this library preloaded they listen on that one address (docs/reliability.md).
 *
 * The address is read once per process, at the first wildcard bind(): a numeric IPv4 or IPv6 address,
 * "localhost", or a host name (resolved with getaddrinfo). An IPv4 address is used for an IPv6 socket as its
 * IPv4-mapped form (::ffff:a.b.c.d), and "::1" as 127.0.0.1 for an IPv4 socket. A wildcard bind() that cannot be
 * kept to that address fails (EADDRNOTAVAIL) with one line on stderr naming the variable and its value: it never
 * falls back to every interface. */
#define _GNU_SOURCE
#include <arpa/inet.h>
#include <dlfcn.h>
#include <errno.h>
#include <netdb.h>
#include <netinet/in.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>

typedef int (*bind_function)(int, const struct sockaddr*, socklen_t);
typedef int (*listen_function)(int, int);

/* The address wildcard binds are kept to (read once per process). */
static struct {
  const char* variable; /* "ROS_IP", "ROS_HOSTNAME" or "default" */
  char value[256];      /* what the variable holds */
  int has_v4, has_v6;
  struct in_addr v4;
  struct in6_addr v6;
} target;

static pthread_once_t target_once = PTHREAD_ONCE_INIT;
static bind_function real_bind;
static __thread int resolving; /* getaddrinfo() is running on this thread: its own binds pass through */

static void map_v4_to_v6(void) { /* ::ffff:a.b.c.d */
  memset(&target.v6, 0, sizeof target.v6);
  target.v6.s6_addr[10] = target.v6.s6_addr[11] = 0xff;
  memcpy(&target.v6.s6_addr[12], &target.v4, 4);
  target.has_v6 = 1;
}

static void read_target(void) {
  real_bind = (bind_function)dlsym(RTLD_NEXT, "bind");
  const char* ip = getenv("ROS_IP");
  const char* host = getenv("ROS_HOSTNAME");
  const char* name = "127.0.0.1";
  target.variable = "default";
  if (ip && *ip) {
    target.variable = "ROS_IP";
    name = ip;
  } else if (host && *host) {
    target.variable = "ROS_HOSTNAME";
    name = host;
  }
  snprintf(target.value, sizeof target.value, "%s", name);
  if (strcmp(name, "localhost") == 0)
    name = "127.0.0.1";
  if (inet_pton(AF_INET, name, &target.v4) == 1) {
    target.has_v4 = 1;
    map_v4_to_v6();
    return;
  }
  if (inet_pton(AF_INET6, name, &target.v6) == 1) {
    target.has_v6 = 1;
    if (IN6_IS_ADDR_LOOPBACK(&target.v6)) {
      target.v4.s_addr = htonl(INADDR_LOOPBACK);
      target.has_v4 = 1;
    } else if (IN6_IS_ADDR_V4MAPPED(&target.v6)) {
      memcpy(&target.v4, &target.v6.s6_addr[12], 4);
      target.has_v4 = 1;
    }
    return;
  }
  struct addrinfo hints, *found = NULL;
  memset(&hints, 0, sizeof hints);
  hints.ai_socktype = SOCK_STREAM;
  resolving = 1;
  int status = getaddrinfo(name, NULL, &hints, &found);
  resolving = 0;
  if (status != 0)
    return;
  for (struct addrinfo* a = found; a; a = a->ai_next) {
    if (a->ai_family == AF_INET && !target.has_v4) {
      target.v4 = ((const struct sockaddr_in*)a->ai_addr)->sin_addr;
      target.has_v4 = 1;
    } else if (a->ai_family == AF_INET6 && !target.has_v6) {
      target.v6 = ((const struct sockaddr_in6*)a->ai_addr)->sin6_addr;
      target.has_v6 = 1;
    }
  }
  freeaddrinfo(found);
  if (target.has_v4 && !target.has_v6)
    map_v4_to_v6();
}

/* One line on stderr, at most once per process. */
static void complain(const char* what, int error) {
  static int said;
  if (__atomic_exchange_n(&said, 1, __ATOMIC_RELAXED))
    return;
  fprintf(stderr, "unexmin bind shim: %s %s='%s'%s%s: expected %s\n", what, target.variable, target.value,
          error ? ": " : "", error ? strerror(error) : "",
          "ROS_IP (or ROS_HOSTNAME) naming an address of this machine");
}

static int is_wildcard(const struct sockaddr* address, socklen_t length) {
  if (address->sa_family == AF_INET && length >= sizeof(struct sockaddr_in))
    return ((const struct sockaddr_in*)address)->sin_addr.s_addr == htonl(INADDR_ANY);
  if (address->sa_family == AF_INET6 && length >= sizeof(struct sockaddr_in6))
    return IN6_IS_ADDR_UNSPECIFIED(&((const struct sockaddr_in6*)address)->sin6_addr);
  return 0;
}

int bind(int fd, const struct sockaddr* address, socklen_t length) {
  if (resolving)
    return ((bind_function)dlsym(RTLD_NEXT, "bind"))(fd, address, length);
  pthread_once(&target_once, read_target);
  int type = 0;
  socklen_t type_length = sizeof type;
  if (!address || !is_wildcard(address, length) || getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &type_length) != 0 ||
      (type != SOCK_STREAM && type != SOCK_DGRAM))
    return real_bind(fd, address, length);

  struct sockaddr_storage kept;
  socklen_t size = address->sa_family == AF_INET ? sizeof(struct sockaddr_in) : sizeof(struct sockaddr_in6);
  memcpy(&kept, address, size);
  if (address->sa_family == AF_INET) {
    if (!target.has_v4) {
      complain("no IPv4 address for", 0);
      errno = EADDRNOTAVAIL;
      return -1;
    }
    ((struct sockaddr_in*)&kept)->sin_addr = target.v4;
  } else {
    if (!target.has_v6) {
      complain("no IPv6 address for", 0);
      errno = EADDRNOTAVAIL;
      return -1;
    }
    ((struct sockaddr_in6*)&kept)->sin6_addr = target.v6;
  }
  int result = real_bind(fd, (const struct sockaddr*)&kept, size);
  if (result != 0 && errno != EADDRINUSE) {
    int error = errno;
    complain("cannot listen on", error);
    errno = error;
  }
  return result;
}

int listen(int fd, int backlog) {
  static listen_function real_listen;
  if (!real_listen)
    real_listen = (listen_function)dlsym(RTLD_NEXT, "listen");
  struct sockaddr_storage own;
  socklen_t length = sizeof own;
  if (getsockname(fd, (struct sockaddr*)&own, &length) == 0 && is_wildcard((const struct sockaddr*)&own, length) &&
      ((const struct sockaddr_in*)&own)->sin_port == 0 && bind(fd, (const struct sockaddr*)&own, length) != 0)
    return -1;
  return real_listen(fd, backlog);
}

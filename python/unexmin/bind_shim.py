"""Where a world's processes listen (docs/reliability.md "Safe by default"): on ROS_IP, the loopback 127.0.0.1
unless the user names an address (ROS_IP or ROS_HOSTNAME), and never on every interface. The preload library
libunexmin_bind_shim.so (cpp/bind_shim/) turns each wildcard bind() of a process into a bind() to that address.
The launcher puts it in LD_PRELOAD of its own environment, so that the roslaunch it starts, its master, rosout and
every node, and any other process it starts afterwards (a rosbag recorder), inherit it; scripts/bind_shim/ does
the same for roslaunch, roscore, rostest and rosrun typed in a shell that sourced scripts/env.sh."""

import os
from pathlib import Path

LIBRARY = "libunexmin_bind_shim.so"


def library_path(env=None):
    """Absolute path of libunexmin_bind_shim.so: the first found in LD_LIBRARY_PATH, then in <prefix>/lib of
    CMAKE_PREFIX_PATH (the catkin workspace's devel or install space). FileNotFoundError naming where it looked."""
    env = os.environ if env is None else env
    folders = [f for f in env.get("LD_LIBRARY_PATH", "").split(":") if f]
    folders += [os.path.join(p, "lib") for p in env.get("CMAKE_PREFIX_PATH", "").split(":") if p]
    for folder in folders:
        candidate = Path(folder) / LIBRARY
        if candidate.is_file():
            return str(candidate.resolve())
    raise FileNotFoundError(
        f"{LIBRARY} is in none of {folders} (LD_LIBRARY_PATH, CMAKE_PREFIX_PATH/lib): "
        "expected a built catkin workspace with the unexmin package, sourced"
    )


def advertised_host(env=None):
    """The address (or host name) the processes advertise and listen on: ROS_IP, else ROS_HOSTNAME, else
    127.0.0.1; an IPv6 address in brackets, ready for a URI."""
    env = os.environ if env is None else env
    host = env.get("ROS_IP") or env.get("ROS_HOSTNAME") or "127.0.0.1"
    return f"[{host}]" if ":" in host else host


def ros_environment(env):
    """`env` (a dict, changed in place and returned) as scripts/env.sh sets it: ROS_IP=127.0.0.1 unless ROS_IP or
    ROS_HOSTNAME is set, and libunexmin_bind_shim.so first in LD_PRELOAD (once)."""
    if not env.get("ROS_IP") and not env.get("ROS_HOSTNAME"):
        env["ROS_IP"] = "127.0.0.1"
    shim = library_path(env)
    preload = [p for p in env.get("LD_PRELOAD", "").replace(":", " ").split() if Path(p).name != LIBRARY]
    env["LD_PRELOAD"] = " ".join([shim, *preload])
    return env

"""One-line diagnosis of the link between the simulator's host and a robot (docs/real_robot.md).

    python -m unexmin.hil.check [--motor-topic /ux1/command/motors] [--timeout 3] [--max-stamp-age 0.05]

Run on the simulator's host with the environment the simulator gets (ROS_MASTER_URI = the robot's master, ROS_IP =
this host's address on the link). It checks, in this order and each within --timeout: the environment, the master,
the robot's publisher of the ESC commands (its advertised address, then its messages reaching this host) and the
age of their stamps on arrival (the clock offset plus the latency). It prints one line: `link OK: ...` (exit
status 0) or the first problem and what to do (exit status 1); 2 for a bad argument.
"""

import argparse
import os
import socket
import statistics
import sys
import time
import xmlrpc.client
from urllib.parse import urlparse

from unexmin.hil.listen import with_bind_shim
from unexmin.topics import ESC_COMMAND_TOPIC


class LinkProblem(Exception):
    """The first thing found wrong, as one line for the user."""


class _TimeoutTransport(xmlrpc.client.Transport):
    def __init__(self, timeout):
        super().__init__()
        self.timeout = timeout

    def make_connection(self, host):
        connection = super().make_connection(host)
        connection.timeout = self.timeout
        return connection


def xmlrpc_call(uri, timeout, method, *args):
    """`method`(*args) on the XML-RPC server `uri`, giving up after `timeout` [s] (OSError, socket.timeout)."""
    return getattr(xmlrpc.client.ServerProxy(uri, transport=_TimeoutTransport(timeout)), method)(*args)


def is_local_address(address):
    """True when `address` is an address of this host (one can bind a socket to it)."""
    try:
        with socket.socket(socket.AF_INET6 if ":" in address else socket.AF_INET, socket.SOCK_DGRAM) as s:
            s.bind((address, 0))
        return True
    except OSError:
        return False


def check_environment(env):
    """(master URI, this host's address) from `env`, or LinkProblem."""
    master = env.get("ROS_MASTER_URI")
    if not master:
        raise LinkProblem("ROS_MASTER_URI is not set: export ROS_MASTER_URI=http://<robot address>:11311")
    host = urlparse(master).hostname
    if not host or not urlparse(master).port:
        raise LinkProblem(f"ROS_MASTER_URI={master!r}: expected http://<robot address>:<port>")
    own = env.get("ROS_IP") or env.get("ROS_HOSTNAME")
    if not own:
        raise LinkProblem(
            "neither ROS_IP nor ROS_HOSTNAME is set: the robot would be given this host's name, which "
            "it may not resolve; export ROS_IP=<this host's address on the link to the robot>"
        )
    try:
        own_address = socket.getaddrinfo(own, None)[0][4][0]
    except socket.gaierror as e:
        raise LinkProblem(f"ROS_HOSTNAME={own!r} does not resolve here ({e.strerror}): use ROS_IP=<address>") from e
    if not is_local_address(own_address):
        raise LinkProblem(
            f"ROS_IP={own} is not an address of this host: expected this host's address on the link "
            f"to the robot (see `ip addr`)"
        )
    try:
        master_address = socket.getaddrinfo(host, None)[0][4][0]
    except socket.gaierror as e:
        raise LinkProblem(
            f"the master's host {host!r} (ROS_MASTER_URI) does not resolve here ({e.strerror}): " "use its address"
        ) from e
    if own_address.startswith("127.") and not master_address.startswith("127."):
        raise LinkProblem(
            f"ROS_IP={own} is the loopback but the master {master} is on another host: the robot "
            "could not reach this host's nodes; export ROS_IP=<this host's address on that link>"
        )
    return master, own


def check_link(motor_topic=ESC_COMMAND_TOPIC, timeout=3.0, max_stamp_age=0.05, env=None):
    """The one line of a healthy link, or LinkProblem naming the first problem."""
    master, own = check_environment(os.environ if env is None else env)
    caller = "/unexmin_link_check"
    try:
        state = xmlrpc_call(master, timeout, "getSystemState", caller)[2]
    except (OSError, xmlrpc.client.Error) as e:
        raise LinkProblem(
            f"cannot reach the master {master} within {timeout:g} s ({e}): is the link up "
            f"(ping {urlparse(master).hostname}) and roscore running on the robot?"
        ) from None
    publishers = next((nodes for topic, nodes in state[0] if topic == motor_topic), [])
    if not publishers:
        raise LinkProblem(f"nobody publishes {motor_topic} on the master {master}: is the robot's software running?")
    for node in publishers:
        uri = xmlrpc_call(master, timeout, "lookupNode", caller, node)[2]
        try:
            xmlrpc_call(uri, timeout, "getPid", caller)
        except (OSError, xmlrpc.client.Error) as e:
            raise LinkProblem(
                f"{node} (publisher of {motor_topic}) advertises {uri}, which this host cannot reach "
                f"({e}): set ROS_IP on the robot to its address on this link"
            ) from None
    subscribers = [n for topic, nodes in state[1] if topic == motor_topic for n in nodes]
    ages, span = receive(motor_topic, timeout, own, publishers)
    age = statistics.median(ages)
    if abs(age) > max_stamp_age:
        raise LinkProblem(
            f"{motor_topic} arrives {age * 1e3:+.1f} ms after its stamps (median of {len(ages)}): the "
            f"clocks of the two hosts differ by about that much; synchronise them (chrony)"
        )
    rate = (len(ages) - 1) / span if span > 0 else float("nan")
    esc = f"subscribed by {', '.join(subscribers)}" if subscribers else "no subscriber yet (start the ESC driver)"
    return (
        f"link OK: master {master}, {motor_topic} from {', '.join(publishers)} at {rate:.1f} Hz, stamp age "
        f"{age * 1e3:+.1f} ms (latency + clock offset), {esc}"
    )


def receive(topic, timeout, own, publishers, count=10):
    """([arrival time - stamp [s]], first to last arrival [s]) of up to `count` messages of `topic` received within
    `timeout` [s]; LinkProblem if none comes."""
    import rospy
    from ux1_msgs.msg import MotorCommand

    rospy.init_node("unexmin_link_check", anonymous=True, disable_signals=True)
    ages, arrivals = [], []

    def on_message(msg):
        now = time.time()
        arrivals.append(now)
        ages.append(now - msg.header.stamp.to_sec())

    sub = rospy.Subscriber(topic, MotorCommand, on_message, tcp_nodelay=True)
    deadline = time.monotonic() + timeout
    while len(ages) < count and time.monotonic() < deadline:
        time.sleep(0.02)
    sub.unregister()
    if not ages:
        raise LinkProblem(
            f"no message on {topic} within {timeout:g} s although {', '.join(publishers)} publishes it: "
            f"the robot cannot connect to this host's ROS_IP={own} (its route or firewall towards it)"
        )
    return ages, arrivals[-1] - arrivals[0]


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m unexmin.hil.check", description=__doc__.split("\n\n")[0])
    p.add_argument("--motor-topic", default=ESC_COMMAND_TOPIC, help="the robot's ESC commands (default %(default)s)")
    p.add_argument("--timeout", type=float, default=3.0, help="time allowed to each step [s] (default %(default)s)")
    p.add_argument(
        "--max-stamp-age", type=float, default=0.05, help="largest accepted |arrival - stamp| [s] (default %(default)s)"
    )
    args = p.parse_args(argv)
    if not 0 < args.timeout <= 60:
        p.error(f"--timeout {args.timeout:g}: expected a time in (0, 60] s")
    if not args.max_stamp_age > 0:
        p.error(f"--max-stamp-age {args.max_stamp_age:g}: expected a time > 0 s")
    with_bind_shim("unexmin.hil.check", argv)
    try:
        print(check_link(args.motor_topic, args.timeout, args.max_stamp_age), flush=True)
        status = 0
    except LinkProblem as e:
        print(f"link problem: {e}", flush=True)
        status = 1
    sys.stderr.flush()
    os._exit(status)  # rospy's shutdown would call a master that may be out of reach: no hang on the way out


if __name__ == "__main__":
    main()

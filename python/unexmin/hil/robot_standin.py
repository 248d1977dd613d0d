"""A stand-in for the UX-1's own software, to try hardware in the loop without the robot (docs/real_robot.md).

    python -m unexmin.hil.robot_standin [--rate 10] [--levels 2129 -2140] [--period 1.0] [--time-port 11399]

On the master of ROS_MASTER_URI it publishes what the real robot's software does for the simulator's ESC driver:
`/ux1/command/motors` (ux1_msgs/MotorCommand, the eight thrusters' propeller speeds in RPM mode, as the real ESC
driver receives them) at `--rate`, and its navigation (nav_msgs/Odometry, `--nav-topic`) at `--nav-rate`, every
message stamped with this host's wall clock whatever /use_sim_time says (a robot keeps its own time). The eight
values are all one level of `--levels`, the next level every `--period` s: steps the simulator's thrust must follow.
The navigation is that of a robot held still on the bench: the pose `--position`, zero velocity.
With `--time-port` it also answers clock-offset requests (unexmin.hil.clock_sync) on UDP ROS_IP:port.
"""

import argparse
import os
import threading
import time

from unexmin.hil.listen import with_bind_shim
from unexmin.topics import ESC_COMMAND_TOPIC

#: Where the stand-in publishes its navigation (the real robot's navigation topic is not part of the simulator).
NAV_TOPIC = "/ux1/navigation/odom"


def level_at(levels, period, elapsed):
    """The command level [rev/min] `elapsed` s after the start: levels[k mod n] during the k-th `period`."""
    return levels[int(elapsed // period) % len(levels)]


def parse_args(argv=None):
    p = argparse.ArgumentParser(prog="python -m unexmin.hil.robot_standin", description=__doc__.split("\n\n")[0])
    p.add_argument("--node-name", default="robot_standin", help="the node's name (default %(default)s)")
    p.add_argument("--motor-topic", default=ESC_COMMAND_TOPIC, help="ESC command topic (default %(default)s)")
    p.add_argument("--rate", type=float, default=10.0, help="ESC command rate [Hz] (default %(default)s)")
    p.add_argument(
        "--levels",
        type=float,
        nargs="+",
        default=[2129.0, -2140.0],
        help="propeller speeds [rev/min] taken in turn (default %(default)s: 17.85 N and -14.12 N with "
        "the ESC driver's default table)",
    )
    p.add_argument("--period", type=float, default=1.0, help="time each level is held [s] (default %(default)s)")
    p.add_argument("--nav-topic", default=NAV_TOPIC, help="navigation topic (default %(default)s)")
    p.add_argument("--nav-rate", type=float, default=10.0, help="navigation rate [Hz] (default %(default)s)")
    p.add_argument(
        "--position",
        type=float,
        nargs=3,
        default=[0.0, 0.0, -1.8],
        metavar=("X", "Y", "Z"),
        help="the navigation's position [m] (default %(default)s)",
    )
    p.add_argument(
        "--time-port",
        type=int,
        default=None,
        help="answer clock-offset requests on this UDP port of ROS_IP (default: no)",
    )
    args = p.parse_args(argv)
    for name in ("rate", "nav_rate", "period"):
        value = getattr(args, name)
        if not 0 < value <= 1000:
            p.error(f"--{name.replace('_', '-')} {value:g}: expected a value in (0, 1000]")
    if args.time_port is not None and not 1 <= args.time_port <= 65535:
        p.error(f"--time-port {args.time_port}: expected a UDP port in [1, 65535]")
    return args


class RobotStandIn:
    """The stand-in's publishers and its two timed loops (ESC commands, navigation), on the wall clock."""

    def __init__(self, args):
        import rospy
        from nav_msgs.msg import Odometry
        from ux1_msgs.msg import MotorCommand

        self.args, self.MotorCommand, self.Odometry = args, MotorCommand, Odometry
        self.motors = rospy.Publisher(args.motor_topic, MotorCommand, queue_size=10)
        self.nav = rospy.Publisher(args.nav_topic, Odometry, queue_size=10)
        self.start = time.time()
        self.stop = threading.Event()

    @staticmethod
    def stamp(t):
        import rospy

        return rospy.Time.from_sec(t)

    def command(self, t):
        msg = self.MotorCommand(mode=self.MotorCommand.RPM)
        msg.header.stamp = self.stamp(t)
        msg.values = [level_at(self.args.levels, self.args.period, t - self.start)] * 8
        return msg

    def navigation(self, t):
        msg = self.Odometry()
        msg.header.stamp, msg.header.frame_id, msg.child_frame_id = self.stamp(t), "world", "ux1/base_link"
        msg.pose.pose.position.x, msg.pose.pose.position.y, msg.pose.pose.position.z = self.args.position
        msg.pose.pose.orientation.w = 1.0
        return msg

    def loop(self, rate, publish):
        """Call publish(wall time) every 1/rate s of the wall clock (monotonic schedule, no drift) until stop."""
        period, tick = 1.0 / rate, time.monotonic()
        while not self.stop.is_set():
            publish(time.time())
            tick += period
            self.stop.wait(max(0.0, tick - time.monotonic()))

    def run(self):
        import rospy

        def commands(t):
            self.motors.publish(self.command(t))

        def navigation(t):
            self.nav.publish(self.navigation(t))

        threads = [
            threading.Thread(target=self.loop, args=(self.args.rate, commands), daemon=True),
            threading.Thread(target=self.loop, args=(self.args.nav_rate, navigation), daemon=True),
        ]
        for t in threads:
            t.start()
        rospy.spin()
        self.stop.set()
        for t in threads:
            t.join(2.0)


def main(argv=None):
    args = parse_args(argv)
    with_bind_shim("unexmin.hil.robot_standin", argv)
    import rospy

    from unexmin.hil.clock_sync import TimeServer

    rospy.init_node(args.node_name)
    server = None
    if args.time_port is not None:
        server = TimeServer(os.environ.get("ROS_IP", "127.0.0.1"), args.time_port)
    rospy.loginfo(
        "robot stand-in: %s (RPM %s, %g s each) at %g Hz, %s at %g Hz, wall-clock stamps%s",
        args.motor_topic,
        args.levels,
        args.period,
        args.rate,
        args.nav_topic,
        args.nav_rate,
        f"; clock-offset server on UDP {server.sock.getsockname()[0]}:{server.port}" if server else "",
    )
    try:
        RobotStandIn(args).run()
    finally:
        if server:
            server.close()


if __name__ == "__main__":
    main()

"""Keyboard teleoperation of a UX robot (thesis 5.10.1, table 5.1), in a terminal (curses).

    W/S up/down          A/D -/+ yaw          I/K forward/backward     J/L left/right
    Z/X +/- linear speed C/V +/- angular speed E/R +/- pendulum 1 deg   Y/U +/- VBS 0.01 kg
    Space stop thrust    Q (or Ctrl-C) quit

Publishes /<robot>/force_moments (geometry_msgs/Wrench, body frame: X forward, Y left, Z up, N about
z, counter-clockwise seen from above, REP-103) for the thruster allocator, /<robot>/pendulum
(std_msgs/Float64 [rad]) and /<robot>/vbs (std_msgs/Float64 [kg]).

A movement key commands its axis for ~key_timeout seconds after the last press (holding the key
down repeats it, so the robot moves while the key is held); ~key_timeout 0 latches every axis until
Space. The wrench is published at ~rate [Hz] (wall clock: this is a human interface) so the
thrusters' watchdog never stops a held motion, and zero once nothing is held. The pendulum and VBS
commands are published (latched) whenever they change. Keys are case-insensitive.

TeleopState below is the keyboard logic without ROS or a terminal (unit-tested); TeleopNode adds
the publishers and the curses screen. Parameters: docs/teleop.md.
"""

import math
import signal
import sys
import time

#: Movement keys: key -> (wrench component, sign). Thesis table 5.1 (A is -yaw, D is +yaw).
MOVE_KEYS = {
    "w": ("Z", +1), "s": ("Z", -1),
    "a": ("N", -1), "d": ("N", +1),
    "i": ("X", +1), "k": ("X", -1),
    "j": ("Y", +1), "l": ("Y", -1),
}
AXES = ("X", "Y", "Z", "K", "M", "N")
LINEAR_AXES = ("X", "Y", "Z")

HELP = (
    "W/S up/down   A/D -/+yaw   I/K forward/backward   J/L left/right   Space stop",
    "Z/X +/- linear speed   C/V +/- angular speed   E/R +/- pendulum   Y/U +/- VBS   Q quit",
)


class TeleopState:
    """Keyboard state: speeds, held axes, pendulum and VBS. No ROS, no terminal; time is passed in [s].

    linear, angular: initial wrench magnitudes of a linear key [N] and a yaw key [N m] (the "speeds"
    of table 5.1: the allocator turns them into thrust).
    linear_step, angular_step: change per Z/X and C/V press; linear_max, angular_max: upper limits
    (lower limit 0).
    pendulum_step: [rad] per E/R press; pendulum_min/max: [rad] limits.
    vbs_step: [kg] per Y/U press; vbs_min/max: [kg] limits.
    key_timeout: [s] a movement key holds its axis this long after its last press; <= 0 latches.
    """

    def __init__(self, linear=10.0, angular=2.0, linear_step=1.0, angular_step=0.5, linear_max=80.0,
                 angular_max=40.0, pendulum_step=math.radians(1.0), pendulum_min=math.radians(-30.0),
                 pendulum_max=math.radians(30.0), vbs_step=0.01, vbs_min=-1.0, vbs_max=1.0, key_timeout=0.7):
        checks = (("linear_step", linear_step), ("angular_step", angular_step), ("linear_max", linear_max),
                  ("angular_max", angular_max), ("pendulum_step", pendulum_step), ("vbs_step", vbs_step))
        for name, value in checks:
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                raise ValueError(f"parameter ~{name} = {value!r}: expected a finite number > 0")
        for name, value, top in (("linear", linear, linear_max), ("angular", angular, angular_max)):
            if not (isinstance(value, (int, float)) and 0 <= value <= top):
                raise ValueError(f"parameter ~{name} = {value!r}: expected a number in [0, {top}] "
                                 f"(~{name}_max)")
        for name, lo, hi in (("pendulum", pendulum_min, pendulum_max), ("vbs", vbs_min, vbs_max)):
            if not (math.isfinite(lo) and math.isfinite(hi) and lo <= 0.0 <= hi):
                raise ValueError(f"parameters ~{name}_min = {lo}, ~{name}_max = {hi}: expected min <= 0 <= max")
        if not math.isfinite(key_timeout):
            raise ValueError(f"parameter ~key_timeout = {key_timeout!r}: expected a number of seconds")
        self.linear, self.angular = float(linear), float(angular)
        self.linear_step, self.angular_step = float(linear_step), float(angular_step)
        self.linear_max, self.angular_max = float(linear_max), float(angular_max)
        self.pendulum_step, self.vbs_step = float(pendulum_step), float(vbs_step)
        self.pendulum_min, self.pendulum_max = float(pendulum_min), float(pendulum_max)
        self.vbs_min, self.vbs_max = float(vbs_min), float(vbs_max)
        self.key_timeout = float(key_timeout)
        # Pendulum and VBS are whole numbers of steps, so repeated presses never accumulate rounding.
        self.pendulum_steps = 0
        self.vbs_steps = 0
        self.held = {}            # axis -> (sign, expiry time [s] or None when latched)
        self.quit = False

    @property
    def pendulum(self):
        """Pendulum target angle [rad]."""
        return self.pendulum_steps * self.pendulum_step

    @property
    def vbs(self):
        """VBS ballast mass [kg]."""
        return round(self.vbs_steps * self.vbs_step, 9)

    def press(self, key, now):
        """Apply one key press at time `now` [s]. Returns what changed: a set of 'wrench', 'speed',
        'pendulum', 'vbs', 'quit' (empty for an unknown key)."""
        k = key.lower() if isinstance(key, str) else key
        if k in MOVE_KEYS:
            axis, sign = MOVE_KEYS[k]
            self.held[axis] = (sign, None if self.key_timeout <= 0 else now + self.key_timeout)
            return {"wrench"}
        if k == " ":
            self.held.clear()
            return {"wrench"}
        if k in ("z", "x"):
            step = self.linear_step if k == "z" else -self.linear_step
            self.linear = min(self.linear_max, max(0.0, round(self.linear + step, 9)))
            return {"speed", "wrench"}
        if k in ("c", "v"):
            step = self.angular_step if k == "c" else -self.angular_step
            self.angular = min(self.angular_max, max(0.0, round(self.angular + step, 9)))
            return {"speed", "wrench"}
        if k in ("e", "r"):
            n = self.pendulum_steps + (1 if k == "e" else -1)
            if self.pendulum_min - 1e-12 <= n * self.pendulum_step <= self.pendulum_max + 1e-12:
                self.pendulum_steps = n
                return {"pendulum"}
            return set()
        if k in ("y", "u"):
            n = self.vbs_steps + (1 if k == "y" else -1)
            if self.vbs_min - 1e-12 <= n * self.vbs_step <= self.vbs_max + 1e-12:
                self.vbs_steps = n
                return {"vbs"}
            return set()
        if k in ("q", "\x03"):
            self.quit = True
            return {"quit"}
        return set()

    def expire(self, now):
        """Drop axes whose key was not pressed again within key_timeout; True if any was dropped."""
        gone = [a for a, (_, until) in self.held.items() if until is not None and now >= until]
        for a in gone:
            del self.held[a]
        return bool(gone)

    def wrench(self, now=None):
        """[X Y Z K M N] ([N], [N m]) commanded now (held axes times the current speeds)."""
        if now is not None:
            self.expire(now)
        w = [0.0] * 6
        for axis, (sign, _) in self.held.items():
            w[AXES.index(axis)] = sign * (self.linear if axis in LINEAR_AXES else self.angular)
        return w

    def status_lines(self, now=None):
        """The lines the terminal shows (speeds, pendulum, VBS, wrench)."""
        w = self.wrench(now)
        held = " ".join(f"{'+' if s > 0 else '-'}{a}" for a, (s, _) in sorted(self.held.items())) or "none"
        return [
            f"linear speed  {self.linear:7.2f} N      angular speed {self.angular:7.2f} N m",
            f"pendulum      {math.degrees(self.pendulum):7.1f} deg    VBS           {self.vbs:+7.2f} kg",
            "wrench        X {:+.2f}  Y {:+.2f}  Z {:+.2f}  K {:+.2f}  M {:+.2f}  N {:+.2f}".format(*w),
            f"held axes     {held}",
        ]


def state_from_params(get_param):
    """TeleopState from parameters read with get_param(name, default) (rospy's, with '~')."""
    return TeleopState(
        linear=get_param("linear", 10.0), angular=get_param("angular", 2.0),
        linear_step=get_param("linear_step", 1.0), angular_step=get_param("angular_step", 0.5),
        linear_max=get_param("linear_max", 80.0), angular_max=get_param("angular_max", 40.0),
        pendulum_step=math.radians(get_param("pendulum_step_deg", 1.0)),
        pendulum_min=get_param("pendulum_min", math.radians(-30.0)),
        pendulum_max=get_param("pendulum_max", math.radians(30.0)),
        vbs_step=get_param("vbs_step", 0.01), vbs_min=get_param("vbs_min", -1.0), vbs_max=get_param("vbs_max", 1.0),
        key_timeout=get_param("key_timeout", 0.7))


class TeleopNode:
    """Publishers of the teleop and its curses loop (run() owns the terminal until Q or Ctrl-C)."""

    def __init__(self):
        import rospy
        from geometry_msgs.msg import Wrench
        from std_msgs.msg import Float64

        from unexmin.topics import robot_param, sync_publisher

        self.rospy, self.Wrench, self.Float64 = rospy, Wrench, Float64
        robot = robot_param()
        self.rate = rospy.get_param("~rate", 10.0)
        if not (isinstance(self.rate, (int, float)) and 0.5 <= self.rate <= 100.0):
            raise ValueError(f"parameter ~rate = {self.rate!r}: expected [0.5, 100] Hz")
        self.state = state_from_params(lambda name, default: rospy.get_param("~" + name, default))
        self.robot = robot
        # Synchronous publishers: the final zero wrench is on the wire before we exit.
        self.wrench_pub = sync_publisher(f"/{robot}/force_moments", Wrench)
        self.pendulum_pub = sync_publisher(f"/{robot}/pendulum", Float64, latch=True)
        self.vbs_pub = sync_publisher(f"/{robot}/vbs", Float64, latch=True)
        self.last_sent = None

    def publish_wrench(self, now):
        w = self.state.wrench(now)
        msg = self.Wrench()
        msg.force.x, msg.force.y, msg.force.z = w[:3]
        msg.torque.x, msg.torque.y, msg.torque.z = w[3:]
        self.wrench_pub.publish(msg)
        self.last_sent = w

    def handle(self, key, now):
        changed = self.state.press(key, now)
        if "pendulum" in changed:
            self.pendulum_pub.publish(self.Float64(self.state.pendulum))
        if "vbs" in changed:
            self.vbs_pub.publish(self.Float64(self.state.vbs))
        return changed

    def draw(self, screen, now):
        screen.erase()
        rows, cols = screen.getmaxyx()
        lines = [f"UNEXMIN keyboard teleop -> /{self.robot}   (thesis table 5.1)", *HELP, ""]
        lines += self.state.status_lines(now)
        if self.wrench_pub.get_num_connections() == 0:
            lines += ["", f"no subscriber on /{self.robot}/force_moments: is the thruster allocator running?"]
        for row, text in enumerate(lines[: max(0, rows - 1)]):
            screen.addnstr(row, 0, text, max(1, cols - 1))
        screen.refresh()

    def run(self, screen):
        import curses

        try:
            curses.curs_set(0)
        except curses.error:
            pass
        screen.keypad(True)
        period = 1.0 / self.rate
        next_pub = time.monotonic()
        while not self.state.quit and not self.rospy.is_shutdown():
            now = time.monotonic()
            if now >= next_pub:
                self.publish_wrench(now)
                next_pub = now + period
                self.draw(screen, now)
            screen.timeout(max(1, int((next_pub - time.monotonic()) * 1000)))
            ch = screen.getch()
            if ch == -1:
                continue
            key = chr(ch) if 0 <= ch < 256 else None
            if key is None:
                continue
            changed = self.handle(key, time.monotonic())
            if changed & {"wrench", "speed"}:
                self.publish_wrench(time.monotonic())
                next_pub = time.monotonic() + period
            self.draw(screen, time.monotonic())
        self.stop()

    def stop(self):
        """Zero wrench: the robot must not keep thrusting once the operator has gone."""
        self.state.held.clear()
        self.publish_wrench(time.monotonic())


def _raise_exit(signum, frame):
    raise SystemExit(128 + signum)


def main():
    """Entry point of nodes/teleop: needs a terminal; restores it on Q, Ctrl-C, SIGTERM and SIGHUP."""
    import curses

    import rospy

    if not sys.stdin.isatty():
        sys.exit("teleop: stdin is not a terminal; run it in a terminal (roslaunch: launch-prefix=\"xterm -e\")")
    rospy.init_node("teleop", disable_signals=True)   # Ctrl-C must reach us as KeyboardInterrupt
    try:
        node = TeleopNode()
    except ValueError as e:
        sys.exit(f"teleop: {e}")
    signal.signal(signal.SIGTERM, _raise_exit)
    signal.signal(signal.SIGHUP, _raise_exit)
    try:
        curses.wrapper(node.run)          # wrapper restores the terminal whatever happens inside
    except KeyboardInterrupt:
        pass
    finally:
        node.stop()
        rospy.signal_shutdown("teleop closed")
    s = node.state
    print(f"teleop: stopped (linear {s.linear:g} N, angular {s.angular:g} N m, "
          f"pendulum {math.degrees(s.pendulum):g} deg, VBS {s.vbs:g} kg)")

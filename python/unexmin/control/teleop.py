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

TeleopState below is the keyboard logic without ROS or a terminal (unit-tested): keys to operator
intents, turned into commands by unexmin.control.operator_commands (shared with the joystick teleop);
TeleopNode adds the publishers and the curses screen. Parameters: docs/teleop.md.
"""

import math
import signal
import sys
import time

from unexmin.control.operator_commands import CommandPublishers, OperatorCommands, command_params

#: Movement keys: key -> (wrench component, sign). Thesis table 5.1 (A is -yaw, D is +yaw).
MOVE_KEYS = {
    "w": ("Z", +1),
    "s": ("Z", -1),
    "a": ("N", -1),
    "d": ("N", +1),
    "i": ("X", +1),
    "k": ("X", -1),
    "j": ("Y", +1),
    "l": ("Y", -1),
}
#: Step keys: key -> operator intent (unexmin.control.operator_commands.STEP_INTENTS).
STEP_KEYS = {
    "z": "linear+",
    "x": "linear-",
    "c": "angular+",
    "v": "angular-",
    "e": "pendulum+",
    "r": "pendulum-",
    "y": "vbs+",
    "u": "vbs-",
}

HELP = (
    "W/S up/down   A/D -/+yaw   I/K forward/backward   J/L left/right   Space stop",
    "Z/X +/- linear speed   C/V +/- angular speed   E/R +/- pendulum   Y/U +/- VBS   Q quit",
)


class TeleopState(OperatorCommands):
    """Keyboard state: the held axes over the shared OperatorCommands (speeds, pendulum, VBS). No ROS,
    no terminal; time is passed in [s].

    key_timeout: [s] a movement key holds its axis this long after its last press; <= 0 latches.
    The other arguments are OperatorCommands's (speeds, steps and limits).
    """

    def __init__(self, key_timeout=0.7, **commands):
        super().__init__(**commands)
        if not math.isfinite(key_timeout):
            raise ValueError(f"parameter ~key_timeout = {key_timeout!r}: expected a number of seconds")
        self.key_timeout = float(key_timeout)
        self.held = {}  # axis -> (sign, expiry time [s] or None when latched)
        self.quit = False

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
        if k in STEP_KEYS:
            return self.apply(STEP_KEYS[k])
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
        return self.wrench_of({axis: sign for axis, (sign, _) in self.held.items()})

    def status_lines(self, now=None):
        """The lines the terminal shows (speeds, pendulum, VBS, wrench, held axes)."""
        held = " ".join(f"{'+' if s > 0 else '-'}{a}" for a, (s, _) in sorted(self.held.items())) or "none"
        return self.command_lines(self.wrench(now)) + [f"held axes     {held}"]


def state_from_params(get_param):
    """TeleopState from parameters read with get_param(name, default) (rospy's, with '~')."""
    return TeleopState(key_timeout=get_param("key_timeout", 0.7), **command_params(get_param))


class TeleopNode:
    """Publishers of the teleop and its curses loop (run() owns the terminal until Q or Ctrl-C)."""

    def __init__(self):
        import rospy

        from unexmin.topics import robot_param

        self.rospy = rospy
        robot = robot_param()
        self.rate = rospy.get_param("~rate", 10.0)
        if not (isinstance(self.rate, (int, float)) and 0.5 <= self.rate <= 100.0):
            raise ValueError(f"parameter ~rate = {self.rate!r}: expected [0.5, 100] Hz")
        self.state = state_from_params(lambda name, default: rospy.get_param("~" + name, default))
        self.robot = robot
        self.pubs = CommandPublishers(robot)

    def publish_wrench(self, now):
        self.pubs.wrench(self.state.wrench(now))

    def handle(self, key, now):
        changed = self.state.press(key, now)
        self.pubs.changes(changed, self.state)
        return changed

    def draw(self, screen, now):
        screen.erase()
        rows, cols = screen.getmaxyx()
        lines = [f"UNEXMIN keyboard teleop -> /{self.robot}   (thesis table 5.1)", *HELP, ""]
        lines += self.state.status_lines(now)
        if self.pubs.wrench_pub.get_num_connections() == 0:
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


def exit_on_signal(signum, frame):
    """Signal handler: unwind (finally blocks publish the zero wrench) with exit status 128 + signum."""
    raise SystemExit(128 + signum)


def main():
    """Entry point of nodes/teleop: needs a terminal; restores it on Q, Ctrl-C, SIGTERM and SIGHUP."""
    import curses

    import rospy

    if not sys.stdin.isatty():
        sys.exit('teleop: stdin is not a terminal; run it in a terminal (roslaunch: launch-prefix="xterm -e")')
    rospy.init_node("teleop", disable_signals=True)  # Ctrl-C must reach us as KeyboardInterrupt
    try:
        node = TeleopNode()
    except ValueError as e:
        sys.exit(f"teleop: {e}")
    signal.signal(signal.SIGTERM, exit_on_signal)
    signal.signal(signal.SIGHUP, exit_on_signal)
    try:
        curses.wrapper(node.run)  # wrapper restores the terminal whatever happens inside
    except KeyboardInterrupt:
        pass
    finally:
        node.stop()
        rospy.signal_shutdown("teleop closed")
    print(f"teleop: stopped ({node.state.summary()})")

"""Operator intents -> commands of a UX robot: the one place shared by the keyboard and joystick teleops.

An operator (keys or a gamepad) expresses *intents*: a deflection of a wrench axis in [-1, 1], or a
step of a speed, the pendulum or the VBS. OperatorCommands holds the speeds and the pendulum and VBS
targets and turns intents into the commands the robot takes (thesis 5.10.1, table 5.1):

- the body wrench [X Y Z K M N] for the thruster allocator: each axis deflection times the current
  speed (`linear` [N] on X, Y, Z; `angular` [N m] on K, M, N);
- the pendulum angle [rad], in whole steps of `pendulum_step` within [pendulum_min, pendulum_max];
- the VBS ballast mass [kg], in whole steps of `vbs_step` within [vbs_min, vbs_max].

CommandPublishers puts them on /<robot>/force_moments, /<robot>/pendulum and /<robot>/vbs.
No ROS is imported by this module until CommandPublishers is constructed. Parameters: docs/teleop.md.
"""

import math

#: Wrench components, body frame (REP-103: X forward, Y left, Z up; K, M, N about x, y, z).
AXES = ("X", "Y", "Z", "K", "M", "N")
LINEAR_AXES = ("X", "Y", "Z")
#: Pendulum step and limit (either side) [rad].
PENDULUM_STEP = math.radians(1.0)
PENDULUM_LIMIT = math.radians(30.0)

#: Step intents: name -> (what, sign). "speed" steps linear and angular together.
STEP_INTENTS = {
    "linear+": ("linear", +1),
    "linear-": ("linear", -1),
    "angular+": ("angular", +1),
    "angular-": ("angular", -1),
    "speed+": ("speed", +1),
    "speed-": ("speed", -1),
    "pendulum+": ("pendulum", +1),
    "pendulum-": ("pendulum", -1),
    "vbs+": ("vbs", +1),
    "vbs-": ("vbs", -1),
}

#: Defaults of the shared parameters (rospy private parameter name -> value; pendulum_step_deg in degrees).
DEFAULTS = {
    "linear": 10.0,
    "angular": 2.0,
    "linear_step": 1.0,
    "angular_step": 0.5,
    "linear_max": 80.0,
    "angular_max": 40.0,
    "pendulum_step_deg": 1.0,
    "pendulum_min": -PENDULUM_LIMIT,
    "pendulum_max": PENDULUM_LIMIT,
    "vbs_step": 0.01,
    "vbs_min": -1.0,
    "vbs_max": 1.0,
}


class OperatorCommands:
    """Speeds, pendulum and VBS of a teleop, and the wrench of a set of axis deflections. No ROS.

    linear, angular: initial wrench magnitude of a full deflection on a linear axis [N] and on a
    rotation axis [N m] (the "speeds" of table 5.1: the allocator turns them into thrust).
    linear_step, angular_step: change per speed step; linear_max, angular_max: upper limits (lower 0).
    pendulum_step: [rad] per step; pendulum_min/max: [rad] limits.
    vbs_step: [kg] per step; vbs_min/max: [kg] limits.
    """

    def __init__(
        self,
        linear=10.0,
        angular=2.0,
        linear_step=1.0,
        angular_step=0.5,
        linear_max=80.0,
        angular_max=40.0,
        pendulum_step=PENDULUM_STEP,
        pendulum_min=-PENDULUM_LIMIT,
        pendulum_max=PENDULUM_LIMIT,
        vbs_step=0.01,
        vbs_min=-1.0,
        vbs_max=1.0,
    ):
        checks = (
            ("linear_step", linear_step),
            ("angular_step", angular_step),
            ("linear_max", linear_max),
            ("angular_max", angular_max),
            ("pendulum_step", pendulum_step),
            ("vbs_step", vbs_step),
        )
        for name, value in checks:
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                raise ValueError(f"parameter ~{name} = {value!r}: expected a finite number > 0")
        for name, value, top in (("linear", linear, linear_max), ("angular", angular, angular_max)):
            if not (isinstance(value, (int, float)) and 0 <= value <= top):
                raise ValueError(f"parameter ~{name} = {value!r}: expected a number in [0, {top}] (~{name}_max)")
        for name, lo, hi in (("pendulum", pendulum_min, pendulum_max), ("vbs", vbs_min, vbs_max)):
            if not (math.isfinite(lo) and math.isfinite(hi) and lo <= 0.0 <= hi):
                raise ValueError(f"parameters ~{name}_min = {lo}, ~{name}_max = {hi}: expected min <= 0 <= max")
        self.linear, self.angular = float(linear), float(angular)
        self.linear_step, self.angular_step = float(linear_step), float(angular_step)
        self.linear_max, self.angular_max = float(linear_max), float(angular_max)
        self.pendulum_step, self.vbs_step = float(pendulum_step), float(vbs_step)
        self.pendulum_min, self.pendulum_max = float(pendulum_min), float(pendulum_max)
        self.vbs_min, self.vbs_max = float(vbs_min), float(vbs_max)
        # Pendulum and VBS are whole numbers of steps, so repeated steps never accumulate rounding.
        self.pendulum_steps = 0
        self.vbs_steps = 0

    @property
    def pendulum(self):
        """Pendulum target angle [rad]."""
        return self.pendulum_steps * self.pendulum_step

    @property
    def vbs(self):
        """VBS ballast mass [kg]."""
        return round(self.vbs_steps * self.vbs_step, 9)

    def _speed(self, what, sign):
        if what == "linear":
            self.linear = min(self.linear_max, max(0.0, round(self.linear + sign * self.linear_step, 9)))
        else:
            self.angular = min(self.angular_max, max(0.0, round(self.angular + sign * self.angular_step, 9)))

    def apply(self, intent):
        """Apply one step intent (a key of STEP_INTENTS). Returns what changed: a set of 'speed' and
        'wrench' (a speed step), 'pendulum' or 'vbs'; empty when a limit stops a pendulum or VBS step."""
        if intent not in STEP_INTENTS:
            raise ValueError(f"intent {intent!r}: expected one of {', '.join(STEP_INTENTS)}")
        what, sign = STEP_INTENTS[intent]
        if what in ("linear", "angular", "speed"):
            for kind in ("linear", "angular") if what == "speed" else (what,):
                self._speed(kind, sign)
            return {"speed", "wrench"}
        step, lo, hi = (
            (self.pendulum_step, self.pendulum_min, self.pendulum_max)
            if what == "pendulum"
            else (self.vbs_step, self.vbs_min, self.vbs_max)
        )
        n = getattr(self, what + "_steps") + sign
        if lo - 1e-12 <= n * step <= hi + 1e-12:
            setattr(self, what + "_steps", n)
            return {what}
        return set()

    def wrench_of(self, deflections):
        """[X Y Z K M N] ([N], [N m]) of axis deflections {axis: value in [-1, 1]} times the current speeds."""
        w = [0.0] * 6
        for axis, value in deflections.items():
            w[AXES.index(axis)] = value * (self.linear if axis in LINEAR_AXES else self.angular)
        return w

    def command_lines(self, wrench):
        """Screen lines of the speeds, pendulum, VBS and a wrench."""
        return [
            f"linear speed  {self.linear:7.2f} N      angular speed {self.angular:7.2f} N m",
            f"pendulum      {math.degrees(self.pendulum):7.1f} deg    VBS           {self.vbs:+7.2f} kg",
            "wrench        X {:+.2f}  Y {:+.2f}  Z {:+.2f}  K {:+.2f}  M {:+.2f}  N {:+.2f}".format(*wrench),
        ]

    def summary(self):
        """One line of the final state (printed when a teleop stops)."""
        return (
            f"linear {self.linear:g} N, angular {self.angular:g} N m, "
            f"pendulum {math.degrees(self.pendulum):g} deg, VBS {self.vbs:g} kg"
        )


def command_params(get_param):
    """OperatorCommands keyword arguments from parameters read with get_param(name, default) (rospy's,
    with '~'), defaults DEFAULTS."""
    kwargs = {name: get_param(name, default) for name, default in DEFAULTS.items() if name != "pendulum_step_deg"}
    kwargs["pendulum_step"] = math.radians(get_param("pendulum_step_deg", DEFAULTS["pendulum_step_deg"]))
    return kwargs


class CommandPublishers:
    """The command topics of one robot: /<robot>/force_moments (geometry_msgs/Wrench, body frame),
    /<robot>/pendulum and /<robot>/vbs (std_msgs/Float64, latched). Synchronous publishers: a node's
    final zero wrench is on the wire before it exits."""

    def __init__(self, robot):
        from geometry_msgs.msg import Wrench
        from std_msgs.msg import Float64

        from unexmin.topics import sync_publisher

        self.Wrench, self.Float64 = Wrench, Float64
        self.wrench_pub = sync_publisher(f"/{robot}/force_moments", Wrench)
        self.pendulum_pub = sync_publisher(f"/{robot}/pendulum", Float64, latch=True)
        self.vbs_pub = sync_publisher(f"/{robot}/vbs", Float64, latch=True)
        self.last_wrench = None

    def wrench(self, w):
        """Publish [X Y Z K M N] ([N], [N m])."""
        msg = self.Wrench()
        msg.force.x, msg.force.y, msg.force.z = w[:3]
        msg.torque.x, msg.torque.y, msg.torque.z = w[3:]
        self.wrench_pub.publish(msg)
        self.last_wrench = list(w)

    def changes(self, changed, commands):
        """Publish the pendulum and VBS targets of `commands` (OperatorCommands) named in `changed`."""
        if "pendulum" in changed:
            self.pendulum_pub.publish(self.Float64(commands.pendulum))
        if "vbs" in changed:
            self.vbs_pub.publish(self.Float64(commands.vbs))

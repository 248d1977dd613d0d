"""Joystick teleoperation of a UX robot (the thesis's "keyboard or joystick", 5.10), from a Linux joystick.

Reads the kernel joystick API (/dev/input/jsN, linux/joystick.h) with the standard library: a stream of
8-byte little-endian records struct js_event {u32 time [ms]; s16 value; u8 type; u8 number}, type
JS_EVENT_BUTTON (0x01) or JS_EVENT_AXIS (0x02), or-ed with JS_EVENT_INIT (0x80) for the synthetic
events that give the initial state when the device is opened. Axis values run from -32767 to 32767
(a stick pushed up or left is negative), buttons are 0 or 1.

Publishes the pad as sensor_msgs/Joy on `joy` (relative to the node's namespace, so other tools can
use it) and the same commands as the keyboard teleop, through unexmin.control.operator_commands:
/<robot>/force_moments (body wrench: stick deflections past a dead zone times the speeds, only while
the dead-man button is held), /<robot>/pendulum and /<robot>/vbs (buttons step them). The axis and
button mapping is a YAML file (config/joystick.yaml: a common gamepad layout).

Safety: the wrench is zero at once when the device reads EOF or an error (ENODEV: unplugged), and
within ~timeout when it stops sending and cannot confirm it is still there; the node then tries to
reopen the device every ~reopen_period and carries on when it is back. A device that cannot be opened
at start-up is one error line and exit status 1.

JoystickState below is the logic without ROS (unit-tested); JoystickDevice reads the device;
JoystickNode adds the publishers and the loop. Parameters: docs/teleop.md.
"""

import errno
import fcntl
import math
import os
import select
import signal
import struct
import sys
import time

from unexmin.control.operator_commands import AXES, STEP_INTENTS, CommandPublishers, OperatorCommands, command_params
from unexmin.control.teleop import exit_on_signal

#: struct js_event of linux/joystick.h: u32 time [ms], s16 value, u8 type, u8 number (little-endian).
EVENT = struct.Struct("<IhBB")
JS_EVENT_BUTTON, JS_EVENT_AXIS, JS_EVENT_INIT = 0x01, 0x02, 0x80
#: Full deflection of an axis.
AXIS_MAX = 32767.0
#: ioctls of linux/joystick.h: _IOR('j', 0x01, __u32), _IOR('j', 0x11, __u8), _IOR('j', 0x12, __u8).
JSIOCGVERSION, JSIOCGAXES, JSIOCGBUTTONS = 0x80046A01, 0x80016A11, 0x80016A12


def pack_event(time_ms, value, kind, number):
    """One js_event record (8 bytes): time [ms], value (-32767..32767 or 0/1), kind (type), number."""
    return EVENT.pack(int(time_ms) & 0xFFFFFFFF, int(value), int(kind), int(number))


def unpack_events(data):
    """(list of (time_ms, value, kind, number), the bytes of an incomplete trailing record)."""
    whole = len(data) - len(data) % EVENT.size
    return list(EVENT.iter_unpack(data[:whole])), data[whole:]


def apply_dead_zone(value, dead_zone):
    """An axis value in [-1, 1] with a dead zone: 0 within ±dead_zone, then rescaled linearly so the
    output is continuous and reaches ±1 at full deflection: sign(v)·(|v| − dz)/(1 − dz)."""
    value = max(-1.0, min(1.0, value))
    if abs(value) <= dead_zone:
        return 0.0
    return math.copysign((abs(value) - dead_zone) / (1.0 - dead_zone), value)


class JoystickMapping:
    """Which pad axis drives which wrench component and which button does which intent.

    axes: {component (X Y Z K M N): (axis number, scale)}: deflection = scale · value/32767 (a scale of −1
    makes a stick pushed up, negative on Linux, a positive command); |scale| <= 1.
    buttons: {intent (unexmin.control.operator_commands.STEP_INTENTS): button number}.
    dead_zone: fraction of full deflection in [0, 1) read as zero. deadman_button: the button that must
    be held for any wrench, or -1 for none.
    """

    def __init__(self, axes, buttons, dead_zone=0.1, deadman_button=-1, source="mapping"):
        self.source = source
        if not isinstance(axes, dict):
            raise ValueError(f"{source}: 'axes' = {axes!r}: expected a map of X Y Z K M N to {{axis, scale}}")
        if not isinstance(buttons, dict):
            raise ValueError(f"{source}: 'buttons' = {buttons!r}: expected a map of intents to button numbers")
        self.axes = {}
        for component, spec in axes.items():
            if component not in AXES:
                raise ValueError(f"{source}: axes.{component}: expected one of {' '.join(AXES)}")
            if not (isinstance(spec, dict) and set(spec) <= {"axis", "scale"} and "axis" in spec):
                raise ValueError(f"{source}: axes.{component} = {spec!r}: expected {{axis: N, scale: S}}")
            number, scale = spec["axis"], spec.get("scale", 1.0)
            if not (isinstance(number, int) and 0 <= number <= 255):
                raise ValueError(f"{source}: axes.{component}.axis = {number!r}: expected an integer in [0, 255]")
            if not (isinstance(scale, (int, float)) and math.isfinite(scale) and 0 < abs(scale) <= 1):
                raise ValueError(f"{source}: axes.{component}.scale = {scale!r}: expected 0 < |scale| <= 1")
            self.axes[component] = (number, float(scale))
        self.buttons = {}
        for intent, number in buttons.items():
            if intent not in STEP_INTENTS:
                raise ValueError(f"{source}: buttons.{intent}: expected one of {', '.join(STEP_INTENTS)}")
            if not (isinstance(number, int) and 0 <= number <= 255):
                raise ValueError(f"{source}: buttons.{intent} = {number!r}: expected an integer in [0, 255]")
            self.buttons[intent] = number
        if not (isinstance(dead_zone, (int, float)) and 0 <= dead_zone < 1):
            raise ValueError(f"{source}: dead_zone = {dead_zone!r}: expected a fraction in [0, 1)")
        if not (isinstance(deadman_button, int) and -1 <= deadman_button <= 255):
            raise ValueError(f"{source}: deadman_button = {deadman_button!r}: expected a button number or -1")
        if deadman_button >= 0 and deadman_button in self.buttons.values():
            raise ValueError(f"{source}: deadman_button = {deadman_button} is also mapped to an intent")
        self.dead_zone, self.deadman_button = float(dead_zone), deadman_button

    @classmethod
    def load(cls, path):
        """The mapping of a YAML file (keys axes, buttons, dead_zone, deadman_button); ValueError names
        the file and the entry."""
        import yaml

        try:
            with open(path) as f:
                doc = yaml.safe_load(f)
        except (OSError, yaml.YAMLError) as e:
            raise ValueError(f"joystick mapping {path}: {e}") from None
        if not isinstance(doc, dict) or not set(doc) <= {"axes", "buttons", "dead_zone", "deadman_button"}:
            raise ValueError(
                f"joystick mapping {path}: expected a map with axes, buttons, dead_zone, "
                f"deadman_button, got {doc!r:.80}"
            )
        return cls(
            doc.get("axes", {}),
            doc.get("buttons", {}),
            doc.get("dead_zone", 0.1),
            doc.get("deadman_button", -1),
            source=f"joystick mapping {path}",
        )


class JoystickState(OperatorCommands):
    """The pad's axes and buttons over the shared OperatorCommands (speeds, pendulum, VBS). No ROS.

    mapping: a JoystickMapping; the other arguments are OperatorCommands's (speeds, steps and limits).
    """

    def __init__(self, mapping, **commands):
        super().__init__(**commands)
        self.mapping = mapping
        self.axes = {}  # axis number -> value in [-1, 1]
        self.buttons = {}  # button number -> 0/1
        self.axis_count = self.button_count = 0
        self._intents = {number: intent for intent, number in mapping.buttons.items()}

    def event(self, value, kind, number):
        """Apply one js_event. Returns what changed: 'joy', and 'wrench', 'speed', 'pendulum', 'vbs'.
        An init event (kind | 0x80) sets the state without stepping anything (a button held when the
        device is opened is not a press)."""
        init = bool(kind & JS_EVENT_INIT)
        kind &= ~JS_EVENT_INIT
        if kind == JS_EVENT_AXIS:
            self.axes[number] = max(-1.0, min(1.0, value / AXIS_MAX))
            self.axis_count = max(self.axis_count, number + 1)
            return {"joy", "wrench"}
        if kind != JS_EVENT_BUTTON:
            return set()
        pressed = 1 if value else 0
        was = self.buttons.get(number, 0)
        self.buttons[number] = pressed
        self.button_count = max(self.button_count, number + 1)
        changed = {"joy"}
        if number == self.mapping.deadman_button:
            changed.add("wrench")
        elif pressed and not was and not init and number in self._intents:
            changed |= self.apply(self._intents[number])
        return changed

    def release(self):
        """Forget every axis and button (the device is gone): the wrench is zero until new events."""
        self.axes.clear()
        self.buttons.clear()

    def deflections(self):
        """{component: deflection in [-1, 1]} of the mapped axes, dead zone applied."""
        return {
            c: apply_dead_zone(scale * self.axes.get(n, 0.0), self.mapping.dead_zone)
            for c, (n, scale) in self.mapping.axes.items()
        }

    def deadman(self):
        """True when the wrench may be non-zero (the dead-man button is held, or there is none)."""
        return self.mapping.deadman_button < 0 or self.buttons.get(self.mapping.deadman_button, 0) == 1

    def wrench(self):
        """[X Y Z K M N] ([N], [N m]) commanded now: zero unless the dead-man button is held."""
        return self.wrench_of(self.deflections()) if self.deadman() else [0.0] * 6

    def joy_arrays(self):
        """(axes, buttons) of a sensor_msgs/Joy: every axis in [-1, 1] (no dead zone) and button 0/1."""
        return (
            [self.axes.get(i, 0.0) for i in range(self.axis_count)],
            [self.buttons.get(i, 0) for i in range(self.button_count)],
        )


class DeviceLost(Exception):
    """The joystick device read EOF or an error (unplugged: ENODEV)."""


class JoystickDevice:
    """A joystick device (or anything yielding js_event records: a FIFO, a file) opened non-blocking."""

    def __init__(self, path):
        self.path = path
        self.fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
        self.rest = b""
        self.axis_count = self._ioctl_u8(JSIOCGAXES)
        self.button_count = self._ioctl_u8(JSIOCGBUTTONS)

    def _ioctl_u8(self, request):
        try:
            return fcntl.ioctl(self.fd, request, b"\0")[0]
        except OSError:
            return 0  # not a joystick device (a FIFO in the tests): the counts grow with the events

    def read(self):
        """Every complete record available now, as (time_ms, value, kind, number); DeviceLost on EOF or error."""
        try:
            data = os.read(self.fd, 64 * EVENT.size)
        except BlockingIOError:
            return []
        except OSError as e:
            raise DeviceLost(f"{self.path}: {os.strerror(e.errno)}") from None
        if not data:
            raise DeviceLost(f"{self.path}: end of file")
        events, self.rest = unpack_events(self.rest + data)
        return events

    def alive(self):
        """True when the kernel confirms the joystick is there (JSIOCGVERSION answers), False when the
        device cannot tell (not a joystick device: only events show it is alive); DeviceLost when gone."""
        try:
            fcntl.ioctl(self.fd, JSIOCGVERSION, b"\0\0\0\0")
            return True
        except OSError as e:
            if e.errno in (errno.ENODEV, errno.EIO, errno.EBADF):
                raise DeviceLost(f"{self.path}: {os.strerror(e.errno)}") from None
            return False

    def close(self):
        if self.fd is not None:
            os.close(self.fd)
            self.fd = None


class JoystickNode:
    """Publishers of the joystick teleop and its loop (run() until shutdown or stop)."""

    def __init__(self, device):
        import rospkg
        import rospy
        from sensor_msgs.msg import Joy

        from unexmin.topics import robot_param, sync_publisher

        self.rospy, self.Joy = rospy, Joy
        self.robot = robot_param()
        default_mapping = os.path.join(rospkg.RosPack().get_path("unexmin"), "config", "joystick.yaml")
        mapping = JoystickMapping.load(rospy.get_param("~mapping", default_mapping))
        params = (
            ("rate", 10.0, 0.5, 100.0, "Hz"),
            ("timeout", 0.5, 0.05, 10.0, "s"),
            ("reopen_period", 1.0, 0.05, 60.0, "s"),
        )
        for name, default, lo, hi, unit in params:
            value = rospy.get_param("~" + name, default)
            if not (isinstance(value, (int, float)) and lo <= value <= hi):
                raise ValueError(f"parameter ~{name} = {value!r}: expected [{lo}, {hi}] {unit}")
            setattr(self, name, float(value))
        self.state = JoystickState(
            mapping, **command_params(lambda name, default: rospy.get_param("~" + name, default))
        )
        self.device = device
        self.path = device.path
        self.state.axis_count, self.state.button_count = device.axis_count, device.button_count
        self.pubs = CommandPublishers(self.robot)
        self.joy_pub = sync_publisher("joy", Joy)
        self.last_alive = time.monotonic()
        self.connected = True
        self.stopped = False

    def publish_joy(self):
        msg = self.Joy()
        msg.header.stamp = self.rospy.Time.now()
        msg.axes, msg.buttons = self.state.joy_arrays()
        self.joy_pub.publish(msg)

    def lose(self, why):
        """The device is gone (or silent): zero wrench now, forget its state, reopen later."""
        if self.connected:
            self.rospy.logerr(f"joystick: lost {why}; wrench zeroed, reopening every {self.reopen_period:g} s")
        self.connected = False
        if self.device is not None:
            self.device.close()
            self.device = None
        self.state.release()
        self.pubs.wrench([0.0] * 6)
        self.publish_joy()

    def reopen(self):
        try:
            self.device = JoystickDevice(self.path)
        except OSError:
            self.device = None
            return
        self.last_alive = time.monotonic()

    def events(self, records):
        changed = set()
        for _, value, kind, number in records:
            changed |= self.state.event(value, kind, number)
        if records and not self.connected:
            self.connected = True
            self.rospy.loginfo(f"joystick: {self.path} is back")
        return changed

    def run(self):
        period = 1.0 / self.rate
        next_pub = next_reopen = time.monotonic()
        while not self.stopped and not self.rospy.is_shutdown():
            now = time.monotonic()
            if self.device is None and now >= next_reopen:
                self.reopen()
                next_reopen = now + self.reopen_period
            deadline = (
                min(next_pub, next_reopen) if self.device is None else min(next_pub, self.last_alive + self.timeout)
            )
            wait = max(0.0, deadline - now)
            changed = set()
            if self.device is None:
                time.sleep(wait)
            elif select.select([self.device.fd], [], [], wait)[0]:
                try:
                    records = self.device.read()
                except DeviceLost as e:
                    self.lose(str(e))
                    next_reopen = time.monotonic() + self.reopen_period
                    continue
                if records:
                    self.last_alive = time.monotonic()
                changed = self.events(records)
            now = time.monotonic()
            if self.device is not None and now - self.last_alive > self.timeout:
                try:
                    if self.device.alive():
                        self.last_alive = now
                    else:
                        self.lose(f"{self.path}: no event for {self.timeout:g} s")
                except DeviceLost as e:
                    self.lose(str(e))
                if self.device is None:
                    next_reopen = now + self.reopen_period
                    continue
            self.pubs.changes(changed, self.state)
            if "joy" in changed:
                self.publish_joy()
            if "wrench" in changed or now >= next_pub:
                self.pubs.wrench(self.state.wrench())
                next_pub = now + period
        self.stop()

    def stop(self):
        """Zero wrench: the robot must not keep thrusting once the operator has gone."""
        self.stopped = True
        self.state.release()
        self.pubs.wrench([0.0] * 6)
        if self.device is not None:
            self.device.close()
            self.device = None


def main():
    """Entry point of nodes/joystick: one error line and exit status 1 when ~device cannot be opened or
    a parameter is wrong; a zero wrench on Ctrl-C, SIGTERM and SIGHUP."""
    import rospy

    rospy.init_node("joystick", disable_signals=True)  # Ctrl-C must reach us as KeyboardInterrupt
    path = rospy.get_param("~device", "/dev/input/js0")
    try:
        device = JoystickDevice(path)
    except OSError as e:
        sys.exit(
            f"joystick: cannot open ~device {path}: {os.strerror(e.errno)} "
            "(is the pad plugged in? another device: _device:=/dev/input/jsN)"
        )
    try:
        node = JoystickNode(device)
    except ValueError as e:
        device.close()
        sys.exit(f"joystick: {e}")
    signal.signal(signal.SIGTERM, exit_on_signal)
    signal.signal(signal.SIGHUP, exit_on_signal)
    try:
        node.run()
    except KeyboardInterrupt:
        pass
    finally:
        node.stop()
        rospy.signal_shutdown("joystick closed")
    print(f"joystick: stopped ({node.state.summary()})")

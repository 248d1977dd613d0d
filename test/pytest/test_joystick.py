"""Joystick teleop (python/unexmin/control/joystick.py, nodes/joystick, config/joystick.yaml), without hardware.

- The logic (no ROS): js_event records, the dead zone, the shipped mapping (sticks -> wrench, buttons ->
  pendulum, VBS, speed), the dead-man button, init events, mapping errors, an unplugged device (ENODEV).
- The real node: `rosrun unexmin joystick` on a private master reads a FIFO the test writes kernel
  js_event records into (a fake /dev/input/js0); a listener records /UX_1/force_moments, /UX_1/pendulum,
  /UX_1/vbs and /joy. Stick deflections give the expected wrench (dead zone applied), buttons step the
  pendulum and VBS, EOF (the pad unplugged) and silence zero the wrench within the timeout, and a missing
  device gives one error line and exit status 1.

Run: python -m pytest test/pytest/test_joystick.py -q -p no:cacheprovider
"""

import errno
import math
import os
import shutil
import subprocess
import time
from pathlib import Path

import pytest
from test_teleop import Rig

from unexmin.control.joystick import (
    EVENT,
    JS_EVENT_AXIS,
    JS_EVENT_BUTTON,
    JS_EVENT_INIT,
    DeviceLost,
    JoystickDevice,
    JoystickMapping,
    JoystickState,
    apply_dead_zone,
    pack_event,
    unpack_events,
)
from unexmin.scripting.launcher import wait_for

MAPPING = Path(__file__).resolve().parents[2] / "config" / "joystick.yaml"
DEG = math.pi / 180.0
# The shipped layout (config/joystick.yaml): axes and buttons of an Xbox 360-style pad.
LEFT_X, LEFT_Y, RIGHT_X, RIGHT_Y = 0, 1, 3, 4
BTN_A, BTN_B, BTN_X, BTN_Y, BTN_LB, BTN_BACK, BTN_START = 0, 1, 2, 3, 4, 6, 7


def deflection(raw, dead_zone=0.1):
    """Closed form of the dead zone: |v| <= dz -> 0, else sign(v) (|v| - dz) / (1 - dz), v = raw / 32767."""
    v = raw / 32767.0
    return 0.0 if abs(v) <= dead_zone else math.copysign((abs(v) - dead_zone) / (1 - dead_zone), v)


# ---------------------------------------------------------------------------------------------
# logic
# ---------------------------------------------------------------------------------------------
def test_event_records_are_the_kernels_8_byte_little_endian_js_event():
    data = pack_event(1000, -32767, JS_EVENT_AXIS, 1)
    assert EVENT.size == 8
    assert data == bytes([0xE8, 0x03, 0x00, 0x00, 0x01, 0x80, 0x02, 0x01])  # u32 1000, s16 -32767, u8 2, u8 1
    two = pack_event(5, 1, JS_EVENT_BUTTON | JS_EVENT_INIT, 4) + data
    assert unpack_events(two + data[:3]) == ([(5, 1, 0x81, 4), (1000, -32767, 2, 1)], data[:3])


@pytest.mark.parametrize("value", [0.0, 0.05, 0.1, 0.1001, 0.3, -0.55, 0.999, 1.0, -1.0, 1.7])
def test_dead_zone_is_zero_inside_and_continuous_to_full_deflection(value):
    v = max(-1.0, min(1.0, value))
    expected = 0.0 if abs(v) <= 0.1 else math.copysign((abs(v) - 0.1) / 0.9, v)
    assert apply_dead_zone(value, 0.1) == pytest.approx(expected, abs=1e-12)


def shipped_state(**kwargs):
    return JoystickState(JoystickMapping.load(MAPPING), **kwargs)


def test_sticks_give_the_wrench_only_while_the_deadman_is_held():
    s = shipped_state(linear=10.0, angular=2.0)
    for number in range(8):
        s.event(0, JS_EVENT_AXIS | JS_EVENT_INIT, number)
    s.event(-20000, JS_EVENT_AXIS, LEFT_Y)  # left stick up: forward
    s.event(9000, JS_EVENT_AXIS, LEFT_X)  # left stick right: sway right (-Y)
    s.event(-2000, JS_EVENT_AXIS, RIGHT_Y)  # inside the dead zone: no heave
    s.event(-32767, JS_EVENT_AXIS, RIGHT_X)  # right stick full left: yaw left (+N)
    assert s.wrench() == [0.0] * 6  # dead-man (LB) not held
    assert s.event(1, JS_EVENT_BUTTON, BTN_LB) == {"joy", "wrench"}
    expected = [10.0 * deflection(20000), -10.0 * deflection(9000), 0.0, 0.0, 0.0, 2.0]
    assert s.wrench() == pytest.approx(expected, abs=1e-12)
    assert s.event(0, JS_EVENT_BUTTON, BTN_LB) == {"joy", "wrench"}
    assert s.wrench() == [0.0] * 6
    axes, buttons = s.joy_arrays()
    assert axes[LEFT_Y] == pytest.approx(-20000 / 32767) and axes[RIGHT_X] == -1.0 and buttons[BTN_LB] == 0


def test_buttons_step_pendulum_vbs_and_speed_on_the_press_edge_only():
    s = shipped_state(linear=10.0, angular=2.0, pendulum_max=2 * DEG)
    assert s.event(1, JS_EVENT_BUTTON | JS_EVENT_INIT, BTN_Y) == {"joy"}  # held at open: not a press
    assert s.pendulum_steps == 0
    s.event(0, JS_EVENT_BUTTON, BTN_Y)
    for _ in range(3):  # 3 presses, the third beyond +2 deg
        s.event(1, JS_EVENT_BUTTON, BTN_Y)
        s.event(0, JS_EVENT_BUTTON, BTN_Y)
    assert s.pendulum == pytest.approx(2 * DEG)
    assert s.event(1, JS_EVENT_BUTTON, BTN_A) == {"joy", "pendulum"}
    assert s.event(1, JS_EVENT_BUTTON, BTN_A) == {"joy"}  # still held: no repeat
    assert s.pendulum == pytest.approx(1 * DEG)
    for button, expected in ((BTN_B, 0.01), (BTN_B, 0.02), (BTN_X, 0.01)):
        assert s.event(1, JS_EVENT_BUTTON, button) == {"joy", "vbs"}
        s.event(0, JS_EVENT_BUTTON, button)
        assert s.vbs == pytest.approx(expected, abs=1e-12)
    s.event(1, JS_EVENT_BUTTON, BTN_START)
    assert (s.linear, s.angular) == (11.0, 2.5)  # speed+: both by their steps
    s.event(0, JS_EVENT_BUTTON, BTN_START)
    s.event(1, JS_EVENT_BUTTON, BTN_BACK)
    assert (s.linear, s.angular) == (10.0, 2.0)


@pytest.mark.parametrize(
    "doc, name",
    [
        ({"axes": {"Q": {"axis": 1}}}, "axes.Q"),
        ({"axes": {"X": {"axis": -1}}}, "axes.X.axis"),
        ({"axes": {"X": {"axis": 1, "scale": 3}}}, "axes.X.scale"),
        ({"buttons": {"jump": 1}}, "buttons.jump"),
        ({"dead_zone": 1.0}, "dead_zone"),
        ({"buttons": {"vbs+": 4}, "deadman_button": 4}, "deadman_button"),
        ({"axis": {}}, "expected a map with axes"),
    ],
)
def test_bad_mappings_name_the_file_and_the_entry(tmp_path, doc, name):
    import yaml

    path = tmp_path / "pad.yaml"
    path.write_text(yaml.safe_dump(doc))
    with pytest.raises(ValueError, match=name) as info:
        JoystickMapping.load(path)
    assert str(path) in str(info.value)


def test_an_unplugged_device_is_lost(tmp_path, monkeypatch):
    fifo = tmp_path / "js0"
    os.mkfifo(fifo)
    writer = os.open(fifo, os.O_RDWR)
    try:
        dev = JoystickDevice(str(fifo))
        assert dev.read() == []  # nothing yet: not lost
        os.write(writer, pack_event(1, 5, JS_EVENT_AXIS, 2) + pack_event(2, 1, JS_EVENT_BUTTON, 0)[:5])
        assert dev.read() == [(1, 5, JS_EVENT_AXIS, 2)]  # a partial record waits for its end
        os.write(writer, pack_event(2, 1, JS_EVENT_BUTTON, 0)[5:])
        assert dev.read() == [(2, 1, JS_EVENT_BUTTON, 0)]
        assert dev.alive() is False  # a FIFO cannot confirm: only events do

        def unplugged(fd, n):
            raise OSError(errno.ENODEV, os.strerror(errno.ENODEV))

        monkeypatch.setattr("unexmin.control.joystick.os.read", unplugged)
        with pytest.raises(DeviceLost, match="No such device"):
            dev.read()
        dev.close()
    finally:
        os.close(writer)


# ---------------------------------------------------------------------------------------------
# the node on a FIFO
# ---------------------------------------------------------------------------------------------
class Pad:
    """A fake /dev/input/js0: a FIFO the test writes js_event records into (held open read-write, so the
    node sees EOF only when unplug() closes it)."""

    def __init__(self, path):
        self.path = path
        os.mkfifo(path)
        self.fd = os.open(path, os.O_RDWR)
        self.t0 = time.monotonic()

    def send(self, *events):
        ms = int((time.monotonic() - self.t0) * 1000)
        os.write(self.fd, b"".join(pack_event(ms, value, kind, number) for value, kind, number in events))

    def plug_in(self):
        """The init events the kernel sends on open: 8 centred axes, 11 released buttons."""
        self.send(
            *[(0, JS_EVENT_AXIS | JS_EVENT_INIT, n) for n in range(8)],
            *[(0, JS_EVENT_BUTTON | JS_EVENT_INIT, n) for n in range(11)],
        )

    def unplug(self):
        os.close(self.fd)
        self.fd = None


@pytest.fixture
def rig(tmp_path):
    for tool in ("rosmaster", "rosrun"):
        if not shutil.which(tool):
            pytest.skip(f"{tool} not installed")
    r = Rig(tmp_path)
    try:
        yield r
    finally:
        r.close()


def start_joystick(rig, pad, *params):
    proc = subprocess.Popen(
        ["rosrun", "unexmin", "joystick", f"_device:={pad.path}", *params],
        env=rig.env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    rig.procs.append(proc)
    rig.wait_message("wrench", [0.0] * 6, 0, timeout=30)  # up and publishing at ~rate
    return proc


def test_sticks_and_buttons_drive_the_commands(rig, tmp_path):
    pad = Pad(tmp_path / "js0")
    start_joystick(rig, pad, "_timeout:=5")
    pad.plug_in()
    n = len(rig.messages("wrench"))
    pad.send((-16384, JS_EVENT_AXIS, LEFT_Y), (-32767, JS_EVENT_AXIS, RIGHT_X))
    # no dead-man yet: the wrench stays zero, but /joy shows the sticks
    wait_for(
        lambda: any(r["data"][0][LEFT_Y] == pytest.approx(-16384 / 32767) for r in rig.messages("joy")),
        10,
        "/joy with the left stick up",
    )
    assert all(r["data"] == [0.0] * 6 for r in rig.messages("wrench")[n:])
    pad.send((1, JS_EVENT_BUTTON, BTN_LB))
    rig.wait_message("wrench", [10.0 * deflection(16384), 0, 0, 0, 0, 2.0], n)
    n = len(rig.messages("wrench"))
    pad.send((12000, JS_EVENT_AXIS, LEFT_X), (1000, JS_EVENT_AXIS, RIGHT_X), (-30000, JS_EVENT_AXIS, RIGHT_Y))
    rig.wait_message(
        "wrench", [10.0 * deflection(16384), -10.0 * deflection(12000), 10.0 * deflection(30000), 0, 0, 0.0], n
    )  # right stick x 1000/32767 = 0.03: in the dead zone
    for button, expected in ((BTN_Y, 1), (BTN_Y, 2), (BTN_A, 1)):
        n = len(rig.messages("pendulum"))
        pad.send((1, JS_EVENT_BUTTON, button), (0, JS_EVENT_BUTTON, button))
        rig.wait_message("pendulum", expected * DEG, n)
    for button, expected in ((BTN_B, 0.01), (BTN_B, 0.02), (BTN_X, 0.01)):
        n = len(rig.messages("vbs"))
        pad.send((1, JS_EVENT_BUTTON, button), (0, JS_EVENT_BUTTON, button))
        rig.wait_message("vbs", expected, n)
    n = len(rig.messages("wrench"))
    pad.send((1, JS_EVENT_BUTTON, BTN_START))  # speed+: linear 11 N
    rig.wait_message(
        "wrench", [11.0 * deflection(16384), -11.0 * deflection(12000), 11.0 * deflection(30000), 0, 0, 0], n
    )
    n = len(rig.messages("wrench"))
    pad.send((0, JS_EVENT_BUTTON, BTN_LB))  # dead-man released
    rig.wait_message("wrench", [0.0] * 6, n)


def test_unplugging_zeroes_the_wrench_at_once(rig, tmp_path):
    pad = Pad(tmp_path / "js0")
    proc = start_joystick(rig, pad, "_timeout:=5")
    pad.plug_in()
    n = len(rig.messages("wrench"))
    pad.send((1, JS_EVENT_BUTTON, BTN_LB), (-32767, JS_EVENT_AXIS, LEFT_Y))
    rig.wait_message("wrench", [10.0, 0, 0, 0, 0, 0], n)
    n = len(rig.messages("wrench"))
    unplugged = time.monotonic()
    pad.unplug()  # EOF
    zero = rig.wait_message("wrench", [0.0] * 6, n, timeout=5)
    assert zero["t"] - unplugged < 1.0  # not the 5 s timeout
    assert proc.poll() is None  # it waits for the pad


def test_a_silent_device_zeroes_the_wrench_within_the_timeout(rig, tmp_path):
    pad = Pad(tmp_path / "js0")
    start_joystick(rig, pad, "_timeout:=0.5")
    pad.plug_in()
    n = len(rig.messages("wrench"))
    pad.send((1, JS_EVENT_BUTTON, BTN_LB), (32767, JS_EVENT_AXIS, RIGHT_Y))
    last_event = time.monotonic()
    on = rig.wait_message("wrench", [0, 0, -10.0, 0, 0, 0], n)
    zero = rig.wait_message("wrench", [0.0] * 6, rig.messages("wrench").index(on) + 1, timeout=5)
    assert 0.4 < zero["t"] - last_event < 0.5 + 0.1 + 0.3  # timeout + one period + transport


def test_a_missing_device_is_one_error_line_and_a_failure(rig, tmp_path):
    missing = tmp_path / "no_such_js0"
    res = subprocess.run(
        ["rosrun", "unexmin", "joystick", f"_device:={missing}"],
        env=rig.env,
        capture_output=True,
        text=True,
        timeout=60,
    )
    lines = [ln for ln in res.stderr.splitlines() if ln.strip()]
    assert res.returncode == 1
    assert len(lines) == 1, res.stderr
    assert str(missing) in lines[0] and "No such file or directory" in lines[0]


# ---------------------------------------------------------------------------------------------
# teleop:= on the world launch files (roslaunch --nodes / --dump-params: no master needed)
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("launch_file", ["tank_world.launch", "mine_world.launch"])
@pytest.mark.parametrize("teleop, node", [("joystick", "/UX_1/joystick"), ("keyboard", "/UX_1/teleop"), ("none", None)])
def test_the_teleop_argument_starts_one_teleop_for_ux_1(launch_file, teleop, node):
    out = subprocess.run(
        ["roslaunch", "--nodes", "unexmin", launch_file, f"teleop:={teleop}"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert out.returncode == 0, out.stderr
    teleops = {n for n in out.stdout.split() if n in ("/UX_1/joystick", "/UX_1/teleop")}
    assert teleops == ({node} if node else set())


def test_the_joystick_device_argument_and_a_bad_teleop_value():
    import yaml

    out = subprocess.run(
        [
            "roslaunch",
            "--dump-params",
            "unexmin",
            "tank_world.launch",
            "teleop:=joystick",
            "joystick_device:=/dev/input/js3",
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert out.returncode == 0, out.stderr
    params = yaml.safe_load(out.stdout)
    assert params["/UX_1/joystick/device"] == "/dev/input/js3"
    assert params["/UX_1/joystick/mapping"].endswith("/config/joystick.yaml")
    bad = subprocess.run(
        ["roslaunch", "--nodes", "unexmin", "tank_world.launch", "teleop:=mouse"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert bad.returncode != 0
    assert "teleop_must_be_keyboard_joystick_or_none" in bad.stdout + bad.stderr

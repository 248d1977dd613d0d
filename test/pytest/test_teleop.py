"""Keyboard teleop (python/unexmin/control/teleop.py, nodes/teleop): thesis table 5.1.

- TeleopState (no ROS, no terminal): every key of the table, limits, the hold timeout.
- The real node in a real terminal: tmux (a private server) runs `rosrun unexmin teleop` on a private
  master; keys are typed with send-keys; a listener process records /UX_1/force_moments,
  /UX_1/pendulum and /UX_1/vbs; the screen is read with capture-pane; after Q or Ctrl-C the
  terminal's settings (stty) must be back to canonical mode with echo.

Run: /work/main_ws/venv/bin/python -m pytest test/pytest/test_teleop.py
"""

import json
import math
import os
import shutil
import subprocess
import sys
import textwrap
import xmlrpc.client

import pytest

from unexmin.control.teleop import MOVE_KEYS, TeleopState
from unexmin.scripting.launcher import free_port, wait_for

DEG = math.pi / 180.0


# ---------------------------------------------------------------------------------------------
# TeleopState
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "key, index, sign",
    [
        ("w", 2, +1),
        ("s", 2, -1),
        ("i", 0, +1),
        ("k", 0, -1),
        ("j", 1, +1),
        ("l", 1, -1),
        ("a", 5, -1),
        ("d", 5, +1),
        ("W", 2, +1),
        ("D", 5, +1),
    ],
)
def test_movement_keys_follow_table_5_1(key, index, sign):
    s = TeleopState(linear=10.0, angular=2.0, key_timeout=0)
    assert s.press(key, 0.0) == {"wrench"}
    expected = [0.0] * 6
    expected[index] = sign * (10.0 if index < 3 else 2.0)
    assert s.wrench(100.0) == expected


def test_keys_on_different_axes_combine_and_the_opposite_key_replaces():
    s = TeleopState(linear=10.0, angular=2.0, key_timeout=0)
    for k in "iwd":
        s.press(k, 0.0)
    assert s.wrench() == [10.0, 0.0, 10.0, 0.0, 0.0, 2.0]
    s.press("k", 0.0)
    assert s.wrench() == [-10.0, 0.0, 10.0, 0.0, 0.0, 2.0]
    s.press(" ", 0.0)
    assert s.wrench() == [0.0] * 6


def test_speed_keys_change_the_wrench_magnitude_within_limits():
    s = TeleopState(
        linear=10.0, angular=2.0, linear_step=1.0, angular_step=0.5, linear_max=12.0, angular_max=3.0, key_timeout=0
    )
    s.press("i", 0.0)
    s.press("d", 0.0)
    for _ in range(5):
        s.press("z", 0.0)
        s.press("c", 0.0)
    assert (s.linear, s.angular) == (12.0, 3.0)  # clamped at the maxima
    assert s.wrench() == [12.0, 0, 0, 0, 0, 3.0]
    for _ in range(30):
        s.press("x", 0.0)
        s.press("v", 0.0)
    assert (s.linear, s.angular) == (0.0, 0.0)  # and at zero
    assert s.wrench() == [0.0] * 6


def test_pendulum_steps_one_degree_and_stops_at_its_limits():
    s = TeleopState(pendulum_min=-3 * DEG, pendulum_max=2 * DEG)
    assert s.press("e", 0.0) == {"pendulum"}
    assert s.pendulum == pytest.approx(1 * DEG, abs=1e-15)
    s.press("e", 0.0)
    assert s.press("e", 0.0) == set()  # 3 deg > max: ignored
    assert s.pendulum == pytest.approx(2 * DEG)
    for _ in range(10):
        s.press("r", 0.0)
    assert s.pendulum == pytest.approx(-3 * DEG)
    # 200 presses up and down come back to exactly zero (whole steps, no drift)
    s = TeleopState(pendulum_min=-math.pi, pendulum_max=math.pi)
    for _ in range(100):
        s.press("e", 0.0)
    for _ in range(100):
        s.press("r", 0.0)
    assert s.pendulum == 0.0


def test_vbs_steps_ten_grams_and_stops_at_its_limits():
    s = TeleopState(vbs_min=-0.02, vbs_max=0.03)
    for _ in range(5):
        s.press("y", 0.0)
    assert s.vbs == pytest.approx(0.03)
    for _ in range(9):
        s.press("u", 0.0)
    assert s.vbs == pytest.approx(-0.02)
    assert s.press("u", 0.0) == set()


def test_a_movement_key_holds_its_axis_for_key_timeout():
    s = TeleopState(linear=10.0, key_timeout=0.7)
    s.press("i", 5.0)
    assert s.wrench(5.69) == [10.0, 0, 0, 0, 0, 0]
    s.press("i", 5.6)  # auto-repeat of a held key re-arms it
    assert s.wrench(6.29) == [10.0, 0, 0, 0, 0, 0]
    assert s.wrench(6.3) == [0.0] * 6


def test_quit_and_unknown_keys():
    s = TeleopState()
    assert s.press("?", 0.0) == set() and not s.quit
    assert s.press("Q", 0.0) == {"quit"} and s.quit


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"linear": -1.0}, "linear"),
        ({"linear": 100.0}, "linear"),
        ({"angular_step": 0}, "angular_step"),
        ({"vbs_min": 0.5}, "vbs_min"),
        ({"pendulum_max": -0.1}, "pendulum"),
        ({"key_timeout": float("nan")}, "key_timeout"),
    ],
)
def test_bad_parameters_are_named(kwargs, name):
    with pytest.raises(ValueError, match=name):
        TeleopState(**kwargs)


def test_screen_lines_show_speeds_pendulum_and_vbs():
    s = TeleopState(key_timeout=0)
    for k in "eeyyyi":
        s.press(k, 0.0)
    text = "\n".join(s.status_lines())
    assert "linear speed    10.00 N" in text and "angular speed    2.00 N m" in text
    assert "pendulum          2.0 deg" in text and "VBS             +0.03 kg" in text
    assert "X +10.00" in text
    assert set(MOVE_KEYS) == set("wsadikjl")


# ---------------------------------------------------------------------------------------------
# the node in tmux
# ---------------------------------------------------------------------------------------------
LISTENER = textwrap.dedent("""
    import json, sys, time
    import rospy
    from geometry_msgs.msg import Wrench
    from sensor_msgs.msg import Joy
    from std_msgs.msg import Float64
    out = open(sys.argv[1], "a", buffering=1)
    def rec(topic, data):
        out.write(json.dumps({"topic": topic, "data": data, "t": time.monotonic()}) + "\\n")
    rospy.init_node("teleop_listener")
    rospy.Subscriber("/UX_1/force_moments", Wrench, lambda m: rec("wrench", [m.force.x, m.force.y, m.force.z,
                     m.torque.x, m.torque.y, m.torque.z]), queue_size=100)
    rospy.Subscriber("/UX_1/pendulum", Float64, lambda m: rec("pendulum", m.data), queue_size=100)
    rospy.Subscriber("/UX_1/vbs", Float64, lambda m: rec("vbs", m.data), queue_size=100)
    rospy.Subscriber("/joy", Joy, lambda m: rec("joy", [list(m.axes), list(m.buttons)]), queue_size=100)
    rec("ready", None)
    rospy.spin()
""")


class Rig:
    """A private master, a listener (of the three command topics and /joy, for test_joystick.py too) and a
    private tmux server; everything is stopped in close()."""

    def __init__(self, tmp_path):
        self.tmp = tmp_path
        self.port = free_port()
        self.env = dict(
            os.environ,
            ROS_MASTER_URI=f"http://127.0.0.1:{self.port}",
            ROS_IP="127.0.0.1",
            ROS_HOME=str(tmp_path / "ros_home"),
            ROS_LOG_DIR=str(tmp_path / "ros_log"),
        )
        self.socket = f"unexmin_teleop_{os.getpid()}_{self.port}"
        self.procs = []
        self.tmux_started = False
        self.log = tmp_path / "messages.jsonl"
        self.procs.append(
            subprocess.Popen(
                ["rosmaster", "--core", "-p", str(self.port)],
                env=self.env,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )
        )
        wait_for(self._master_up, 20, "rosmaster")
        self.procs.append(
            subprocess.Popen(
                [sys.executable, "-c", LISTENER, str(self.log)],
                env=self.env,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )
        )
        wait_for(lambda: self.messages("ready"), 30, "the listener")

    def _master_up(self):
        try:
            xmlrpc.client.ServerProxy(f"http://127.0.0.1:{self.port}").getSystemState("/probe")
            return True
        except OSError:
            return False

    def tmux(self, *args, check=True):
        return subprocess.run(
            ["tmux", "-L", self.socket, *args], env=self.env, capture_output=True, text=True, check=check
        )

    def start_teleop(self, *params):
        stty = self.tmp / "stty_after.txt"
        cmd = f"rosrun unexmin teleop {' '.join(params)}; echo teleop-exit=$?; stty -a > {stty}; sleep 600"
        self.tmux(
            "new-session",
            "-d",
            "-s",
            "teleop",
            "-x",
            "110",
            "-y",
            "24",
            f"env ROS_MASTER_URI={self.env['ROS_MASTER_URI']} bash --norc --noprofile -c '{cmd}'",
        )
        self.tmux_started = True
        return stty

    def keys(self, *keys):
        self.tmux("send-keys", "-t", "teleop", *keys)

    def screen(self):
        return self.tmux("capture-pane", "-p", "-t", "teleop").stdout

    def messages(self, topic):
        if not self.log.exists():
            return []
        rows = [json.loads(ln) for ln in self.log.read_text().splitlines() if ln.strip()]
        return [r for r in rows if r["topic"] == topic]

    def wait_message(self, topic, expected, after, timeout=10.0):
        """Wait for a message on `topic` (after the first `after` ones) equal to `expected`."""

        def match():
            for r in self.messages(topic)[after:]:
                got = r["data"]
                if isinstance(expected, list) and got == pytest.approx(expected, abs=1e-9):
                    return r
                if not isinstance(expected, list) and got == pytest.approx(expected, abs=1e-12):
                    return r
            return None

        return wait_for(match, timeout, f"{topic} = {expected}")

    def close(self):
        if self.tmux_started:
            self.tmux("kill-server", check=False)
        for p in reversed(self.procs):
            p.terminate()
            try:
                p.wait(10)
            except subprocess.TimeoutExpired:
                p.kill()


@pytest.fixture
def rig(tmp_path):
    for tool in ("tmux", "rosmaster", "rosrun"):
        if not shutil.which(tool):
            pytest.skip(f"{tool} not installed")
    r = Rig(tmp_path)
    try:
        yield r
    finally:
        r.close()


def assert_terminal_restored(rig, stty):
    wait_for(lambda: stty.exists() and stty.stat().st_size > 0, 15, "the shell after teleop")
    flags = stty.read_text().split()
    assert "icanon" in flags and "echo" in flags and "-icanon" not in flags and "-echo" not in flags
    assert "teleop-exit=0" in rig.screen()


def test_every_key_publishes_the_expected_message(rig):
    stty = rig.start_teleop("_key_timeout:=0")  # latched: each axis holds until Space
    rig.wait_message("wrench", [0.0] * 6, 0, timeout=30)
    steps = [  # (key, expected wrench [X Y Z K M N]) with the default speeds 10 N / 2 N m
        ("i", [10, 0, 0, 0, 0, 0]),
        ("k", [-10, 0, 0, 0, 0, 0]),
        ("Space", [0] * 6),
        ("j", [0, 10, 0, 0, 0, 0]),
        ("l", [0, -10, 0, 0, 0, 0]),
        ("Space", [0] * 6),
        ("w", [0, 0, 10, 0, 0, 0]),
        ("s", [0, 0, -10, 0, 0, 0]),
        ("Space", [0] * 6),
        ("a", [0, 0, 0, 0, 0, -2]),
        ("d", [0, 0, 0, 0, 0, 2]),
        ("Space", [0] * 6),
        ("I", [10, 0, 0, 0, 0, 0]),
        ("z", [11, 0, 0, 0, 0, 0]),
        ("z", [12, 0, 0, 0, 0, 0]),
        ("x", [11, 0, 0, 0, 0, 0]),
        ("d", [11, 0, 0, 0, 0, 2]),
        ("c", [11, 0, 0, 0, 0, 2.5]),
        ("v", [11, 0, 0, 0, 0, 2]),
        ("v", [11, 0, 0, 0, 0, 1.5]),
        ("Space", [0] * 6),
    ]
    for key, expected in steps:
        n = len(rig.messages("wrench"))
        rig.keys(key)
        rig.wait_message("wrench", [float(v) for v in expected], n)
    for key, expected in (("e", 1), ("e", 2), ("e", 3), ("r", 2)):
        n = len(rig.messages("pendulum"))
        rig.keys(key)
        rig.wait_message("pendulum", expected * DEG, n)
    for key, expected in (("y", 0.01), ("y", 0.02), ("u", 0.01), ("Y", 0.02)):
        n = len(rig.messages("vbs"))
        rig.keys(key)
        rig.wait_message("vbs", expected, n)
    screen = rig.screen()
    assert "linear speed    11.00 N" in screen and "angular speed    1.50 N m" in screen
    assert "pendulum          2.0 deg" in screen and "VBS             +0.02 kg" in screen
    rig.keys("i")
    rig.wait_message("wrench", [11.0, 0, 0, 0, 0, 0], 0)
    n = len(rig.messages("wrench"))
    rig.keys("q")
    assert_terminal_restored(rig, stty)
    assert rig.messages("wrench")[-1]["data"] == [0.0] * 6  # the last word is a stop
    assert "teleop: stopped" in rig.screen() and len(rig.messages("wrench")) > n


def test_held_key_times_out_and_ctrl_c_restores_the_terminal(rig):
    stty = rig.start_teleop()  # default ~key_timeout 0.7 s
    rig.wait_message("wrench", [0.0] * 6, 0, timeout=30)
    n = len(rig.messages("wrench"))
    rig.keys("i")
    on = rig.wait_message("wrench", [10.0, 0, 0, 0, 0, 0], n)
    off = rig.wait_message("wrench", [0.0] * 6, rig.messages("wrench").index(on) + 1, timeout=5)
    held = off["t"] - on["t"]
    assert 0.5 < held < 1.5, held  # ~0.7 s, at the 10 Hz publishing rate
    rig.keys("C-c")
    assert_terminal_restored(rig, stty)
    assert "teleop: stopped" in rig.screen()

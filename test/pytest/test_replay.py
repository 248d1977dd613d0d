"""Rosbag mission replay (python/unexmin/replay/, nodes/replay_mission) and its sample bag.

- Pure parts (no roscore): start-frame alignment and error figures against trajectories built here
  in closed form (the angle maths: test_geometry.py); reading the shipped sample bag.
- Round trip: a bag recorded from a known command sequence in the nominal simulator
  (worlds/tools/make_sample_bag.py --nominal) replays to the recorded trajectory within 1 cm and
  0.5 deg; the shipped perturbed bag replays with a much larger error.
- Damaged bags: truncated, corrupt or missing -> one error line, exit status 2, no simulator.

Simulator runs are subprocesses (each launches its own world on a private master and closes it),
so this process never initialises rospy. Run:
    python -m pytest test/pytest/test_replay.py      (after source scripts/env.sh)
"""

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from unexmin.geometry import wrap_angle
from unexmin.replay import MOTORS_TOPIC, Mission, ReplayError, compare, read_bag, to_start_frame

REPO = Path(__file__).resolve().parents[2]
SAMPLE_BAG = REPO / "worlds" / "bags" / "ux1_tank_perturbed.bag"
MAKER = REPO / "worlds" / "tools" / "make_sample_bag.py"
G = 9.80665


def run(args, tmp_path, timeout=240):
    env = dict(
        os.environ, ROS_HOME=str(tmp_path / "ros_home"), ROS_LOG_DIR=str(tmp_path / "ros_log"), PYTHONWARNINGS="ignore"
    )
    return subprocess.run(
        [sys.executable, *map(str, args)], capture_output=True, text=True, timeout=timeout, env=env, cwd=tmp_path
    )


# ---------------------------------------------------------------------------------------------
# pure
# ---------------------------------------------------------------------------------------------
def helix(t, x0=0.0, y0=0.0, z0=0.0, yaw0=0.0):
    """A trajectory in closed form: forward at 0.2 m/s while turning at 0.1 rad/s and sinking 0.01 m/s."""
    yaw = yaw0 + 0.1 * t
    x = x0 + 2.0 * (np.sin(yaw) - math.sin(yaw0))
    y = y0 - 2.0 * (np.cos(yaw) - math.cos(yaw0))
    return np.column_stack([t, x, y, z0 - 0.01 * t, 0 * t, 0 * t, wrap_angle(yaw)])


def test_alignment_removes_start_pose_and_error_is_zero_for_the_same_motion():
    t = np.arange(0, 30.01, 0.1)
    sim = helix(t, -1.7, -0.85, -1.0, 0.46365)
    nav = helix(t, 12.0, -4.0, -30.0, -2.5)  # same motion, elsewhere, another heading
    metrics, s, n = compare(sim, nav, align=True)
    assert metrics["position_error_m"]["max"] < 1e-9
    assert metrics["yaw_error_deg"]["max_abs"] < 1e-9
    # the start frame: forward along +x, the turn to the left (+y), 30 s x 0.2 m/s = 6 m of path
    assert s[0, 1:4] == pytest.approx([0, 0, 0], abs=1e-12)
    assert s[-1, 1] == pytest.approx(2.0 * math.sin(3.0), abs=1e-9)
    assert s[-1, 2] == pytest.approx(2.0 * (1 - math.cos(3.0)), abs=1e-9)
    assert metrics["bag_path_length_m"] == pytest.approx(math.hypot(6.0, 0.3), rel=1e-3)
    unaligned, _, _ = compare(sim, nav, align=False)
    assert unaligned["position_error_m"]["final"] > 10.0


def test_errors_of_a_known_drift_and_yaw_offset():
    t = np.arange(0, 20.01, 0.5)
    sim = helix(t)
    nav = sim.copy()
    nav[:, 3] += 0.05 * t  # rises 5 cm/s faster than the simulated robot
    nav[:, 6] = wrap_angle(nav[:, 6] + np.radians(2.0) * t / 20.0)  # yaw drifts to +2 deg
    metrics, _, _ = compare(sim, nav, align=True)
    assert metrics["position_error_m"]["final"] == pytest.approx(1.0, abs=1e-9)
    assert metrics["final_error_xyz_m"] == pytest.approx([0, 0, -1.0], abs=1e-9)
    assert metrics["position_error_m"]["rms"] == pytest.approx(0.05 * math.sqrt(np.mean(t**2)), rel=1e-9)
    assert metrics["yaw_error_deg"]["final"] == pytest.approx(-2.0, abs=1e-9)


def test_navigation_is_interpolated_at_the_simulated_times():
    t = np.arange(0, 10.01, 0.1)
    sim = helix(t)
    nav = helix(np.arange(0, 10.01, 0.7))  # coarser, not on the same times
    metrics, s, n = compare(sim, nav, align=False)
    assert metrics["t_end_s"] <= 9.8 + 1e-9  # the last nav sample is at 9.8 s
    assert metrics["position_error_m"]["max"] < 5e-3  # chord error of linear interpolation


def test_to_start_frame_of_a_straight_line():
    t = np.arange(0, 5.01, 1.0)
    yaw = math.radians(30)
    traj = np.column_stack([t, 3 + t * math.cos(yaw), 4 + t * math.sin(yaw), -2 + 0 * t, 0 * t, 0 * t, yaw + 0 * t])
    out = to_start_frame(traj, 0.0)
    np.testing.assert_allclose(out[:, 1], t, atol=1e-12)
    np.testing.assert_allclose(out[:, 2:4], 0, atol=1e-12)
    np.testing.assert_allclose(out[:, 6], 0, atol=1e-12)


@pytest.mark.skipif(not SAMPLE_BAG.exists(), reason="sample bag not made yet")
def test_sample_bag_contents():
    m = read_bag(SAMPLE_BAG)
    assert SAMPLE_BAG.stat().st_size < 2_000_000
    assert m.topics == {"motors": MOTORS_TOPIC, "pendulum": "/UX_1/pendulum", "vbs": "/UX_1/vbs", "nav": "/UX_1/odom"}
    assert len(m.motors) == 421 and len(m.nav) == 421  # 42 s at 10 Hz, both ends included
    assert m.motors[0][0] == 0.0 and m.motors[1][0] == pytest.approx(0.1)
    assert all(mode == 0 and len(v) == 8 for _, mode, v in m.motors)  # RPM
    # forward segment (2..7 s): X = 6 -> +-3 N (0.306 kgf) on the horizontal thrusters -> the T200 rpm
    # giving it: forward between the rows 573 rpm (0.13 kgf) and 1237 rpm (0.60 kgf), reverse between
    # -1246 rpm (-0.48 kgf) and -578 rpm (-0.10 kgf)
    fwd = 573 + (3.0 / G - 0.13) * (1237 - 573) / (0.60 - 0.13)
    rev = -578 + (-3.0 / G + 0.10) * (-1246 + 578) / (-0.48 + 0.10)
    t, _, values = next(c for c in m.motors if c[0] >= 3.0)
    np.testing.assert_allclose(values, [fwd, 0, rev, 0, fwd, 0, rev, 0], atol=1e-6)
    # the perturbed robot rests at roll 8 deg, pitch 14 deg (urdf/ux1_perturbed.xacro)
    assert math.degrees(m.nav[0, 4]) == pytest.approx(8.0, abs=0.2)
    assert math.degrees(m.nav[0, 5]) == pytest.approx(14.0, abs=0.2)
    assert [v for _, v in m.pendulum] == pytest.approx([0.0, math.radians(10), 0.0])
    assert [v for _, v in m.vbs] == pytest.approx([0.0, 0.02])
    # the navigation sensors for dead reckoning (make_sample_bag.py --sensors): IMU at 50 Hz, DVL at 8 Hz,
    # pressure at 10 Hz over the 42 s
    from collections import Counter

    from unexmin.bag import read_messages, topic_types

    types = topic_types(SAMPLE_BAG)
    assert types["/UX_1/imu"] == "sensor_msgs/msg/Imu"
    assert types["/UX_1/dvl_twist"] == "geometry_msgs/msg/TwistWithCovarianceStamped"
    assert types["/UX_1/pressure"] == "sensor_msgs/msg/FluidPressure"
    sensors = {"/UX_1/imu", "/UX_1/dvl_twist", "/UX_1/pressure"}
    counts = Counter(topic for topic, *_ in read_messages(SAMPLE_BAG, sensors))
    assert counts == {"/UX_1/imu": 2101, "/UX_1/dvl_twist": 336, "/UX_1/pressure": 420}


def test_mission_events_order():
    m = Mission(
        path="x", t0=0.0, motors=[(1.0, 0, (0,) * 8), (0.0, 0, (0,) * 8)], pendulum=[(1.0, 0.1)], vbs=[(0.5, 0.01)]
    )
    assert [(t, k) for t, k, _ in m.events()] == [(0.0, "motors"), (0.5, "vbs"), (1.0, "motors"), (1.0, "pendulum")]
    assert m.duration == 1.0


# ---------------------------------------------------------------------------------------------
# damaged bags: one clear error, exit status 2, no simulator started
# ---------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def nominal_bag(tmp_path_factory):
    """A 12 s bag of the sample mission recorded by the nominal simulator."""
    tmp = tmp_path_factory.mktemp("nominal")
    bag = tmp / "nominal.bag"
    res = run([MAKER, "--nominal", "--out", bag, "--duration", "12"], tmp)
    assert res.returncode == 0, res.stdout + res.stderr
    return bag


def _damaged(tmp_path, src, kind):
    data = src.read_bytes()
    out = tmp_path / f"{kind}.bag"
    if kind == "truncated":
        out.write_bytes(data[: len(data) // 2])
    elif kind == "corrupt":
        rng = np.random.default_rng(5)
        b = bytearray(data)
        b[13:4096] = rng.integers(0, 256, 4096 - 13, dtype=np.uint8).tobytes()  # header and first records
        out.write_bytes(bytes(b))
    elif kind == "not_a_bag":
        out.write_text("this is not a rosbag\n")
    else:
        out = tmp_path / "missing.bag"
    return out


@pytest.mark.parametrize("kind", ["truncated", "corrupt", "not_a_bag", "missing"])
def test_damaged_bag_gives_one_clear_error(nominal_bag, tmp_path, kind):
    bag = _damaged(tmp_path, nominal_bag, kind)
    res = run(["-m", "unexmin.replay", bag, "--out", tmp_path / "out", "--quiet"], tmp_path, timeout=60)
    assert res.returncode == 2, res.stdout + res.stderr
    lines = [ln for ln in res.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1, res.stderr
    assert lines[0].startswith("replay_mission: error: ") and str(bag) in lines[0]
    assert "Traceback" not in res.stderr
    assert not (tmp_path / "out" / "ros_log").exists()  # failed before launching a simulator


def test_bag_without_motor_commands(tmp_path):
    from std_msgs.msg import Float64

    from unexmin.bag import BagWriter

    bag = tmp_path / "no_motors.bag"
    with BagWriter(bag) as w:
        w.write("/UX_1/vbs", Float64(0.1), 1.0)
    with pytest.raises(ReplayError, match="no motors command"):
        read_bag(bag)


# ---------------------------------------------------------------------------------------------
# replays in the simulator
# ---------------------------------------------------------------------------------------------
def replay_report(bag, tmp_path, *extra):
    out = tmp_path / "out"
    res = run(["-m", "unexmin.replay", bag, "--out", out, "--quiet", *extra], tmp_path)
    assert res.returncode == 0, res.stdout + res.stderr
    report = json.loads((out / "report.json").read_text())
    for name in report["plots"]:
        assert (out / name).stat().st_size > 5000, name
    return report, out


@pytest.mark.alone
def test_nominal_bag_replays_to_the_recorded_trajectory(nominal_bag, tmp_path):
    report, out = replay_report(nominal_bag, tmp_path)
    e = report["errors"]
    assert report["messages"]["motors"] == 121 and e["samples"] == 121
    assert e["bag_path_length_m"] > 0.5  # the mission moved the robot
    assert e["position_error_m"]["max"] < 0.01  # stated tolerance: 1 cm
    assert e["yaw_error_deg"]["max_abs"] < 0.5  # and 0.5 deg
    assert report["speed_vs_real_time"] > 1.0  # faster than real time
    assert sorted(report["plots"]) == ["error.png", "xy.png", "xz.png", "yaw.png", "yz.png"]
    csv = np.genfromtxt(out / "trajectory.csv", delimiter=",", names=True)
    assert len(csv) == 121 and "bag_z" in csv.dtype.names


@pytest.mark.skipif(not SAMPLE_BAG.exists(), reason="sample bag not made yet")
def test_perturbed_sample_bag_reports_a_larger_error(tmp_path):
    report, _ = replay_report(SAMPLE_BAG, tmp_path)
    e = report["errors"]
    # positive buoyancy: the prototype ends well above the nominal robot (z), the plan view agrees
    assert e["position_error_m"]["final"] > 0.5
    assert e["final_error_xyz_m"][2] < -0.5
    assert abs(e["final_error_xyz_m"][0]) < 0.3 and abs(e["final_error_xyz_m"][1]) < 0.3
    assert report["mission_duration_s"] == pytest.approx(42.0)

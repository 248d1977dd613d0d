"""The navigation sensors in the UX-1 description (urdf/sensor_plugins.xacro inside <unexmin>):
types, links, rates and the derived figures, against properties.xacro's formulas and the beam frames
of sensors.xacro. The simulator's parser and models check the rest at start-up (test/gtest).

Run: /work/main_ws/venv/bin/python -m pytest test/pytest/test_sensor_description.py
"""

import math
import shutil
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from unexmin.geometry import rpy_matrix

REPO = Path(__file__).resolve().parents[2]


def expand(name="UX_1"):
    exe = Path(sys.executable).parent / "xacro"
    exe = str(exe) if exe.exists() else shutil.which("xacro")
    if not exe:
        pytest.skip("xacro not found")
    proc = subprocess.run([exe, str(REPO / "urdf" / "ux1.urdf.xacro"), f"name:={name}"], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    return ET.fromstring(proc.stdout)


def sensors(robot):
    return {s.get("name"): s for s in robot.find("unexmin").findall("sensor")}


def param(sensor, name):
    for p in sensor.findall("param"):
        if p.get("name") == name:
            return p.get("value")
    raise KeyError(name)


def test_navigation_sensors_types_links_and_rates():
    robot = expand("UX_2")
    links = {link.get("name") for link in robot.findall("link")}
    s = sensors(robot)
    expected = {
        "imu": ("imu", "UX_2/imu_link", 500.0),
        "dvl": ("dvl", "UX_2/dvl_link", 8.0),
        "pressure": ("pressure", "UX_2/pressure_link", 10.0),
    }
    for name, (kind, link, rate) in expected.items():
        assert s[name].get("type") == kind
        assert s[name].get("link") == link and link in links
        assert float(s[name].get("rate")) == rate
    assert param(s["imu"], "kvh_topic") == "kvh/imu_raw"


def test_derived_noise_figures_follow_their_formulas():
    s = sensors(expand())
    a = float(param(s["dvl"], "beam_angle"))
    assert a == pytest.approx(math.radians(25.0))
    # per-axis 0.005 m/s on x, y (two beams): s_b = s_x sqrt(2) sin a
    assert float(param(s["dvl"], "beam_velocity_noise")) == pytest.approx(0.005 * math.sqrt(2) * math.sin(a))
    # 0.012 deg/sqrt(h) = 0.012 * pi / 180 / 60 rad/s/sqrt(Hz)
    assert float(param(s["imu"], "gyro_noise_density")) == pytest.approx(math.radians(0.012) / 60.0)
    # K = B / sqrt(1000 s), B = 0.05 deg/h
    assert float(param(s["imu"], "gyro_bias_random_walk")) == pytest.approx(math.radians(0.05) / 3600 / math.sqrt(1000))


def test_dvl_beam_frames_point_along_the_model_beams():
    robot = expand()
    s = sensors(robot)["dvl"]
    a, c0 = float(param(s, "beam_angle")), float(param(s, "beam_azimuth_0"))
    joints = {j.find("child").get("link"): j for j in robot.findall("joint")}
    for i, link in enumerate(param(s, "beam_frames").split()):
        j = joints[link]
        assert j.find("parent").get("link") == s.get("link")
        rpy = [float(v) for v in j.find("origin").get("rpy").split()]
        x = rpy_matrix(rpy)[:, 0]
        c = c0 + i * math.pi / 2
        assert x == pytest.approx([math.sin(a) * math.cos(c), math.sin(a) * math.sin(c), math.cos(a)], abs=1e-9)


def test_malformed_sensor_parameter_stops_the_simulator_naming_sensor_and_parameter(tmp_path):
    """End to end: an overrides file puts the DVL beams at 95 deg; the simulator node must refuse to start
    and say which sensor and which parameter (through a real master, no launch file)."""
    import os

    from unexmin.scripting.launcher import free_port

    node = None
    for ws in (os.environ.get("UNEXMIN_WS"), str(REPO.parent / (REPO.name + "_ws"))):
        if ws and (Path(ws) / "devel/lib/unexmin/simulator_node").exists():
            node = Path(ws) / "devel/lib/unexmin/simulator_node"
            break
    if node is None or not shutil.which("rosmaster"):
        pytest.skip("simulator_node not built or no rosmaster")
    overrides = tmp_path / "bad_dvl.xacro"
    overrides.write_text(
        '<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:property name="dvl_beam_angle" value="${radians(95.0)}"/>\n</robot>\n'
    )
    exe = Path(sys.executable).parent / "xacro"
    exe = str(exe) if exe.exists() else shutil.which("xacro")
    urdf = subprocess.run(
        [exe, str(REPO / "urdf" / "ux1.urdf.xacro"), "name:=UX_1", f"overrides:={overrides}"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    port = free_port()
    env = dict(
        os.environ,
        ROS_MASTER_URI=f"http://127.0.0.1:{port}",
        ROS_LOG_DIR=str(tmp_path / "log"),
        ROS_HOME=str(tmp_path / "home"),
    )
    master = subprocess.Popen(
        ["rosmaster", "--core", "-p", str(port)], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
    )
    try:
        from xmlrpc.client import ServerProxy

        proxy = ServerProxy(env["ROS_MASTER_URI"])
        deadline = time.monotonic() + 20.0
        while True:  # wait for the master to answer (condition with a timeout)
            try:
                proxy.setParam("/test", "/UX_1/robot_description", urdf)
                break
            except OSError:
                assert time.monotonic() < deadline, "rosmaster did not start within 20 s"
                time.sleep(0.05)
        proc = subprocess.run(
            [str(node), f"_world_file:={REPO / 'worlds' / 'tank.world'}", "_paused:=true"],
            env=env,
            capture_output=True,
            text=True,
            timeout=60,
        )
    finally:
        master.terminate()
        master.wait(10)
    assert proc.returncode != 0
    out = proc.stdout + proc.stderr
    assert "sensor 'dvl'" in out and "'beam_angle'" in out, out

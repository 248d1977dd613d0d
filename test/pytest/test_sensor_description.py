"""The navigation sensors in the UX-1 description (urdf/sensor_plugins.xacro inside <unexmin>):
types, links, rates and the derived figures, against properties.xacro's formulas and the beam frames
of sensors.xacro. The simulator's parser and models check the rest at start-up (test/gtest).

Run: /work/main_ws/venv/bin/python -m pytest test/pytest/test_sensor_description.py
"""
import math
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

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


def rpy_matrix(r, p, y):
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def test_navigation_sensors_types_links_and_rates():
    robot = expand("UX_2")
    links = {l.get("name") for l in robot.findall("link")}
    s = sensors(robot)
    expected = {"imu": ("imu", "UX_2/imu_link", 500.0), "dvl": ("dvl", "UX_2/dvl_link", 8.0),
                "pressure": ("pressure", "UX_2/pressure_link", 10.0)}
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
        x = rpy_matrix(*rpy)[:, 0]
        c = c0 + i * math.pi / 2
        assert x == pytest.approx([math.sin(a) * math.cos(c), math.sin(a) * math.sin(c), math.cos(a)], abs=1e-9)

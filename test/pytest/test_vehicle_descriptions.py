"""The BlueROV2 Heavy and REMUS 100 descriptions (urdf/bluerov2_heavy*.xacro, urdf/remus100*.xacro): frame tree,
mass, and actuator geometry against the published layouts.

Run: /work/main_ws/venv/bin/python -m pytest test/pytest/test_vehicle_descriptions.py
"""

import math
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest

from unexmin.geometry import rpy_matrix

URDF = Path(__file__).resolve().parents[2] / "urdf"
VEHICLES = {"ROV_1": "bluerov2_heavy.urdf.xacro", "AUV_1": "remus100.urdf.xacro"}


@lru_cache(maxsize=None)
def description(name):
    """The parsed expansion of vehicle `name`; xacro must neither fail nor warn."""
    local = Path(sys.executable).parent / "xacro"
    exe = str(local) if local.exists() else shutil.which("xacro")
    if exe is None:
        pytest.skip("xacro not found")
    proc = subprocess.run([exe, str(URDF / VEHICLES[name]), "name:=" + name], capture_output=True, text=True)
    assert proc.returncode == 0 and proc.stderr.strip() == "", proc.stderr
    return ET.fromstring(proc.stdout)


def numbers(text):
    return np.array([float(v) for v in text.split()])


def pose_of(robot, link):
    """(position, rotation) of `link` in base_link with every joint at zero."""
    by_child = {j.find("child").get("link"): j for j in robot.findall("joint")}
    chain = []
    while link in by_child:
        chain.append(by_child[link])
        link = by_child[link].find("parent").get("link")
    p, rot = np.zeros(3), np.eye(3)
    for joint in reversed(chain):
        o = joint.find("origin")
        xyz = numbers(o.get("xyz", "0 0 0")) if o is not None else np.zeros(3)
        rpy = numbers(o.get("rpy", "0 0 0")) if o is not None else np.zeros(3)
        p, rot = p + rot @ xyz, rot @ rpy_matrix(rpy)
    return p, rot


def actuator_frames(robot, tag):
    """Per <thruster>/<fin> in id order: (position, joint frame rotation, joint axis in base_link)."""
    joints = {j.get("name"): j for j in robot.findall("joint")}
    out = []
    for element in sorted(robot.find("unexmin").findall(tag), key=lambda e: int(e.get("id"))):
        joint = joints[element.get("joint")]
        p, rot = pose_of(robot, joint.find("child").get("link"))
        out.append((p, rot, rot @ numbers(joint.find("axis").get("xyz"))))
    return out


@pytest.mark.parametrize("name", sorted(VEHICLES))
def test_frames_prefixed_and_one_tree(name):
    robot = description(name)
    links = [link.get("name") for link in robot.findall("link")]
    joints = robot.findall("joint")
    assert all(n.startswith(name + "/") for n in links + [j.get("name") for j in joints])
    children = [j.find("child").get("link") for j in joints]
    assert len(set(children)) == len(children)
    assert set(links) - set(children) == {name + "/base_link"}
    for element in robot.find("unexmin").iter():
        if element.get("link") is not None:
            assert element.get("link") in links, element.get("link")


@pytest.mark.parametrize("name", sorted(VEHICLES))
def test_inertial_mass_is_the_hydrodynamics_mass(name):
    robot = description(name)
    total = sum(float(i.get("value")) for i in robot.findall("link/inertial/mass"))
    assert total == pytest.approx(float(robot.find("unexmin/hydrodynamics/mass").get("value")), rel=1e-12)


def test_rov_masses_and_buoyancy_are_von_benzons():
    hydro = description("ROV_1").find("unexmin/hydrodynamics")
    assert float(hydro.find("mass").get("value")) == 13.5
    assert float(hydro.find("volume").get("value")) == 0.0134
    assert numbers(hydro.find("added_mass").get("value")).reshape(6, 6).diagonal() == pytest.approx(
        [6.3567, 7.1206, 18.6863, 0.1858, 0.1348, 0.2215]
    )
    radius = float(hydro.find("radius").get("value"))
    assert 4.0 / 3.0 * math.pi * radius**3 == pytest.approx(0.0134, rel=1e-12)


def test_rov_thrusters_actuate_all_six_degrees_of_freedom():
    """Configuration matrix B = [d; r x d] of the 8 thrusters: full rank; all four horizontal push forward at +thrust,
    surge needs no yaw, and the yaw arm is (0.156 + 0.111) cos 45 deg."""
    frames = actuator_frames(description("ROV_1"), "thruster")
    b = np.array([np.concatenate([d, np.cross(p, d)]) for p, _, d in frames]).T
    assert np.linalg.matrix_rank(b, tol=1e-9) == 6
    horizontal, vertical = b[:, :4], b[:, 4:]
    assert horizontal[0] == pytest.approx([math.sqrt(0.5)] * 4)
    assert horizontal[5].sum() == pytest.approx(0.0, abs=1e-12)
    assert np.abs(horizontal[5]) == pytest.approx([(0.156 + 0.111) * math.sqrt(0.5)] * 4)
    assert vertical[2] == pytest.approx([1.0] * 4)
    box = numbers(description("ROV_1").find("unexmin/hydrodynamics/bounding_box").get("size"))
    for p, _, _ in frames:
        assert np.all(np.abs(p) <= box / 2 + 1e-9)


def test_auv_fins_turn_about_their_span_with_the_chord_forward():
    frames = actuator_frames(description("AUV_1"), "fin")
    spans = [[0, 0, 1], [0, 0, 1], [0, 1, 0], [0, 1, 0], [0, 0, 1], [0, 1, 0]]
    for (_p, rot, axis), span in zip(frames, spans):
        assert axis == pytest.approx(span, abs=1e-12)
        assert rot[:, 0] == pytest.approx([1, 0, 0], abs=1e-12), "the chord at angle 0 points forward"
    assert [p[0] for p, _, _ in frames] == pytest.approx([-0.638] * 4 + [-0.321] * 2)
    fins = sorted(description("AUV_1").find("unexmin").findall("fin"), key=lambda e: int(e.get("id")))
    limits = [(float(f.find("angle").get("min")), float(f.find("angle").get("max"))) for f in fins]
    assert limits[4:] == [(0.0, 0.0), (0.0, 0.0)], "the body-lift surfaces are fixed"
    assert all(lo < 0.0 < hi for lo, hi in limits[:4])


def test_auv_is_positively_buoyant_in_sea_water():
    hydro = description("AUV_1").find("unexmin/hydrodynamics")
    mass, volume = float(hydro.find("mass").get("value")), float(hydro.find("volume").get("value"))
    assert 1030.0 * volume * 9.81 - mass * 9.81 == pytest.approx(306.0 - 299.0, rel=1e-9)

"""Robot description (urdf/*.xacro) and world files (worlds/*.world) against physics and the thesis.

Expected values come from formulas in this file (sphere volume and inertia, added mass, drag, the
thesis's allocation matrix eq. 5.12), never from a previous expansion.

Run: /work/main_ws/venv/bin/python -m pytest test/pytest/test_urdf.py
xacro is taken from $XACRO, else from the running interpreter's bin folder, else from PATH.
"""

import math
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest
import yaml

from unexmin.geometry import rpy_matrix

REPO = Path(__file__).resolve().parents[2]
URDF_DIR = REPO / "urdf"
ROBOT_FILE = URDF_DIR / "ux1.urdf.xacro"
WORLDS_DIR = REPO / "worlds"
SHIPPED_WORLDS = ["tank.world", "tank_target.world", "test_box.world"]

RHO = 1000.0  # [kg/m^3] fresh water (thesis 5.3)
R_HULL = 0.3  # [m] 0.6 m diameter sphere (thesis 2.3)
MU = 1.0e-3  # [Pa s] water viscosity
CD_SPHERE = 0.47  # [-] subcritical sphere (Hoerner)

# Thesis eq. 5.12: rows X Y Z K M N, columns M0..M7.
A_THESIS = np.array(
    [
        [0.5, 0.0, -0.5, 0.0, 0.5, 0.0, -0.5, 0.0],
        [-0.25, -0.25, -0.25, 0.25, 0.25, -0.25, 0.25, -0.25],
        [0.0, -0.5, 0.0, -0.5, 0.0, 0.5, 0.0, -0.5],
        [0.0] * 8,
        [0.0] * 8,
        [-0.25, 0.0, 0.25, 0.0, 0.25, 0.0, -0.25, 0.0],
    ]
)
DOF = ["X", "Y", "Z", "K", "M", "N"]


# ----------------------------------------------------------------------------------------------
# helpers
# ----------------------------------------------------------------------------------------------
def xacro_exe():
    env = os.environ.get("XACRO")
    if env:
        return env
    local = Path(sys.executable).parent / "xacro"
    if local.exists():
        return str(local)
    found = shutil.which("xacro")
    if not found:
        pytest.skip("xacro not found (set $XACRO or install xacro==1.13.3 into this interpreter's venv)")
    return found


def run_xacro(path, *args):
    proc = subprocess.run([xacro_exe(), str(path)] + list(args), capture_output=True, text=True)
    assert proc.returncode == 0, "xacro %s %s failed:\n%s" % (path, " ".join(args), proc.stderr)
    return proc


@lru_cache(maxsize=None)
def expand(name, *extra):
    """Expanded URDF text of the robot file for robot `name`; xacro must not warn."""
    proc = run_xacro(ROBOT_FILE, "name:=%s" % name, *extra)
    assert proc.stderr.strip() == "", "xacro warned:\n" + proc.stderr
    return proc.stdout


def robot_xml(name, *extra):
    return ET.fromstring(expand(name, *extra))


def floats(text):
    return np.array([float(v) for v in text.split()])


def axis_angle_matrix(axis, angle):
    k = np.asarray(axis, float) / np.linalg.norm(axis)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * kx + (1 - math.cos(angle)) * kx @ kx


def joint_origin(joint):
    origin = joint.find("origin")
    xyz = floats(origin.get("xyz", "0 0 0")) if origin is not None else np.zeros(3)
    rpy = floats(origin.get("rpy", "0 0 0")) if origin is not None else np.zeros(3)
    return xyz, rpy_matrix(rpy)


def joints_by_name(robot):
    return {j.get("name"): j for j in robot.findall("joint")}


def links_by_name(robot):
    return {link.get("name"): link for link in robot.findall("link")}


def link_pose(robot, link_name):
    """Pose (p, R) of a link in the root frame with every joint at zero."""
    by_child = {j.find("child").get("link"): j for j in robot.findall("joint")}
    p, rot = np.zeros(3), np.eye(3)
    chain = []
    while link_name in by_child:
        joint = by_child[link_name]
        chain.append(joint)
        link_name = joint.find("parent").get("link")
    for joint in reversed(chain):
        xyz, r = joint_origin(joint)
        p, rot = p + rot @ xyz, rot @ r
    return p, rot


def hydro(robot):
    blocks = robot.findall("unexmin")
    assert len(blocks) == 1, "expected exactly one <unexmin> child of <robot>"
    return blocks[0]


def hydro_value(robot, tag, attr="value"):
    element = hydro(robot).find("hydrodynamics/" + tag)
    assert element is not None, "<hydrodynamics> has no <%s>" % tag
    return floats(element.get(attr))


def inertials(robot):
    """(link name, mass, com in link frame, inertia 3x3 in link frame) for every <inertial>."""
    out = []
    for link in robot.findall("link"):
        inertial = link.find("inertial")
        if inertial is None:
            continue
        origin = inertial.find("origin")
        com = floats(origin.get("xyz", "0 0 0")) if origin is not None else np.zeros(3)
        rot = rpy_matrix(floats(origin.get("rpy", "0 0 0"))) if origin is not None else np.eye(3)
        i = inertial.find("inertia")
        g = {k: float(i.get(k, "0")) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
        tensor = np.array(
            [[g["ixx"], g["ixy"], g["ixz"]], [g["ixy"], g["iyy"], g["iyz"]], [g["ixz"], g["iyz"], g["izz"]]]
        )
        out.append((link.get("name"), float(inertial.find("mass").get("value")), com, rot @ tensor @ rot.T))
    return out


def thruster_geometry(robot, name):
    """Positions r_i and unit thrust directions d_i (body frame) of thrusters 0..7."""
    joints = joints_by_name(robot)
    r, d = [], []
    for i in range(8):
        joint = joints["%s/thruster_%d_joint" % (name, i)]
        assert joint.find("parent").get("link") == "%s/base_link" % name
        xyz, rot = joint_origin(joint)
        axis = floats(joint.find("axis").get("xyz"))
        r.append(xyz)
        d.append(rot @ (axis / np.linalg.norm(axis)))
    return np.array(r), np.array(d)


def configuration_matrix(r, d):
    """6x8 B: column i = [d_i; r_i x d_i] (force and moment of unit thrust)."""
    return np.vstack([d.T, np.cross(r, d).T])


def check_allocation(b_matrix):
    """Raise AssertionError unless pinv(B) reproduces the thesis A row by row up to positive scale."""
    assert np.allclose(b_matrix[3:5], 0.0, atol=1e-9), "thrusters make roll/pitch moments:\n%s" % b_matrix[3:5]
    alloc = np.linalg.pinv(b_matrix).T  # 6x8: row j maps tau_j to the 8 thrusts
    for j, row in enumerate(alloc):
        a = A_THESIS[j]
        if not a.any():
            assert np.allclose(row, 0.0, atol=1e-9), "%s row should be zero: %s" % (DOF[j], row)
            continue
        scale = row @ a / (a @ a)
        assert scale > 0, "%s row has a negative scale %g: %s vs %s" % (DOF[j], scale, row, a)
        assert np.allclose(row, scale * a, rtol=1e-6, atol=1e-9 * np.abs(row).max()), (
            "%s row %s is not a positive multiple of %s" % (DOF[j], row, a)
        )


# ----------------------------------------------------------------------------------------------
# description: structure
# ----------------------------------------------------------------------------------------------
@pytest.mark.parametrize("path", sorted(URDF_DIR.glob("*.xacro")), ids=lambda p: p.name)
def test_every_xacro_file_expands(path):
    run_xacro(path)


@pytest.mark.parametrize("name", ["UX_1", "UX_2"])
def test_names_prefixed_and_tree_connected(name):
    robot = robot_xml(name)
    assert robot.get("name") == name
    links, joints = links_by_name(robot), joints_by_name(robot)
    assert len(links) == len(robot.findall("link")), "duplicate link names"
    assert len(joints) == len(robot.findall("joint")), "duplicate joint names"
    for n in list(links) + list(joints):
        assert n.startswith(name + "/") and len(n) > len(name) + 1, "name not prefixed: " + n
    children = []
    for jname, joint in joints.items():
        parent, child = joint.find("parent").get("link"), joint.find("child").get("link")
        assert parent in links, "%s: parent %s is not a link" % (jname, parent)
        assert child in links, "%s: child %s is not a link" % (jname, child)
        children.append(child)
    assert len(children) == len(set(children)), "a link has two parents"
    roots = set(links) - set(children)
    assert roots == {name + "/base_link"}
    for element in robot.iter():
        for attr in ("link", "joint"):
            if element.tag in ("hydrodynamics", "thruster", "pendulum") and element.get(attr):
                assert element.get(attr) in (links if attr == "link" else joints), element.get(attr)


def test_other_robot_names_change_every_frame():
    # Compare the parsed trees (comments dropped): UX_2's is UX_1's with the name replaced.
    a = ET.tostring(robot_xml("UX_1"), encoding="unicode")
    b = ET.tostring(robot_xml("UX_2"), encoding="unicode")
    assert "UX_2" not in a and "UX_1" not in b
    assert a.replace("UX_1", "UX_2") == b


def test_sensor_and_actuator_frames_exist():
    name = "UX_1"
    robot = robot_xml(name)
    joints, links = joints_by_name(robot), links_by_name(robot)

    def jtype(j):
        return joints[name + "/" + j].get("type")

    assert jtype("msis_head_joint") == "continuous"
    assert jtype("pendulum_joint") == "revolute"
    for i in range(8):
        assert jtype("thruster_%d_joint" % i) == "continuous"
    for i in range(4):
        assert jtype("sls_%d_motor_joint" % i) == "revolute"
        assert name + "/sls_%d_light_link" % i in links
    for i in range(5):
        assert name + "/camera_%d_link" % i in links
        assert name + "/camera_%d_optical_frame" % i in links
    for link in ("msis_head_link", "m3_link", "dvl_link", "imu_link", "pressure_link", "water_probe_link"):
        assert name + "/" + link in links
    # Sensors on the hull must sit on (or inside) it.
    for link in links:
        p, _ = link_pose(robot, link)
        assert np.linalg.norm(p) <= R_HULL + 0.08, "%s is %.3f m from the centre" % (link, np.linalg.norm(p))


def test_camera_optical_frames_follow_rep103():
    robot = robot_xml("UX_1")
    for i in range(5):
        _, r_link = link_pose(robot, "UX_1/camera_%d_link" % i)
        p_link, _ = link_pose(robot, "UX_1/camera_%d_link" % i)
        _, r_opt = link_pose(robot, "UX_1/camera_%d_optical_frame" % i)
        assert np.allclose(r_opt[:, 2], r_link[:, 0], atol=1e-12)  # optical z = camera forward
        assert np.allclose(r_opt[:, 0], -r_link[:, 1], atol=1e-12)  # optical x = right
        # Cameras look outwards from the hull.
        assert r_link[:, 0] @ p_link / np.linalg.norm(p_link) > 0.99


def test_dvl_beams_point_down_at_the_janus_angle():
    robot = robot_xml("UX_1")
    azimuths = []
    for i in range(4):
        _, rot = link_pose(robot, "UX_1/dvl_beam_%d_link" % i)
        beam = rot[:, 0]
        angle_from_down = math.degrees(math.acos(beam @ np.array([0, 0, -1.0])))
        assert angle_from_down == pytest.approx(25.0, abs=1e-9)
        azimuths.append(math.atan2(beam[1], beam[0]))
    spread = sorted(math.degrees(a) % 360 for a in azimuths)
    assert np.allclose(np.diff(spread), 90.0, atol=1e-9)


def test_msis_scan_plane_clears_the_hull():
    robot = robot_xml("UX_1")
    p, rot = link_pose(robot, "UX_1/msis_head_link")
    assert np.allclose(rot[:, 2], [0, 0, 1], atol=1e-12), "MSIS head must turn about body z"
    assert p[2] > R_HULL, "a 360 deg scan at z=%.3f would hit the hull top" % p[2]


def test_urdfdom_parses_the_description(tmp_path):
    """Load the expansion with the URDF parser robot_state_publisher uses (urdfdom)."""
    compiler = shutil.which("g++")
    if compiler is None or not Path("/usr/include/urdf_parser/urdf_parser.h").exists():
        pytest.skip("g++ or liburdfdom-headers-dev not available")
    src = tmp_path / "check.cpp"
    src.write_text(
        "#include <urdf_parser/urdf_parser.h>\n#include <iostream>\n#include <sstream>\n"
        "int main() { std::stringstream s; s << std::cin.rdbuf();\n"
        "  urdf::ModelInterfaceSharedPtr m = urdf::parseURDF(s.str());\n"
        "  if (!m) return 1;\n"
        '  std::cout << m->getName() << " " << m->getRoot()->name << " " << m->links_.size()'
        ' << " " << m->joints_.size() << std::endl; return 0; }\n'
    )
    exe = tmp_path / "check"
    build = subprocess.run(
        [compiler, "-std=c++17", str(src), "-o", str(exe), "-lurdfdom_model"], capture_output=True, text=True
    )
    if build.returncode != 0:
        pytest.skip("cannot build against urdfdom: " + build.stderr[-300:])
    for name in ("UX_1", "UX_2"):
        robot = robot_xml(name)
        out = subprocess.run([str(exe)], input=expand(name), capture_output=True, text=True)
        assert out.returncode == 0, "urdfdom rejected the description:\n" + out.stderr
        got_name, root, nlinks, njoints = out.stdout.split()
        assert (got_name, root) == (name, name + "/base_link")
        assert (int(nlinks), int(njoints)) == (len(robot.findall("link")), len(robot.findall("joint")))


# ----------------------------------------------------------------------------------------------
# description: mass, inertia, hydrodynamics
# ----------------------------------------------------------------------------------------------
@pytest.mark.parametrize("name", ["UX_1", "UX_2"])
def test_total_mass_is_hydro_mass_and_neutral(name):
    robot = robot_xml(name)
    total = sum(m for _, m, _, _ in inertials(robot))
    (hydro_mass,) = hydro_value(robot, "mass")
    (volume,) = hydro_value(robot, "volume")
    (radius,) = hydro_value(robot, "radius")
    assert total == pytest.approx(hydro_mass, abs=1e-6)
    sphere_volume = 4.0 / 3.0 * math.pi * R_HULL**3
    assert radius == pytest.approx(R_HULL, abs=1e-12)
    assert volume == pytest.approx(sphere_volume, rel=1e-12)
    assert total == pytest.approx(RHO * sphere_volume, abs=1e-3), "not neutrally buoyant"
    assert total == pytest.approx(113.097, abs=1e-3)
    # The collision/visual hull is the same sphere.
    base = links_by_name(robot)[name + "/base_link"]
    assert float(base.find("collision/geometry/sphere").get("radius")) == pytest.approx(radius)


def test_inertia_and_centre_of_gravity_are_consistent():
    """Whole vehicle about the centre (pendulum at 0) equals 2/5 m R^2; CG of the non-pendulum part."""
    name = "UX_1"
    robot = robot_xml(name)
    total_inertia = np.zeros((3, 3))
    mass_rest, moment_rest = 0.0, np.zeros(3)
    for link, m, com, tensor in inertials(robot):
        p, rot = link_pose(robot, link)
        c = p + rot @ com
        total_inertia += rot @ tensor @ rot.T + m * (c @ c * np.eye(3) - np.outer(c, c))
        if link != name + "/pendulum":
            mass_rest += m
            moment_rest += m * c
    m_total = hydro_value(robot, "mass")[0]
    expected = 0.4 * m_total * R_HULL**2
    assert np.allclose(total_inertia, np.diag([expected] * 3), rtol=1e-9, atol=1e-12)
    assert np.allclose(hydro_value(robot, "inertia", "ixx"), expected, rtol=1e-12)
    for key in ("iyy", "izz"):
        assert np.allclose(hydro_value(robot, "inertia", key), expected, rtol=1e-12)
    cog = floats(hydro(robot).find("hydrodynamics/center_of_gravity").get("xyz"))
    assert np.allclose(moment_rest / mass_rest, cog, atol=1e-12)
    assert cog[2] < 0, "CG must be below the centre of buoyancy for static stability"
    assert np.allclose(floats(hydro(robot).find("hydrodynamics/center_of_buoyancy").get("xyz")), 0)


def test_hydrodynamic_defaults_match_sphere_formulas():
    robot = robot_xml("UX_1")
    volume = 4.0 / 3.0 * math.pi * R_HULL**3
    added = hydro_value(robot, "added_mass").reshape(6, 6)
    expected_added = np.diag([0.5 * RHO * volume] * 3 + [0.0] * 3)
    assert np.allclose(added, expected_added, rtol=1e-12, atol=1e-12)
    assert added[0, 0] == pytest.approx(56.549, abs=1e-3)
    lin = hydro_value(robot, "linear_damping")
    quad = hydro_value(robot, "quadratic_damping")
    assert lin.shape == (6,) and quad.shape == (6,)
    assert np.allclose(lin[:3], 6 * math.pi * MU * R_HULL, rtol=1e-12)
    assert np.allclose(lin[3:], 8 * math.pi * MU * R_HULL**3, rtol=1e-12)
    assert np.allclose(quad[:3], 0.5 * RHO * CD_SPHERE * math.pi * R_HULL**2, rtol=1e-12)
    assert quad[0] == pytest.approx(66.44, abs=0.01)
    # rotational: the protrusions' drag 1/2 rho Cd A r^3, itemised (docs/identification.md, "The default
    # rotational damping"): (count, Cd, area [m^2], arm [m])
    items = [
        (4, 1.0, math.pi * 0.035**2, R_HULL),
        (4, 1.0, 0.07 * 0.08, R_HULL / math.sqrt(2.0)),
        (4, 1.0, 0.05 * 0.04, 0.32),
        (4, 1.0, 0.04 * 0.04, 0.32),
        (1, 1.05, 0.15 * 0.10, R_HULL),
        (1, 1.0, 0.0034, 0.13),
    ]
    rotational = sum(n * 0.5 * RHO * cd * a * r**3 for n, cd, a, r in items)
    assert np.allclose(quad[3:], rotational, rtol=1e-12)
    assert rotational == pytest.approx(0.767, abs=0.001)
    # Terminal speed at full forward thrust lies in a sane range for a 0.6 m sphere.
    thrust_max = float(hydro(robot).find("thruster/thrust").get("max"))
    _, d = thruster_geometry(robot, "UX_1")
    x_force = thrust_max * np.abs(d[:, 0]).sum()
    v_terminal = math.sqrt(x_force / quad[0])
    assert 0.3 < v_terminal < 2.0


def test_thruster_models_schema():
    name = "UX_1"
    robot = robot_xml(name)
    joints = joints_by_name(robot)
    thrusters = hydro(robot).findall("thruster")
    assert sorted(int(t.get("id")) for t in thrusters) == list(range(8))
    for t in thrusters:
        assert t.get("joint") == "%s/thruster_%s_joint" % (name, t.get("id"))
        assert joints[t.get("joint")].get("type") == "continuous"
        dyn = t.find("dynamics")
        assert dyn.get("type") == "first_order"
        assert float(dyn.find("param[@name='tau']").get("value")) == pytest.approx(0.1)
        assert t.find("conversion").get("type") == "identity"
        for tag in ("thrust", "command"):
            assert (float(t.find(tag).get("min")), float(t.find(tag).get("max"))) == (-40.0, 40.0)
        assert float(t.find("timeout").get("value")) == pytest.approx(1.0)
    pend = hydro(robot).find("pendulum")
    assert pend.get("joint") == name + "/pendulum_joint"
    assert float(pend.get("mass")) == pytest.approx(10.0)
    assert float(pend.get("arm")) == pytest.approx(0.12)
    assert float(pend.get("speed")) == pytest.approx(math.radians(10))
    assert (float(pend.get("min")), float(pend.get("max"))) == pytest.approx((-math.radians(30), math.radians(30)))
    limit = joints[name + "/pendulum_joint"].find("limit")
    assert (float(limit.get("lower")), float(limit.get("upper"))) == pytest.approx(
        (float(pend.get("min")), float(pend.get("max")))
    )
    vbs = hydro(robot).find("vbs")
    assert float(vbs.get("min")) < 0 < float(vbs.get("max")) and floats(vbs.get("xyz")).shape == (3,)
    # The pendulum link carries the pendulum mass at the arm.
    ((link, m, com, _),) = [x for x in inertials(robot) if x[0] == name + "/pendulum"]
    assert m == pytest.approx(float(pend.get("mass")))
    assert np.allclose(com, [0, 0, -float(pend.get("arm"))])


def test_positive_pendulum_angle_moves_the_mass_forward():
    """Sign convention of cpp/unexmin/hydro/pendulum.h: mass at arm (sin a, 0, -cos a)."""
    robot = robot_xml("UX_1")
    joint = joints_by_name(robot)["UX_1/pendulum_joint"]
    xyz, rot = joint_origin(joint)
    axis = rot @ floats(joint.find("axis").get("xyz"))
    arm, angle = 0.12, 0.3
    mass = xyz + axis_angle_matrix(axis, angle) @ rot @ np.array([0, 0, -arm])
    assert np.allclose(mass, arm * np.array([math.sin(angle), 0, -math.cos(angle)]), atol=1e-12)


# ----------------------------------------------------------------------------------------------
# description: thruster geometry against the thesis allocation matrix
# ----------------------------------------------------------------------------------------------
@pytest.mark.parametrize("name", ["UX_1", "UX_2"])
def test_thruster_geometry_reproduces_thesis_allocation(name):
    robot = robot_xml(name)
    r, d = thruster_geometry(robot, name)
    assert np.allclose(np.linalg.norm(r, axis=1), R_HULL, atol=1e-12), "thrusters off the hull"
    b_matrix = configuration_matrix(r, d)
    check_allocation(b_matrix)
    # And the other way round: A's columns are B's columns up to the per-row scale.
    assert np.linalg.matrix_rank(b_matrix) == 4


def test_allocation_check_catches_a_flipped_or_moved_thruster():
    """The check above must fail for a wrong geometry (flipped axis, swapped yaw arm)."""
    r, d = thruster_geometry(robot_xml("UX_1"), "UX_1")
    for i in range(8):
        flipped = d.copy()
        flipped[i] = -flipped[i]
        with pytest.raises(AssertionError):
            check_allocation(configuration_matrix(r, flipped))
    swapped = r.copy()
    swapped[[0, 2]] = swapped[[2, 0]]  # M0 and M2 trade places: yaw moments change sign
    with pytest.raises(AssertionError):
        check_allocation(configuration_matrix(swapped, d))
    lifted = r.copy()
    lifted[1] += np.array([0.05, 0, 0])  # M1 off the centre line: a pitch moment appears
    with pytest.raises(AssertionError):
        check_allocation(configuration_matrix(lifted, d))


# ----------------------------------------------------------------------------------------------
# description: per-robot overrides
# ----------------------------------------------------------------------------------------------
def test_overrides_file_changes_only_what_it_names(tmp_path):
    override = tmp_path / "ux3.xacro"
    override.write_text(
        '<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:property name="msis_elevation_deg" value="90.0"/>\n'
        '  <xacro:property name="thruster_dynamics" value="zero_order"/>\n'
        '  <xacro:property name="thruster_conversion" value="table"/>\n'
        "</robot>\n"
    )
    robot = robot_xml("UX_3", "overrides:=%s" % override)
    joints = joints_by_name(robot)
    xyz, _ = joint_origin(joints["UX_3/msis_base_joint"])
    assert np.allclose(xyz, [0, 0, R_HULL], atol=1e-12)
    t = hydro(robot).find("thruster")
    assert t.find("dynamics").get("type") == "zero_order" and t.find("dynamics/param") is None
    conv = t.find("conversion")
    assert conv.get("type") == "table"
    assert (
        len(floats(conv.find("param[@name='input']").get("value")))
        == len(floats(conv.find("param[@name='output']").get("value")))
        >= 2
    )
    # Everything else is unchanged.
    default = robot_xml("UX_3")
    assert ET.tostring(hydro(default).find("hydrodynamics")) == ET.tostring(hydro(robot).find("hydrodynamics"))


# ----------------------------------------------------------------------------------------------
# worlds
# ----------------------------------------------------------------------------------------------
WORLD_KEYS = {
    "name",
    "gravity",
    "water",
    "atmospheric_pressure",
    "visibility",
    "ray_caster",
    "current",
    "meshes",
    "robots",
}
MESH_KEYS = {"name", "file", "scale", "xyz", "rpy", "collision", "visual"}
ROBOT_KEYS = {"name", "description", "xyz", "rpy"}


def load_world(file_name):
    with open(WORLDS_DIR / file_name) as f:
        return yaml.safe_load(f)


def placed_mesh(world_file, entry):
    """The entry's mesh in world coordinates (scale, then rpy rotation, then xyz)."""
    import trimesh

    mesh = trimesh.load(str((WORLDS_DIR / world_file).parent / entry["file"]), force="mesh")
    transform = np.eye(4)
    transform[:3, :3] = rpy_matrix(entry["rpy"]) @ np.diag(entry["scale"])
    transform[:3, 3] = entry["xyz"]
    mesh.apply_transform(transform)
    return mesh


def interior_bounds(mesh):
    """Bounds of the faces that face the inside of a box-shaped container (normals towards its centre)."""
    centre = mesh.bounds.mean(axis=0)
    inward = np.einsum("ij,ij->i", mesh.triangles_center - centre, mesh.face_normals) < 0
    assert inward.any(), "container mesh has no inward-facing faces"
    vertices = mesh.vertices[np.unique(mesh.faces[inward])]
    return vertices.min(axis=0), vertices.max(axis=0)


def gap_to_box(point, lo, hi):
    """Distance from a point to an axis-aligned box (0 inside)."""
    return float(np.linalg.norm(np.maximum(0.0, np.maximum(lo - point, point - hi))))


def robot_radius(world_robot):
    assert (URDF_DIR / world_robot["description"]).exists()
    robot = robot_xml(world_robot["name"])
    return hydro_value(robot, "radius")[0]


@pytest.mark.parametrize("world_file", SHIPPED_WORLDS)
def test_world_schema(world_file):
    world = load_world(world_file)
    assert set(world) == WORLD_KEYS
    assert world["name"] == Path(world_file).stem
    assert world["gravity"] == pytest.approx(9.81)
    assert set(world["water"]) == {"density", "surface_z"} and world["water"]["density"] > 0
    assert world["atmospheric_pressure"] == pytest.approx(101325.0)
    assert world["visibility"]["level"] in ("none", "low", "medium", "high")
    assert len(world["visibility"]["colour"]) == 3
    assert world["ray_caster"] in ("embree", "bullet")
    assert set(world["current"]) == {"speed", "horizontal_angle", "vertical_angle"}
    for var in world["current"].values():
        assert set(var) == {"mean", "min", "max", "noise", "mu"}
        assert var["min"] <= var["mean"] <= var["max"]
    for entry in world["meshes"]:
        assert MESH_KEYS <= set(entry) <= MESH_KEYS | {"albedo", "material"}
        path = (WORLDS_DIR / world_file).parent / entry["file"]
        assert path.is_file(), "missing mesh " + str(path)
        assert path.stat().st_size < 200 * 1024
        for key in ("scale", "xyz", "rpy"):
            assert len(entry[key]) == 3
        assert isinstance(entry["collision"], bool) and isinstance(entry["visual"], bool)
    names = [r["name"] for r in world["robots"]]
    assert names == ["UX_1", "UX_2", "UX_3"]
    for r in world["robots"]:
        assert set(r) == ROBOT_KEYS
        assert (URDF_DIR / r["description"]).is_file()
        assert len(r["xyz"]) == 3 and len(r["rpy"]) == 3


@pytest.mark.parametrize("world_file", SHIPPED_WORLDS)
def test_spawns_inside_container_and_submerged(world_file):
    world = load_world(world_file)
    meshes = {e["name"]: placed_mesh(world_file, e) for e in world["meshes"]}
    container = max(meshes, key=lambda n: np.prod(meshes[n].extents))
    lo, hi = interior_bounds(meshes[container])
    for r in world["robots"]:
        p, radius = np.array(r["xyz"], float), robot_radius(r)
        assert np.all(p - lo >= radius) and np.all(hi - p >= radius), (
            "%s at %s is within %g m of a wall of %s [%s .. %s]" % (r["name"], p, radius, container, lo, hi)
        )
        assert p[2] + radius <= world["water"]["surface_z"], r["name"] + " is not fully submerged"
        for name, mesh in meshes.items():
            if name != container:
                assert gap_to_box(p, *mesh.bounds) >= radius, "%s overlaps %s" % (r["name"], name)


def test_tank_scene():
    world = load_world("tank.world")
    meshes = {e["name"]: placed_mesh("tank.world", e) for e in world["meshes"]}
    lo, hi = interior_bounds(meshes["tank"])
    assert np.allclose(lo, [-3, -2, -3], atol=1e-5) and np.allclose(hi, [3, 2, 0.3], atol=1e-5)
    assert world["water"]["surface_z"] == 0.0
    anchor = meshes["anchor"]
    assert anchor.bounds[1][2] == pytest.approx(-1.8, abs=1e-5)  # top at 1.8 m depth
    assert 0.5 <= anchor.extents[2] <= 0.7  # about 0.6 m tall
    assert np.allclose(anchor.bounds.mean(axis=0)[:2], 0.0, atol=0.05)  # in the middle
    clearance = 0.8  # [m] of water between a hull and anything else
    robots = world["robots"]
    for r in robots:
        p, radius = np.array(r["xyz"], float), robot_radius(r)
        assert p[2] == pytest.approx(-1.0)
        assert np.all(p - lo - radius >= clearance - 1e-9) and np.all(hi[:2] - p[:2] - radius >= clearance - 1e-9)
        assert gap_to_box(p, *anchor.bounds) - radius >= clearance
    for i in range(len(robots)):
        for j in range(i + 1, len(robots)):
            gap = np.linalg.norm(np.subtract(robots[i]["xyz"], robots[j]["xyz"])) - 2 * R_HULL
            assert gap >= clearance, "%s and %s are %.2f m apart" % (robots[i]["name"], robots[j]["name"], gap)


def test_tank_target_scene():
    """tank_target.world is tank.world and the checkerboard plate, its 9 x 7 squares of 8 cm and 6 cm margin filling
    the plate (docs/worlds.md)."""
    tank, target = load_world("tank.world"), load_world("tank_target.world")
    assert target["robots"] == tank["robots"] and target["meshes"][:2] == tank["meshes"]
    plate = target["meshes"][2]
    material = plate["material"]
    assert material["kind"] == "checkerboard" and plate["collision"]
    extents = placed_mesh("tank.world", dict(plate, xyz=[0, 0, 0], rpy=[0, 0, 0])).extents
    squares = np.array([material["columns"], material["rows"]]) * material["square"]
    assert np.allclose(extents[:2], squares + 2 * material["border"], atol=1e-6) and extents[2] == pytest.approx(0.01)


def test_test_box_scene():
    world = load_world("test_box.world")
    lo, hi = interior_bounds(placed_mesh("test_box.world", world["meshes"][0]))
    assert np.allclose(hi - lo, [4, 4, 4], atol=1e-5)
    assert world["water"]["surface_z"] >= hi[2] + 10
    spawns = np.array([r["xyz"] for r in world["robots"]], float)
    assert np.allclose(spawns[0], (lo + hi) / 2, atol=1e-9)
    gaps = [np.linalg.norm(spawns[i] - spawns[j]) for i in range(3) for j in range(i + 1, 3)]
    assert min(gaps) == pytest.approx(1.2)


def test_mesh_normals_face_the_water():
    """Tank and box are closed, consistently wound solids: their water-side faces point into the water."""
    import trimesh

    for file_name in ("tank.stl", "test_box.stl"):
        mesh = trimesh.load(str(WORLDS_DIR / "meshes" / file_name), force="mesh")
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
    box = trimesh.load(str(WORLDS_DIR / "meshes" / "test_box.stl"), force="mesh")
    # A ray from the centre hits an inner face whose normal points back at the centre.
    inner = np.abs(box.triangles_center).max(axis=1) < 2.0 + 1e-6
    assert inner.sum() == 12
    assert np.all(np.einsum("ij,ij->i", box.triangles_center[inner], box.face_normals[inner]) < 0)


def test_meshes_are_binary_stl_and_reproducible(tmp_path):
    """The committed meshes are exactly what worlds/tools/make_tank.py writes."""
    subprocess.run(
        [sys.executable, str(WORLDS_DIR / "tools" / "make_tank.py"), "--out", str(tmp_path)],
        check=True,
        capture_output=True,
    )
    for file_name in ("tank.stl", "anchor.stl", "test_box.stl", "target.stl"):
        committed = (WORLDS_DIR / "meshes" / file_name).read_bytes()
        count = int.from_bytes(committed[80:84], "little")
        assert len(committed) == 84 + 50 * count, file_name + " is not a binary STL"
        assert len(committed) < 200 * 1024
        assert committed == (tmp_path / file_name).read_bytes(), file_name + " differs from the generator's"

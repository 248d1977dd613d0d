"""Frames of the UX-1's cameras rendered in-process (unexmin.core, visual mode, seeded noise) for the vision judges
(test_camera_calibration.py, test_camera_rectify.py, test_camera_vo.py; docs/vision.md "Tests").

- `description(folder, **properties)`: UX_1's description expanded by xacro with properties.xacro's values
  overridden (e.g. camera_0_width=640), as `UX_1_overrides:=` does;
- `world_file(folder, base, robot_pose, meshes)`: a world file beside links to the shipped meshes: the shipped
  world `base` with UX_1 at `robot_pose` (its other robots dropped) and `meshes` added;
- `camera_pose(urdf, camera)`: the optical frame's pose in base_link from the description's joints;
- rotations: `rpy_matrix`, `angle_of`.
"""

import shutil
import subprocess
from pathlib import Path
from xml.etree import ElementTree

import cv2
import numpy as np
import yaml

from unexmin.geometry import rpy_matrix
from unexmin.worlds.files import link_meshes

REPO = Path(__file__).resolve().parents[2]


def description(folder, **properties):
    """UX_1's URDF text with each properties.xacro property `name` set to `value` (an overrides file in `folder`)."""
    xacro = shutil.which("xacro")
    assert xacro, "xacro not on PATH: source scripts/env.sh"
    lines = [f'  <xacro:property name="{k}" value="{v}"/>' for k, v in properties.items()]
    overrides = Path(folder) / "overrides.xacro"
    overrides.write_text(
        '<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        + "\n".join(lines)
        + "\n</robot>\n"
    )
    args = [xacro, str(REPO / "urdf" / "ux1.urdf.xacro"), "name:=UX_1", f"overrides:={overrides}"]
    return subprocess.run(args, check=True, capture_output=True, text=True).stdout


def world_file(folder, base, robot_pose, meshes=(), name="view"):
    """worlds/<base>.world with UX_1 at robot_pose = (x, y, z, roll, pitch, yaw) [m, rad] and `meshes` (world-file
    mesh entries, files relative to worlds/) added, written as <folder>/<name>.world beside links to the meshes."""
    world = yaml.safe_load((REPO / "worlds" / f"{base}.world").read_text())
    world["meshes"] = list(world["meshes"]) + [dict(m) for m in meshes]
    robot = dict(world["robots"][0], name="UX_1", xyz=list(robot_pose[:3]), rpy=list(robot_pose[3:]))
    world["robots"] = [robot]
    folder = Path(folder)
    link_meshes(world["meshes"], str(REPO / "worlds"), str(folder))
    path = folder / f"{name}.world"
    path.write_text(yaml.safe_dump(world))
    return path


def _origin(element):
    origin = element.find("origin")
    xyz = [float(v) for v in (origin.get("xyz", "0 0 0") if origin is not None else "0 0 0").split()]
    rpy = [float(v) for v in (origin.get("rpy", "0 0 0") if origin is not None else "0 0 0").split()]
    return np.array(xyz), rpy_matrix(rpy)


def camera_pose(urdf, camera="camera_0", robot="UX_1"):
    """(t, R) of <robot>/<camera>_optical_frame in <robot>/base_link [m], from the URDF's fixed joints."""
    joints = {j.find("child").get("link"): j for j in ElementTree.fromstring(urdf).iter("joint")}
    link, t, R = f"{robot}/{camera}_optical_frame", np.zeros(3), np.eye(3)
    while link != f"{robot}/base_link":
        joint = joints[link]
        assert joint.get("type") == "fixed", f"{joint.get('name')} is not fixed"
        tj, Rj = _origin(joint)
        t, R = tj + Rj @ t, Rj @ R
        link = joint.find("parent").get("link")
    return t, R


def angle_of(R):
    """Rotation angle of rotation matrix R [rad]."""
    return float(np.arccos(np.clip((np.trace(R) - 1.0) / 2.0, -1.0, 1.0)))


def rpy_of(R):
    """(roll, pitch, yaw) [rad] of rotation matrix R = Rz(yaw) Ry(pitch) Rx(roll)."""
    return (
        float(np.arctan2(R[2, 1], R[2, 2])),
        float(-np.arcsin(np.clip(R[2, 0], -1.0, 1.0))),
        float(np.arctan2(R[1, 0], R[0, 0])),
    )


def axis_rotation(axis, angle):
    """Rotation by `angle` [rad] about coordinate axis 0 (x), 1 (y) or 2 (z)."""
    rpy = [0.0, 0.0, 0.0]
    rpy[axis] = angle
    return rpy_matrix(rpy)


def render(world, urdf, camera="camera_0", seed=1, visibility=""):
    """The first frame of UX_1's `camera` in world file `world` (visual mode, only the camera family, noise seeded by
    `seed`; the first sample is at t = 1/rate, the robot still at its spawn pose to well under a millimetre):
    (image rows x columns x 3 uint8 RGB, K 3 x 3, D 5)."""
    from unexmin.core import World

    w = World(
        str(world), seed=seed, sensors="camera", visibility=visibility, mode="visual", descriptions={"UX_1": urdf}
    )
    ux = w.robot("UX_1")
    while ux.sample(camera)["count"] == 0:
        assert w.time < 1.0, f"{camera}: no frame in 1 s"
        w.step(1)
    s = ux.sample(camera)
    assert s["rendered"], f"{camera} rendered no frame"
    return s["image"].copy(), s["K"].copy(), s["D"].copy()


# The tank's checkerboard target (worlds/tank_target.world, docs/worlds.md): 9 x 7 squares of 0.08 m, 8 x 6 inner
# corners; camera 0 at 640 x 480 for the judges.
SQUARE, ROWS, COLUMNS = 0.08, 7, 9
SIZE = (640, 480)  # [px]
# [m, rad] UX_1 in the tank for the checkerboard views: camera 0 (20 deg left of the bow) looks along +x, 5 m of water
TANK_POSE = (-2.0, -1.0, -1.5, 0.0, 0.0, -0.349)


def camera_0(folder, broad_lights=False):
    """UX_1's description with camera 0 at 640 x 480, the other cameras at 32 x 24 (cheap), the SLS lasers off.
    broad_lights: the LEDs' beams made broad (cone 170 deg, cos^1 instead of cos^4), so that a target anywhere in
    camera 0's image is lit, as in a lit calibration tank (the UX-1's own LED lights only the right half of camera
    0's view: the camera sits 20 deg left of SLS 0's LED), and the exposure 3 instead of 20 so that the white squares
    0.6-1.5 m away do not saturate."""
    lights = {"sls_light_cone": 2.967, "sls_light_exponent": 1.0, "camera_exposure": 3.0} if broad_lights else {}
    return description(
        folder,
        camera_width=SIZE[0],
        camera_height=SIZE[1],
        camera_render_scale=0.05,
        camera_0_render_scale=1.0,
        sls_laser_power=0.0,
        **lights,
    )


def board_mesh(t, R):
    """The target plate (worlds/meshes/target.stl, checkerboard) at position t [m] and rotation R in the world."""
    return {
        "name": "target",
        "file": "meshes/target.stl",
        "xyz": [float(v) for v in t],
        "rpy": list(rpy_of(R)),
        "collision": True,
        "visual": True,
        "material": {"kind": "checkerboard", "square": SQUARE, "rows": ROWS, "columns": COLUMNS, "border": 0.06},
    }


def square_corners():
    """Every corner of the squares in the board's frame [m] (the inner ones and the outline), row by row."""
    x = (np.arange(COLUMNS + 1) - COLUMNS / 2) * SQUARE
    y = (np.arange(ROWS + 1) - ROWS / 2) * SQUARE
    return np.array([[a, b, 0.0] for b in y for a in x])


def in_view(centre, R_cb, K, D, margin):
    """Whether every square of the board at `centre` [m], rotation R_cb in camera 0's optical frame, is in the image
    at least `margin` px from its edges (projected with K, D)."""
    points = centre + square_corners() @ R_cb.T
    if points[:, 2].min() < 0.3:
        return False
    pixels = cv2.projectPoints(points, np.zeros(3), np.zeros(3), K, D)[0].reshape(-1, 2)
    return bool((pixels >= margin).all() and (pixels <= np.array(SIZE) - 1 - margin).all())


def board_in_world(urdf, robot_pose, centre, R_cb):
    """(t, R) in the world of the board at `centre` [m], rotation R_cb in camera 0's optical frame, UX_1 at
    robot_pose = (x, y, z, roll, pitch, yaw)."""
    t_bc, R_bc = camera_pose(urdf, "camera_0")
    R_wb = rpy_matrix(robot_pose[3:])
    t_wc, R_wc = np.array(robot_pose[:3]) + R_wb @ t_bc, R_wb @ R_bc
    return t_wc + R_wc @ centre, R_wc @ R_cb


__all__ = [
    "TANK_POSE",
    "COLUMNS",
    "ROWS",
    "SIZE",
    "SQUARE",
    "board_in_world",
    "board_mesh",
    "camera_0",
    "in_view",
    "square_corners",
    "REPO",
    "angle_of",
    "axis_rotation",
    "camera_pose",
    "description",
    "render",
    "rpy_matrix",
    "rpy_of",
    "world_file",
]

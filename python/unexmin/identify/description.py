"""The physics of a robot description (urdf/ux1.urdf.xacro [+ overrides]) as plain numbers.

The identification needs the parameters it does not estimate (volume, inertia, thruster geometry and
dynamics, pendulum, VBS) and the nominal values of those it does (its prior and the reference for
flat directions). They are read from the expanded xacro: the <unexmin> block the simulator reads
(docs/robot_description.md) and the thruster joints' origins.
"""

import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from unexmin.geometry import rpy_matrix

REPO = Path(__file__).resolve().parents[3]
ROBOT_FILE = REPO / "urdf" / "ux1.urdf.xacro"


class DescriptionError(ValueError):
    """A robot description that cannot be expanded or lacks what the identification needs."""


@dataclass
class Thruster:
    id: int
    position: np.ndarray  # [m] body frame
    direction: np.ndarray  # unit thrust direction, body frame
    tau: float  # [s] first-order time constant (0: zero order)
    thrust_min: float  # [N]
    thrust_max: float  # [N]
    command_min: float  # [command unit]
    command_max: float
    timeout: float  # [s] watchdog (<= 0: off)
    conversion: str  # identity | table | basic
    gain: float = 1.0  # thrust gain of a linear table (thruster_gain_*: a two-point table), else 1

    @property
    def horizontal(self):
        return abs(self.direction[2]) < 1e-6


@dataclass
class RobotPhysics:
    """Numbers of the <unexmin> block. Body frame x forward, y left, z up; origin at the hull centre."""

    mass: float  # [kg] dry mass incl. pendulum, VBS empty
    volume: float  # [m^3]
    radius: float  # [m]
    cog_base: np.ndarray  # [m] CG of the vehicle less the pendulum
    cob: np.ndarray  # [m]
    inertia: np.ndarray  # [kg m^2] principal moments
    added_mass: np.ndarray  # 6 x 6
    linear_damping: np.ndarray  # 6
    quadratic_damping: np.ndarray  # 6
    thrusters: list
    pendulum_mass: float = 0.0  # [kg]
    pendulum_arm: float = 0.0  # [m]
    pendulum_speed: float = 1.0  # [rad/s]
    pendulum_min: float = 0.0  # [rad]
    pendulum_max: float = 0.0
    vbs_min: float = 0.0  # [kg]
    vbs_max: float = 0.0
    vbs_position: np.ndarray = None  # [m]

    @property
    def cog(self):
        """[m] whole-vehicle centre of gravity, pendulum at 0 rad, VBS empty, body frame."""
        return (
            (self.mass - self.pendulum_mass) * self.cog_base
            + self.pendulum_mass * np.array([0.0, 0.0, -self.pendulum_arm])
        ) / self.mass

    def groups(self):
        """{'horizontal': [ids], 'vertical': [ids]} of the thrusters (vertical: any thrust along z)."""
        return {
            "horizontal": [t.id for t in self.thrusters if t.horizontal],
            "vertical": [t.id for t in self.thrusters if not t.horizontal],
        }


def xacro_executable():
    """xacro of the running interpreter's venv, else $XACRO, else PATH."""
    for candidate in (os.environ.get("XACRO"), str(Path(sys.executable).parent / "xacro"), shutil.which("xacro")):
        if candidate and Path(candidate).is_file():
            return candidate
    raise DescriptionError("xacro not found: install xacro==1.13.3 (scripts/setup.sh) or set $XACRO")


def expand(description=ROBOT_FILE, name="UX_1", overrides=None):
    """URDF text of the xacro `description` for robot `name`, with an optional overrides file."""
    args = [xacro_executable(), str(description), f"name:={name}"]
    if overrides:
        args.append(f"overrides:={Path(overrides).resolve()}")
    proc = subprocess.run(args, capture_output=True, text=True)
    if proc.returncode != 0:
        raise DescriptionError(f"xacro {description} {' '.join(args[2:])} failed: {proc.stderr.strip()}")
    return proc.stdout


def _floats(text, n, what):
    values = [float(v) for v in str(text).split()]
    if len(values) != n:
        raise DescriptionError(f"{what}: expected {n} numbers, got {text!r}")
    return np.array(values)


def _table_gain(conversion):
    """Slope of a `table` conversion that is one straight line through zero (how thruster_gain_* is
    emitted), else 1."""
    if conversion is None or conversion.get("type") != "table":
        return 1.0
    x = [float(v) for v in conversion.find("param[@name='input']").get("value").split()]
    y = [float(v) for v in conversion.find("param[@name='output']").get("value").split()]
    slopes = [b / a for a, b in zip(x, y) if a != 0.0]
    if (
        slopes
        and all(abs(k - slopes[0]) < 1e-9 * max(1.0, abs(slopes[0])) for k in slopes)
        and all(b == 0.0 for a, b in zip(x, y) if a == 0.0)
    ):
        return slopes[0]
    return 1.0


def parse(urdf):
    """RobotPhysics of an expanded URDF (text)."""
    root = ET.fromstring(urdf)
    hydro = root.find("unexmin/hydrodynamics")
    if hydro is None:
        raise DescriptionError("the description has no <unexmin><hydrodynamics> block")

    def attr(tag, key="value", n=1):
        el = hydro.find(tag)
        if el is None:
            raise DescriptionError(f"<hydrodynamics> has no <{tag}>")
        v = _floats(el.get(key), n, f"<{tag} {key}>")
        return float(v[0]) if n == 1 else v

    inertia = hydro.find("inertia")
    joints = {j.get("name"): j for j in root.findall("joint")}
    thrusters = []
    for el in root.findall("unexmin/thruster"):
        joint = joints.get(el.get("joint"))
        if joint is None:
            raise DescriptionError(f"thruster {el.get('id')}: no joint {el.get('joint')}")
        origin = joint.find("origin")
        rot = rpy_matrix(_floats(origin.get("rpy", "0 0 0"), 3, "joint rpy"))
        axis = _floats(joint.find("axis").get("xyz") if joint.find("axis") is not None else "1 0 0", 3, "axis")
        dyn = el.find("dynamics")
        tau = 0.0
        if dyn.get("type") == "first_order":
            tau = float(dyn.find("param[@name='tau']").get("value"))
        thrusters.append(
            Thruster(
                id=int(el.get("id")),
                position=_floats(origin.get("xyz", "0 0 0"), 3, "joint xyz"),
                direction=rot @ axis / np.linalg.norm(axis),
                tau=tau,
                thrust_min=float(el.find("thrust").get("min")),
                thrust_max=float(el.find("thrust").get("max")),
                command_min=float(el.find("command").get("min")),
                command_max=float(el.find("command").get("max")),
                timeout=float(el.find("timeout").get("value")),
                conversion=el.find("conversion").get("type"),
                gain=_table_gain(el.find("conversion")),
            )
        )
    physics = RobotPhysics(
        mass=attr("mass"),
        volume=attr("volume"),
        radius=attr("radius"),
        cog_base=attr("center_of_gravity", "xyz", 3),
        cob=attr("center_of_buoyancy", "xyz", 3),
        inertia=np.array([float(inertia.get(k)) for k in ("ixx", "iyy", "izz")]),
        added_mass=attr("added_mass", n=36).reshape(6, 6),
        linear_damping=attr("linear_damping", n=6),
        quadratic_damping=attr("quadratic_damping", n=6),
        thrusters=sorted(thrusters, key=lambda t: t.id),
        vbs_position=np.zeros(3),
    )
    pend = root.find("unexmin/pendulum")
    if pend is not None:
        physics.pendulum_mass, physics.pendulum_arm = float(pend.get("mass")), float(pend.get("arm"))
        physics.pendulum_speed = float(pend.get("speed"))
        physics.pendulum_min, physics.pendulum_max = float(pend.get("min")), float(pend.get("max"))
    vbs = root.find("unexmin/vbs")
    if vbs is not None:
        physics.vbs_min, physics.vbs_max = float(vbs.get("min")), float(vbs.get("max"))
        physics.vbs_position = _floats(vbs.get("xyz", "0 0 0"), 3, "<vbs xyz>")
    return physics


def load(description=ROBOT_FILE, name="UX_1", overrides=None):
    """RobotPhysics of a xacro robot file (expanded for `name`, with `overrides`)."""
    return parse(expand(description, name, overrides))


def rest_attitude(physics):
    """(roll, pitch) [rad] at which the robot rests (pendulum 0, VBS empty): centre of gravity straight
    below the centre of buoyancy. ZYX Euler, pitch positive nose down (thesis 7 convention of
    urdf/ux1_perturbed.xacro)."""
    g = physics.cog - physics.cob
    lever = np.linalg.norm(g)
    if lever < 1e-12:
        return 0.0, 0.0
    # g = -L (-sin p, sin r cos p, cos r cos p) in the body frame
    pitch = float(np.arcsin(np.clip(g[0] / lever, -1.0, 1.0)))
    roll = float(np.arctan2(-g[1], -g[2]))
    return roll, pitch

"""The actuators of a robot description, read for the allocator: thrusters and fins with their poses, families and
limits. Pure Python, no ROS.

read_actuators(xml) parses an expanded robot description (URDF with the simulator's `<unexmin>` block,
docs/robot_description.md) the way the simulator does: an actuator's pose is its joint's frame in base_link (the
root link) with every joint at zero, its axis the joint's `<axis>` (URDF default 1 0 0) in base_link, a fin's chord
at angle 0 the joint frame's x axis. Positions [m], body frame x forward, y left, z up (REP-103).

Each thrust-conversion family the simulator knows has its inverse here (thrust [N] -> command in the thruster's own
unit), registered by the family's name in CONVERSIONS; each fin lift family its lift slope in LIFT_SLOPES.
"""

import math
from dataclasses import dataclass, field
from xml.etree import ElementTree

import numpy as np

from unexmin.geometry import rpy_matrix


class DescriptionError(ValueError):
    """The robot description lacks what the allocator needs, or has a family it cannot invert; the message names
    the element."""


@dataclass
class Thruster:
    """One <thruster>: thrust along `axis` at `position` (body frame), command -> thrust by its conversion family."""

    id: int
    position: np.ndarray  # [m]
    axis: np.ndarray  # unit, body frame
    conversion: str
    params: dict = field(default_factory=dict)  # the conversion's <param>s, numbers or lists of numbers
    thrust_min: float = 0.0  # [N]
    thrust_max: float = 0.0  # [N]
    command_min: float = 0.0  # command unit
    command_max: float = 0.0


@dataclass
class Fin:
    """One <fin>: turns about `axis` (span) at `position`; at angle 0 its chord is `chord` (body frame)."""

    id: int
    position: np.ndarray  # [m]
    axis: np.ndarray  # unit span
    chord: np.ndarray  # unit
    model: str
    params: dict = field(default_factory=dict)
    area: float = 0.0  # [m^2]
    angle_min: float = 0.0  # [rad]
    angle_max: float = 0.0  # [rad]

    @property
    def movable(self):
        """False for a fixed surface (limits 0, 0: a body-lift term)."""
        return self.angle_max > self.angle_min


def _numbers(text, where, count=None):
    try:
        values = [float(v) for v in str(text).split()]
    except ValueError:
        raise DescriptionError(f"{where}: expected numbers, got {text!r}") from None
    if count is not None and len(values) != count:
        raise DescriptionError(f"{where}: expected {count} numbers, got {text!r}")
    return values


def _attr(element, name, where):
    if element is None or element.get(name) is None:
        raise DescriptionError(f"{where}: missing attribute '{name}'")
    return _numbers(element.get(name), f"{where}@{name}", 1)[0]


def _params(element, where):
    out = {}
    for p in element.findall("param") if element is not None else ():
        values = _numbers(p.get("value", ""), f"{where}/param[{p.get('name')}]")
        out[p.get("name")] = values[0] if len(values) == 1 else values
    return out


def _joint_frames(robot):
    """joint name -> (position [m], rotation) of the joint's frame in the root link, every joint at zero."""
    joints = {j.get("name"): j for j in robot.findall("joint")}
    by_child = {j.find("child").get("link"): j for j in joints.values()}

    def origin(j):
        o = j.find("origin")
        xyz = _numbers(o.get("xyz", "0 0 0"), f"joint {j.get('name')}/origin@xyz", 3) if o is not None else [0] * 3
        rpy = _numbers(o.get("rpy", "0 0 0"), f"joint {j.get('name')}/origin@rpy", 3) if o is not None else [0] * 3
        return np.array(xyz), rpy_matrix(rpy)

    def frame(j):
        chain = [j]
        link = j.find("parent").get("link")
        while link in by_child:
            chain.append(by_child[link])
            link = by_child[link].find("parent").get("link")
        p, rot = np.zeros(3), np.eye(3)
        for k in reversed(chain):
            xyz, r = origin(k)
            p, rot = p + rot @ xyz, rot @ r
        return p, rot

    return joints, frame


def _pose(element, joints, frame, where):
    name = element.get("joint")
    if name not in joints:
        raise DescriptionError(f"{where}: joint '{name}' is not in the description")
    p, rot = frame(joints[name])
    a = joints[name].find("axis")
    axis = np.array(_numbers(a.get("xyz"), f"joint {name}/axis@xyz", 3) if a is not None else [1.0, 0.0, 0.0])
    if np.linalg.norm(axis) < 1e-9:
        raise DescriptionError(f"joint {name}/axis has zero length")
    return p, rot, rot @ (axis / np.linalg.norm(axis))


def read_actuators(xml, source="robot_description"):
    """(thrusters, fins) of the expanded description `xml` (a string), each sorted by id. `source` names the
    description in errors."""
    try:
        robot = ElementTree.fromstring(xml)
    except ElementTree.ParseError as e:
        raise DescriptionError(f"{source}: not XML ({e})") from None
    block = robot.find("unexmin")
    if block is None:
        raise DescriptionError(f"{source}: no <unexmin> block (docs/robot_description.md)")
    joints, frame = _joint_frames(robot)
    thrusters, fins = [], []
    for t in block.findall("thruster"):
        where = f"{source}: <thruster id={t.get('id')}>"
        p, _, axis = _pose(t, joints, frame, where)
        conv = t.find("conversion")
        thrust, command = t.find("thrust"), t.find("command")
        lo, hi = _attr(thrust, "min", where + "/thrust"), _attr(thrust, "max", where + "/thrust")
        thrusters.append(
            Thruster(
                id=int(t.get("id")),
                position=p,
                axis=axis,
                conversion=conv.get("type", "") if conv is not None else "identity",
                params=_params(conv, where + "/conversion"),
                thrust_min=lo,
                thrust_max=hi,
                command_min=_attr(command, "min", where + "/command") if command is not None else lo,
                command_max=_attr(command, "max", where + "/command") if command is not None else hi,
            )
        )
    for f in block.findall("fin"):
        where = f"{source}: <fin id={f.get('id')}>"
        p, rot, axis = _pose(f, joints, frame, where)
        model = f.find("model")
        angle = f.find("angle")
        fins.append(
            Fin(
                id=int(f.get("id")),
                position=p,
                axis=axis,
                chord=rot[:, 0],
                model=model.get("type", "") if model is not None else "",
                params=_params(model, where + "/model"),
                area=_attr(f.find("area"), "value", where + "/area"),
                angle_min=_attr(angle, "min", where + "/angle"),
                angle_max=_attr(angle, "max", where + "/angle"),
            )
        )
    thrusters.sort(key=lambda a: a.id)
    fins.sort(key=lambda a: a.id)
    return thrusters, fins


# ------------------------------------------------------------------------------------------------------------------
# Inverse thrust conversions, by family name: thrust [N] -> command (the thruster's unit)
# ------------------------------------------------------------------------------------------------------------------
def _identity(thruster, thrust):
    return thrust


def _basic(thruster, thrust):
    """thrust = gain w |w|  ->  w = sign(thrust / gain) sqrt(|thrust / gain|)."""
    gain = thruster.params.get("gain")
    if not gain:
        raise DescriptionError(f"<thruster id={thruster.id}>: conversion 'basic' needs a non-zero 'gain'")
    ratio = thrust / gain
    return math.copysign(math.sqrt(abs(ratio)), ratio)


def _table(thruster, thrust):
    """Inverse of the piecewise-linear table (input, output): the outputs must not decrease. A thrust on a flat part
    (a dead band, within 1e-9 N) maps to the middle of its inputs; beyond the ends to the end inputs."""
    x = np.atleast_1d(np.asarray(thruster.params.get("input", []), float))
    y = np.atleast_1d(np.asarray(thruster.params.get("output", []), float))
    if x.size < 2 or x.size != y.size or np.any(np.diff(y) < 0.0):
        raise DescriptionError(
            f"<thruster id={thruster.id}>: conversion 'table' cannot be inverted: expected input and output of the "
            "same length >= 2 with the output not decreasing"
        )
    if thrust <= y[0]:
        return float(x[0])
    if thrust >= y[-1]:
        return float(x[-1])
    on = np.flatnonzero(np.abs(y - thrust) <= 1e-9)  # [N] rounding of the allocation: on the plateau
    if on.size:
        return float(0.5 * (x[on[0]] + x[on[-1]]))
    k = int(np.searchsorted(y, thrust)) - 1  # y[k] < thrust < y[k + 1]
    return float(x[k] + (thrust - y[k]) * (x[k + 1] - x[k]) / (y[k + 1] - y[k]))


def _forward_table(thruster, command):
    x = np.asarray(thruster.params["input"], float)
    y = np.asarray(thruster.params["output"], float)
    return float(np.interp(command, x, y))


#: conversion family name -> (inverse: thrust [N] -> command, forward: command -> thrust [N]).
CONVERSIONS = {
    "identity": (_identity, lambda t, c: c),
    "basic": (_basic, lambda t, c: t.params["gain"] * c * abs(c)),
    "table": (_table, _forward_table),
}

#: fin lift family name -> lift slope dC_L/d(alpha) [1/rad] at zero angle of attack, from its <param>s.
LIFT_SLOPES = {"linear_lift": lambda fin: float(fin.params.get("lift_slope", 0.0))}


def conversion_of(thruster):
    """(inverse, forward) of the thruster's conversion family; DescriptionError naming the known ones."""
    if thruster.conversion not in CONVERSIONS:
        raise DescriptionError(
            f"<thruster id={thruster.id}>: conversion '{thruster.conversion}' has no inverse in the allocator "
            f"(known: {', '.join(sorted(CONVERSIONS))})"
        )
    return CONVERSIONS[thruster.conversion]


def lift_slope_of(fin):
    """dC_L/d(alpha) [1/rad] of the fin's lift family; DescriptionError naming the known ones."""
    if fin.model not in LIFT_SLOPES:
        raise DescriptionError(
            f"<fin id={fin.id}>: lift model '{fin.model}' is unknown to the allocator (known: {', '.join(LIFT_SLOPES)})"
        )
    return LIFT_SLOPES[fin.model](fin)

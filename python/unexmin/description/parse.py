"""One parse of an expanded robot description (URDF text) into a RobotDescription, by the simulator's rules
(cpp/unexmin/sim/description_*.cpp, docs/robot_description.md): the links and the joint tree, then one stage per
entity (hydrodynamics, thrusters, fins, pendulum, ballast, magnetic, sensors), in the simulator's order.

The parser's own rules are the simulator's: which elements and attributes are required, their defaults and number
counts, joints and links that must exist, actuator ids 0..n-1, actuators inside the hull, unique sensor names with a
rate > 0, a pendulum lighter than the vehicle. The ranges of the models' parameters (mass > 0, a symmetric added
mass, a family's own parameters, the fin and pendulum limits) are checked by the models the simulator builds from the
record (cpp/unexmin/hydro), not here.
"""

import math
from xml.etree import ElementTree

import numpy as np

from unexmin.description.reader import Reader, c_number, number_text, text_of
from unexmin.description.records import (
    Fin,
    Hydrodynamics,
    Joint,
    Magnetics,
    Pendulum,
    RobotDescription,
    Sensor,
    Thruster,
    Vbs,
)
from unexmin.geometry import rpy_matrix

_HULL_SLACK = 1e-6  # [m] rounding of the expanded description


def parse(xml, source="robot_description"):
    """The RobotDescription of the expanded description `xml` (a string); `source` names it in errors."""
    r = Reader(source)
    try:
        robot = ElementTree.fromstring(xml)
    except ElementTree.ParseError as e:
        r.fail(f"not valid XML: {e}")
    if robot.tag != "robot":
        r.fail("no <robot> element")
    links = {link.get("name") for link in robot.findall("link") if link.get("name") is not None}
    joints = [_joint(r, j, links) for j in robot.findall("joint")]
    ext = robot.find("unexmin")
    if ext is None:
        r.fail("no <unexmin> element (hydrodynamics, thrusters, pendulum, vbs)")
    base_link, hydro = _hydrodynamics(r, ext, links)
    d = RobotDescription(
        source=source,
        name=text_of(robot, "name"),
        base_link=base_link,
        hydro=hydro,
        joints=joints,
        thrusters=[],
        fins=[],
        pendulum=Pendulum(),
        vbs=Vbs(),
        sensors=[],
    )
    d.thrusters = _by_id(r, [_thruster(r, t, d) for t in ext.findall("thruster")], "thruster")
    d.fins = _by_id(r, [_fin(r, f, d) for f in ext.findall("fin")], "fin")
    d.pendulum = _pendulum(r, ext.find("pendulum"), d)
    d.vbs = _ballast(r, ext.find("vbs"))
    d.magnetics = _magnetics(r, ext, d)
    for s in ext.findall("sensor"):
        d.sensors.append(_sensor(r, s, links, d))
    return d


def load(description, name="UX_1", overrides=None):
    """The RobotDescription of the xacro robot file `description` expanded for robot `name` (with `overrides`)."""
    from unexmin.description.xacro import expand

    return parse(expand(description, name, overrides), str(description))


# ------------------------------------------------------------------------------------------------ the joint tree
def _joint(r, j, links):
    name = text_of(j, "name")
    where = f"joint '{name}'"
    parent = text_of(r.child(j, "parent", where), "link")
    child = text_of(r.child(j, "child", where), "link")
    if parent not in links:
        r.fail(f"{where}: parent link '{parent}' does not exist")
    if child not in links:
        r.fail(f"{where}: child link '{child}' does not exist")
    xyz, rpy = np.zeros(3), np.zeros(3)
    origin = j.find("origin")
    if origin is not None:
        if origin.get("xyz") is not None:
            xyz = r.vector3(origin, "xyz", f"{where}/origin")
        if origin.get("rpy") is not None:
            rpy = r.vector3(origin, "rpy", f"{where}/origin")
    axis = np.array([1.0, 0.0, 0.0])
    a = j.find("axis")
    if a is not None:
        axis = r.vector3(a, "xyz", f"{where}/axis")
        if np.linalg.norm(axis) < 1e-9:
            r.fail(f"{where}/axis has zero length")
        axis = axis / np.linalg.norm(axis)
    return Joint(name, text_of(j, "type"), parent, child, xyz, rpy_matrix(rpy), axis)


def _joint_frame(d, joint):
    """(position, rotation) of the joint's own frame in the body frame: its parent link's pose then its origin."""
    p, rot = d.link_pose(joint.parent)
    return p + rot @ joint.position, rot @ joint.rotation


# ------------------------------------------------------------------------------------------------ hydrodynamics
def _hydrodynamics(r, ext, links):
    hw = "<hydrodynamics>"
    hyd = r.child(ext, "hydrodynamics", "<unexmin>")
    base_link = text_of(hyd, "link")
    if base_link not in links:
        r.fail(f"{hw}@link '{base_link}' is not a link of the robot")
    inertia = r.child(hyd, "inertia", hw)
    h = Hydrodynamics(
        mass=r.value_of(hyd, "mass", 1, hw)[0],
        volume=r.value_of(hyd, "volume", 1, hw)[0],
        radius=r.value_of(hyd, "radius", 1, hw)[0],
        center_of_gravity=r.vector3(r.child(hyd, "center_of_gravity", hw), "xyz", f"{hw}/center_of_gravity"),
        center_of_buoyancy=r.vector3(r.child(hyd, "center_of_buoyancy", hw), "xyz", f"{hw}/center_of_buoyancy"),
        inertia=np.array([r.attr(inertia, k, f"{hw}/inertia") for k in ("ixx", "iyy", "izz")]),
        added_mass=np.array(r.value_of(hyd, "added_mass", 36, hw)).reshape(6, 6),
        linear_damping=np.array(r.value_of(hyd, "linear_damping", 6, hw)),
        quadratic_damping=np.array(r.value_of(hyd, "quadratic_damping", 6, hw)),
        hull_box=np.zeros(3),
    )
    box = hyd.find("bounding_box")
    if box is not None:
        h.hull_box = r.vector3(box, "size", f"{hw}/bounding_box")
        if not h.hull_box.min() > 0.0:
            r.fail(f"{hw}/bounding_box@size must be three lengths > 0 [m]")
    return base_link, h


# ------------------------------------------------------------------------------------------------ actuators
def _actuator_id(r, e, tag):
    value = r.attr(e, "id", f"<{tag}>")
    if value < 0 or value != math.floor(value):
        r.fail(f"<{tag}>@id must be a non-negative integer")
    return int(value)


def _actuator_joint(r, d, e, where):
    name = e.get("joint")
    if name is None:
        r.fail(f"{where} has no 'joint' attribute")
    joint = next((j for j in d.joints if j.name == name), None)
    if joint is None:
        r.fail(f"{where}: joint '{name}' does not exist")
    return joint


def _xyz(v):
    return "(" + ", ".join(number_text(float(x)) for x in v) + ")"


def _inside_hull(r, d, at, where):
    """An actuator at `at` [m] must lie inside the hull: its box when the description gives one, else its sphere."""
    box, radius = d.hydro.hull_box, d.hydro.radius
    if box.min() > 0.0:
        half = 0.5 * box
        if (np.abs(at) - half).max() > _HULL_SLACK:
            r.fail(
                f"{where}: position {_xyz(at)} [m] is outside the hull's bounding box (accepted: "
                f"|x| <= {number_text(half[0])}, |y| <= {number_text(half[1])}, |z| <= {number_text(half[2])} [m])"
            )
    elif radius > 0.0 and np.linalg.norm(at) > radius + _HULL_SLACK:
        r.fail(
            f"{where}: position {_xyz(at)} [m] is outside the hull (accepted: distance from the centre <= "
            f"{number_text(radius)} [m])"
        )


def _by_id(r, items, what):
    """`items` sorted by id, which must be 0..n-1."""
    items = sorted(items, key=lambda a: a.id)
    if any(a.id != k for k, a in enumerate(items)):
        r.fail(f"{what} ids must be 0..{len(items) - 1} without gaps or repeats")
    return items


def _thruster(r, t, d):
    tid = _actuator_id(r, t, "thruster")
    tw = f"<thruster id={tid}>"
    joint = _actuator_joint(r, d, t, tw)
    position, rot = _joint_frame(d, joint)
    _inside_hull(r, d, position, tw)
    dyn = r.child(t, "dynamics", tw)
    dynamics_params = r.params(dyn, f"{tw}/dynamics")
    conv = r.child(t, "conversion", tw)
    conversion_params = r.params(conv, f"{tw}/conversion")
    thrust = r.child(t, "thrust", tw)
    lo, hi = r.attr(thrust, "min", f"{tw}/thrust"), r.attr(thrust, "max", f"{tw}/thrust")
    command = t.find("command")
    timeout = t.find("timeout")
    return Thruster(
        id=tid,
        joint=joint.name,
        position=position,
        axis=rot @ joint.axis,
        dynamics=text_of(dyn, "type"),
        dynamics_params=dynamics_params,
        conversion=text_of(conv, "type"),
        conversion_params=conversion_params,
        min_thrust=lo,
        max_thrust=hi,
        min_command=r.attr_or(command, "min", f"{tw}/command", lo),
        max_command=r.attr_or(command, "max", f"{tw}/command", hi),
        timeout=r.attr(timeout, "value", f"{tw}/timeout") if timeout is not None else 1.0,
    )


def _fin(r, f, d):
    fid = _actuator_id(r, f, "fin")
    fw = f"<fin id={fid}>"
    joint = _actuator_joint(r, d, f, fw)
    position, rot = _joint_frame(d, joint)  # origin: centre of pressure, axis: span, x: chord at angle 0
    _inside_hull(r, d, position, fw)
    model = f.find("model")
    if model is None:
        r.fail(f"{fw}: missing <model type=...> (a fin lift family, e.g. linear_lift)")
    model_params = r.params(model, f"{fw}/model")
    area = f.find("area")
    if area is None:
        r.fail(f"{fw}: missing <area value=...> (planform area > 0 [m^2])")
    area_value = r.attr(area, "value", f"{fw}/area")
    angle = f.find("angle")
    if angle is None or angle.get("min") is None or angle.get("max") is None:
        r.fail(f"{fw}: missing <angle min=... max=...> (limits [rad], -pi/2 <= min <= 0 <= max <= pi/2)")
    min_angle, max_angle = r.attr(angle, "min", f"{fw}/angle"), r.attr(angle, "max", f"{fw}/angle")
    rate = f.find("rate")
    if rate is None:
        r.fail(f"{fw}: missing <rate value=...> (largest fin speed > 0 [rad/s])")
    rate_value = r.attr(rate, "value", f"{fw}/rate")
    timeout = f.find("timeout")
    return Fin(
        id=fid,
        joint=joint.name,
        position=position,
        axis=rot @ joint.axis,
        chord=rot[:, 0].copy(),
        model=text_of(model, "type"),
        model_params=model_params,
        area=area_value,
        min_angle=min_angle,
        max_angle=max_angle,
        rate=rate_value,
        timeout=r.attr(timeout, "value", f"{fw}/timeout") if timeout is not None else 1.0,
    )


def _pendulum(r, pend, d):
    if pend is None:
        return Pendulum()
    pw = "<pendulum>"
    joint = _actuator_joint(r, d, pend, pw).name
    p = Pendulum(joint, *(r.attr(pend, k, pw) for k in ("mass", "arm", "speed", "min", "max")))
    if p.mass >= d.hydro.mass:
        r.fail(f"{pw}@mass must be less than the vehicle mass")
    return p


def _ballast(r, vbs):
    if vbs is None:
        return Vbs()
    vw = "<vbs>"
    v = Vbs(r.attr(vbs, "min", vw), r.attr(vbs, "max", vw))
    if vbs.get("xyz") is not None:
        v.position = r.vector3(vbs, "xyz", vw)
    return v


# ------------------------------------------------------------------------------------------------ the robot's field
_MAGNETIC_TAGS = ("hard_iron", "soft_iron", "thruster_current", "thruster")


def _at_most(r, v, limit, where, unit):
    if np.linalg.norm(v) > limit:
        size = number_text(np.linalg.norm(v))
        r.fail(f"{where} has magnitude {size} {unit}, expected at most {number_text(limit)} {unit}")


def _magnetics(r, ext, d):
    """<magnetic> (cpp/unexmin/sim/description_magnetic.cpp); none: a zero field."""
    found = ext.findall("magnetic")
    m = Magnetics()
    if not found:
        return m
    if len(found) > 1:
        r.fail("<magnetic> given twice: expected one <magnetic> element")
    mag = found[0]
    for e in mag:
        if isinstance(e.tag, str) and e.tag not in _MAGNETIC_TAGS:
            r.fail(f"<magnetic>: unknown element <{e.tag}> (expected hard_iron, soft_iron, thruster_current, thruster)")
    h = mag.find("hard_iron")
    if h is not None:
        m.hard_iron = r.vector3(h, "value", "<magnetic><hard_iron>")
        _at_most(r, m.hard_iron, 1e6, "<magnetic><hard_iron>@value", "nT")
    s = mag.find("soft_iron")
    if s is not None:
        m.soft_iron = np.array(r.attr_numbers(s, "value", 9, "<magnetic><soft_iron>")).reshape(3, 3)
        sv = np.linalg.svd(m.soft_iron, compute_uv=False)
        det = np.linalg.det(m.soft_iron)
        if det <= 0.0 or sv.min() < 0.5 or sv.max() > 2.0:
            r.fail(
                f"<magnetic><soft_iron>@value has singular values {number_text(sv.min())} .. {number_text(sv.max())}"
                f" and determinant {number_text(det)}: expected a rotation-preserving matrix (determinant > 0) with"
                " singular values in [0.5, 2]"
            )
    c = mag.find("thruster_current")
    if c is not None:
        cw = "<magnetic><thruster_current>"
        m.current_coefficient = r.attr_or(c, "coefficient", cw, m.current_coefficient)
        m.current_exponent = r.attr_or(c, "exponent", cw, m.current_exponent)
        if not 0.0 <= m.current_coefficient <= 1000.0:
            r.fail(f"{cw}@coefficient = {number_text(m.current_coefficient)}: expected [0, 1000] A/N^n")
        if not 0.5 <= m.current_exponent <= 3.0:
            r.fail(f"{cw}@exponent = {number_text(m.current_exponent)}: expected [0.5, 3]")
    n = len(d.thrusters)
    seen = [False] * n
    for t in mag.findall("thruster"):
        tid = _actuator_id(r, t, "magnetic><thruster")
        tw = f'<magnetic><thruster id="{tid}">'
        if tid >= n:
            r.fail(f"{tw}: the robot has no thruster {tid} (ids 0 .. {number_text(n - 1.0)})")
        if seen[tid]:
            r.fail(f"{tw} given twice")
        seen[tid] = True
        if not m.thruster_field:
            m.thruster_field = [np.zeros(3) for _ in range(n)]
        m.thruster_field[tid] = r.vector3(t, "field", tw)
        _at_most(r, m.thruster_field[tid], 1e5, f"{tw}@field", "nT/A")
    return m


# ------------------------------------------------------------------------------------------------ sensors
def _sensor_param(r, q, sw, sensor):
    """One <param name value>: into sensor.params when every word of the value is a number, else into sensor.text."""
    key, value = q.get("name"), q.get("value")
    if key is None:
        r.fail(f"{sw}/param has no 'name'")
    if value is None:
        r.fail(f"{sw}/param[{key}] has no 'value'")
    numbers = []
    for token in value.split():
        v = c_number(token)
        if v is not None and not math.isfinite(v):
            r.fail(f"{sw}/param[{key}]: '{token}' is not finite")
        numbers.append(v)
    if numbers and None not in numbers:
        sensor.params[key] = numbers
    else:
        sensor.text[key] = value


def _sensor(r, e, links, d):
    name = text_of(e, "name")
    sw = f"<sensor name='{name}'>"
    if not name:
        r.fail("a <sensor> has no 'name'")
    if any(s.name == name for s in d.sensors):
        r.fail(f"{sw}: the name is used twice")
    kind = text_of(e, "type")
    if not kind:
        r.fail(f"{sw} has no 'type'")
    link = text_of(e, "link")
    if link not in links:
        r.fail(f"{sw}@link '{link}' is not a link of the robot")
    position, rotation = d.link_pose(link)
    rate = r.attr(e, "rate", sw)
    if not rate > 0.0:
        r.fail(f"{sw}@rate = {number_text(rate)} must be > 0 [Hz]")
    sensor = Sensor(name, kind, link, position, rotation, rate)
    for q in e.findall("param"):
        _sensor_param(r, q, sw, sensor)
    return sensor

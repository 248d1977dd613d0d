"""The Python robot description parser (unexmin.description.parse) against its C++ twin (sim::parseRobotDescription,
cpp/unexmin/sim/robot_description.h, which the simulator and unexmin.core use) on the same URDF files: every shipped
vehicle description (urdf/*.urdf.xacro), variants that take the parser's defaults, and malformed descriptions that
both must reject with the same message. The C++ side runs through test/pytest/clients/description_twin.cpp (built
with the workspace), which prints its record as JSON; every field is compared, numbers within 1e-12 (the poses are
composed by two different matrix libraries).

Run: python -m pytest test/pytest/test_description_twin.py (workspace built and sourced).
"""

import json
import os
import subprocess
from pathlib import Path
from xml.etree import ElementTree

import numpy as np
import pytest

from unexmin import description

REPO = Path(__file__).resolve().parents[2]
VEHICLES = sorted((REPO / "urdf").glob("*.urdf.xacro"))
TOLERANCE = 1e-12  # relative and absolute


def twin():
    for ws in (os.environ.get("UNEXMIN_WS"), str(REPO.parent / (REPO.name + "_ws"))):
        if ws and (Path(ws) / "devel/lib/unexmin/description_twin").exists():
            return Path(ws) / "devel/lib/unexmin/description_twin"
    pytest.fail("description_twin is not built: build the workspace (UNEXMIN_WS, scripts/setup.sh)")


_expanded = {}


def expanded(vehicle, name="TWIN"):
    """URDF text of urdf/<vehicle> for robot `name` (xacro once per file)."""
    if vehicle not in _expanded:
        _expanded[vehicle] = description.expand(REPO / "urdf" / vehicle, name)
    return _expanded[vehicle]


def cpp_parse(path):
    """(record as a dict, None) or (None, error message) of the C++ parser on the file `path`."""
    out = subprocess.run([str(twin()), str(path)], capture_output=True, text=True, timeout=60)
    if out.returncode == 1:
        return None, out.stderr.strip()
    assert out.returncode == 0, f"description_twin {path}: exit {out.returncode}: {out.stderr}"
    return json.loads(out.stdout), None


def py_parse(path):
    """(record as the twin's dict, None) or (None, error message) of the Python parser on the file `path`."""
    try:
        return as_dict(description.parse(Path(path).read_text(), str(path))), None
    except description.DescriptionError as e:
        return None, str(e)


def _pose(position, rotation):
    return {"position": list(position), "rotation": list(np.asarray(rotation).ravel())}


def as_dict(robot):
    """The Python record in the twin's JSON layout."""
    h = robot.hydro
    return {
        "name": robot.name,
        "base_link": robot.base_link,
        "hydrodynamics": {
            "mass": h.mass,
            "volume": h.volume,
            "radius": h.radius,
            "center_of_gravity": list(h.center_of_gravity),
            "center_of_buoyancy": list(h.center_of_buoyancy),
            "inertia": list(h.inertia),
            "added_mass": list(h.added_mass.ravel()),
            "linear_damping": list(h.linear_damping),
            "quadratic_damping": list(h.quadratic_damping),
            "hull_box": list(h.hull_box),
        },
        "joints": [
            {"name": j.name, "type": j.type, "parent": j.parent, "child": j.child}
            | _pose(j.position, j.rotation)
            | {"axis": list(j.axis)}
            for j in robot.joints
        ],
        "thrusters": [
            {
                "id": t.id,
                "joint": t.joint,
                "position": list(t.position),
                "axis": list(t.axis),
                "dynamics": t.dynamics,
                "dynamics_params": t.dynamics_params,
                "conversion": t.conversion,
                "conversion_params": t.conversion_params,
                "min_thrust": t.min_thrust,
                "max_thrust": t.max_thrust,
                "min_command": t.min_command,
                "max_command": t.max_command,
                "timeout": t.timeout,
            }
            for t in robot.thrusters
        ],
        "fins": [
            {
                "id": f.id,
                "joint": f.joint,
                "position": list(f.position),
                "axis": list(f.axis),
                "chord": list(f.chord),
                "model": f.model,
                "model_params": f.model_params,
                "area": f.area,
                "min_angle": f.min_angle,
                "max_angle": f.max_angle,
                "rate": f.rate,
                "timeout": f.timeout,
            }
            for f in robot.fins
        ],
        "pendulum": {
            "joint": robot.pendulum.joint,
            "mass": robot.pendulum.mass,
            "arm": robot.pendulum.arm,
            "speed": robot.pendulum.speed,
            "min_angle": robot.pendulum.min_angle,
            "max_angle": robot.pendulum.max_angle,
        },
        "vbs": {"min_mass": robot.vbs.min_mass, "max_mass": robot.vbs.max_mass, "position": list(robot.vbs.position)},
        "magnetics": {
            "hard_iron": list(robot.magnetics.hard_iron),
            "soft_iron": list(np.asarray(robot.magnetics.soft_iron).ravel()),
            "thruster_field": [list(v) for v in robot.magnetics.thruster_field],
            "current_coefficient": robot.magnetics.current_coefficient,
            "current_exponent": robot.magnetics.current_exponent,
        },
        "sensors": [
            {"name": s.name, "type": s.type, "link": s.link}
            | _pose(s.position, s.rotation)
            | {"rate": s.rate, "params": s.params, "text": s.text}
            for s in robot.sensors
        ],
    }


def differences(cpp, py, where="record"):
    """Where the two records differ: a list of 'path: C++ value != Python value'."""
    if isinstance(cpp, dict) and isinstance(py, dict):
        if set(cpp) != set(py):
            return [f"{where}: keys {sorted(cpp)} != {sorted(py)}"]
        return [d for k in cpp for d in differences(cpp[k], py[k], f"{where}.{k}")]
    if isinstance(cpp, list) and isinstance(py, list):
        if len(cpp) != len(py):
            return [f"{where}: {len(cpp)} items != {len(py)}"]
        return [d for i, (a, b) in enumerate(zip(cpp, py)) for d in differences(a, b, f"{where}[{i}]")]
    if isinstance(cpp, (int, float)) and not isinstance(cpp, bool) and isinstance(py, (int, float, np.floating)):
        same = abs(float(cpp) - float(py)) <= TOLERANCE * max(1.0, abs(float(cpp)))
        return [] if same else [f"{where}: {cpp!r} != {float(py)!r}"]
    return [] if cpp == py else [f"{where}: {cpp!r} != {py!r}"]


def written(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


def edited(vehicle, edit):
    """The expanded `vehicle` with `edit(root)` applied to its XML tree."""
    root = ElementTree.fromstring(expanded(vehicle))
    edit(root)
    return ElementTree.tostring(root, encoding="unicode")


def test_the_differences_catch_a_changed_field():
    """The comparison itself: a number beyond the tolerance, a string and a missing item each count."""
    assert differences({"a": [1.0, 2.0], "b": "x"}, {"a": [1.0, 2.0 + 1e-15], "b": "x"}) == []
    assert differences({"a": [1.0, 2.0]}, {"a": [1.0, 2.0 + 1e-9]}) == ["record.a[1]: 2.0 != 2.000000001"]
    assert differences({"b": "x"}, {"b": "y"}) == ["record.b: 'x' != 'y'"]
    assert differences({"a": [1.0]}, {"a": []}) == ["record.a: 1 items != 0"]


@pytest.mark.parametrize("vehicle", [v.name for v in VEHICLES])
def test_every_shipped_vehicle_parses_the_same_in_python_and_cpp(tmp_path, vehicle):
    path = written(tmp_path, "robot.urdf", expanded(vehicle))
    (cpp, cpp_error), (py, py_error) = cpp_parse(path), py_parse(path)
    assert cpp_error is None and py_error is None, (cpp_error, py_error)
    assert cpp["thrusters"] and cpp["sensors"] and cpp["joints"], f"{vehicle}: an empty record proves nothing"
    assert differences(cpp, py) == []


def _defaults(root):
    """Leave out what the parser fills in: the thrusters' <command> and <timeout>, the VBS position; add a sensor
    <param> that is text because one word is not a number."""
    ext = root.find("unexmin")
    for t in ext.findall("thruster"):
        for tag in ("command", "timeout"):
            t.remove(t.find(tag))
    del ext.find("vbs").attrib["xyz"]
    ElementTree.SubElement(ext.find("sensor"), "param", name="mixed", value="1.5 metres")


def _no_pendulum_nor_ballast(root):
    ext = root.find("unexmin")
    ext.remove(ext.find("pendulum"))
    ext.remove(ext.find("vbs"))


def _no_magnetic(root):
    ext = root.find("unexmin")
    ext.remove(ext.find("magnetic"))


def _fins_without_timeout(root):
    for f in root.find("unexmin").findall("fin"):
        if f.find("timeout") is not None:
            f.remove(f.find("timeout"))


@pytest.mark.parametrize(
    "vehicle, edit",
    [
        ("ux1.urdf.xacro", _defaults),
        ("ux1.urdf.xacro", _no_pendulum_nor_ballast),
        ("ux1.urdf.xacro", _no_magnetic),
        ("remus100.urdf.xacro", _fins_without_timeout),
    ],
    ids=["defaults", "no-pendulum-nor-ballast", "no-magnetic", "fin-defaults"],
)
def test_the_defaults_are_the_same_in_python_and_cpp(tmp_path, vehicle, edit):
    path = written(tmp_path, "robot.urdf", edited(vehicle, edit))
    (cpp, cpp_error), (py, py_error) = cpp_parse(path), py_parse(path)
    assert cpp_error is None and py_error is None, (cpp_error, py_error)
    assert differences(cpp, py) == []


def _set(path, attr, value):
    def edit(root):
        root.find(path).set(attr, value)

    return edit


def _remove(parent, tag):
    def edit(root):
        p = root.find(parent)
        p.remove(p.find(tag))

    return edit


def _duplicate_sensor(root):
    ext = root.find("unexmin")
    ext.append(ext.find("sensor"))


def _thruster_outside_hull(root):
    joint = root.find("unexmin/thruster").get("joint")
    next(j for j in root.findall("joint") if j.get("name") == joint).find("origin").set("xyz", "5 0 0")


def _detached_sensor(root):
    ElementTree.SubElement(root, "link", name="detached")
    root.find("unexmin/sensor").set("link", "detached")


def _heavy_pendulum(root):
    mass = root.find("unexmin/hydrodynamics/mass").get("value")
    root.find("unexmin/pendulum").set("mass", mass)


MALFORMED = {
    "not-xml": ("ux1.urdf.xacro", None),
    "no-unexmin": ("ux1.urdf.xacro", _remove(".", "unexmin")),
    "no-mass": ("ux1.urdf.xacro", _remove("unexmin/hydrodynamics", "mass")),
    "added-mass-35": ("ux1.urdf.xacro", _set("unexmin/hydrodynamics/added_mass", "value", " ".join(["1"] * 35))),
    "nan-volume": ("ux1.urdf.xacro", _set("unexmin/hydrodynamics/volume", "value", "nan")),
    "underscore-number": ("ux1.urdf.xacro", _set("unexmin/hydrodynamics/volume", "value", "1_0")),
    "no-inertia-izz": ("ux1.urdf.xacro", lambda r: r.find("unexmin/hydrodynamics/inertia").attrib.pop("izz")),
    "unknown-base-link": ("ux1.urdf.xacro", _set("unexmin/hydrodynamics", "link", "nowhere")),
    "unknown-thruster-joint": ("ux1.urdf.xacro", _set("unexmin/thruster", "joint", "nowhere")),
    "thruster-id-repeated": ("ux1.urdf.xacro", _set("unexmin/thruster", "id", "1")),
    "thruster-id-fraction": ("ux1.urdf.xacro", _set("unexmin/thruster", "id", "0.5")),
    "no-dynamics": ("ux1.urdf.xacro", _remove("unexmin/thruster", "dynamics")),
    "no-thrust-max": ("ux1.urdf.xacro", lambda r: r.find("unexmin/thruster/thrust").attrib.pop("max")),
    "thruster-outside-hull": ("ux1.urdf.xacro", _thruster_outside_hull),
    "zero-axis": ("ux1.urdf.xacro", _set("joint/axis", "xyz", "0 0 0")),
    "unknown-child-link": ("ux1.urdf.xacro", _set("joint/child", "link", "nowhere")),
    "heavy-pendulum": ("ux1.urdf.xacro", _heavy_pendulum),
    "pendulum-no-speed": ("ux1.urdf.xacro", lambda r: r.find("unexmin/pendulum").attrib.pop("speed")),
    "vbs-no-min": ("ux1.urdf.xacro", lambda r: r.find("unexmin/vbs").attrib.pop("min")),
    "sensor-rate-zero": ("ux1.urdf.xacro", _set("unexmin/sensor", "rate", "0")),
    "sensor-unknown-link": ("ux1.urdf.xacro", _set("unexmin/sensor", "link", "nowhere")),
    "sensor-twice": ("ux1.urdf.xacro", _duplicate_sensor),
    "sensor-on-a-detached-link": ("ux1.urdf.xacro", _detached_sensor),
    "sensor-param-inf": ("ux1.urdf.xacro", _set("unexmin/sensor/param", "value", "1 inf")),
    "magnetic-unknown-thruster": ("ux1.urdf.xacro", _set("unexmin/magnetic/thruster", "id", "8")),
    "magnetic-unknown-element": ("ux1.urdf.xacro", lambda r: ElementTree.SubElement(r.find("unexmin/magnetic"), "x")),
    "magnetic-exponent": ("ux1.urdf.xacro", _set("unexmin/magnetic/thruster_current", "exponent", "4")),
    "magnetic-hard-iron-2": ("ux1.urdf.xacro", _set("unexmin/magnetic/hard_iron", "value", "1 2")),
    "fin-no-rate": ("remus100.urdf.xacro", _remove("unexmin/fin", "rate")),
    "fin-no-model": ("remus100.urdf.xacro", _remove("unexmin/fin", "model")),
    "bounding-box-zero": ("remus100.urdf.xacro", _set("unexmin/hydrodynamics/bounding_box", "size", "1 0 1")),
}


@pytest.mark.parametrize("case", sorted(MALFORMED))
def test_both_reject_a_malformed_description_with_the_same_message(tmp_path, case):
    vehicle, edit = MALFORMED[case]
    text = expanded(vehicle).replace("</robot>", "") if edit is None else edited(vehicle, edit)
    path = written(tmp_path, "robot.urdf", text)
    (cpp, cpp_error), (py, py_error) = cpp_parse(path), py_parse(path)
    assert cpp is None, f"{case}: the C++ parser accepted it"
    assert py is None, f"{case}: the Python parser accepted it"
    assert cpp_error.startswith(f"{path}: ") and py_error.startswith(f"{path}: ")
    if edit is not None:  # the XML parsers' own messages differ
        assert py_error == cpp_error

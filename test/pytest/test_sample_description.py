"""A sensor family's sample reaches Python through the family's own description (Sensor::describe,
cpp/unexmin/sensors/sample_fields.h) and nothing else: the binding (cpp/python/world_binding.cpp) knows no family.

- A family defined only in a test (test/pytest/clients/test_family_module.cpp: "test_altimeter", rays straight down)
  comes out of the binding with its fields, units and shapes: in the 4 m test box, from the centre, the floor lies
  2 m below (a closed form; the robot sinks or rises by far less than the tolerance in 0.1 s).
- Every built-in family lists its fields (name, unit, dtype, shape) and sample() holds exactly those.
- The imaging sonar's polar image and the side-scan's waterfall come out in-process (they did not before).
"""

import importlib.util
import os
from pathlib import Path

import numpy as np
import pytest

from unexmin.core import World
from unexmin.description import expand
from unexmin.vehicles import team_names

REPO = Path(__file__).resolve().parents[2]
SENSOR = (
    '<sensor name="alt" type="test_altimeter" link="UX_1/base_link" rate="10">'
    '<param name="max_range" value="5"/></sensor>'
)


def family_module():
    """The engine's binding built with one family more (CMakeLists.txt's tests section)."""
    for ws in (os.environ.get("UNEXMIN_WS"), str(REPO.parent / (REPO.name + "_ws"))):
        found = sorted(Path(ws).glob("devel/lib/unexmin/_test_family_core*.so")) if ws else []
        if found:
            spec = importlib.util.spec_from_file_location("_test_family_core", found[0])
            module = importlib.util.module_from_spec(spec)
            spec.loader.exec_module(module)
            return module
    pytest.fail("_test_family_core is not built: build the workspace (UNEXMIN_WS, scripts/setup.sh)")


def with_altimeter(urdf):
    assert "</unexmin>" in urdf, "the UX-1's description has no <unexmin> block to add a sensor to"
    return urdf.replace("</unexmin>", SENSOR + "</unexmin>", 1)


def test_a_family_defined_only_in_a_test_reaches_python_with_its_fields():
    core = family_module()
    assert "test_altimeter" in core.families() and "camera" in core.families()
    world_file = str(REPO / "worlds" / "test_box.world")
    urdf = with_altimeter(expand(name="UX_1"))
    w = core.World(world_file, {"UX_1": urdf}, 1, [], 3, "test_altimeter", "", 500.0, "operational", 1)
    fields = w.sample_fields("UX_1", "alt")
    assert [f[:3] for f in fields] == [
        ("time", "s", "float64"),
        ("count", "", "uint64"),
        ("ranges", "m", "float32"),
        ("depth", "m", "float64"),
        ("bottom_seen", "", "uint64"),
    ]
    assert fields[2][3] == [0], "no ranges before the first sample"
    w.step(50, True)  # 0.1 s: the first sample at t = 0.1 s
    assert w.sample_fields("UX_1", "alt")[2][3] == [2]
    s = w.sample("UX_1", "alt")
    assert s["name"] == "alt" and s["type"] == "test_altimeter"
    assert s["count"] == 1 and s["time"] == pytest.approx(0.1)
    assert s["ranges"].dtype == np.float32 and s["ranges"].shape == (2,)
    half_box = 2.0  # worlds/test_box.world: a 4 m cube centred on the origin, the robot at its centre
    np.testing.assert_allclose(s["ranges"], [half_box, half_box], atol=0.02)
    assert s["depth"] == pytest.approx(100.0, abs=0.02)  # surface_z 100 m
    assert s["bottom_seen"] == 1


@pytest.mark.long
def test_every_builtin_family_lists_the_fields_its_samples_hold():
    w = World("tank", sensors="all", mode="visual", seed=1)
    ux = w.robot("UX_1")
    w.step(250)
    seen = set()
    for name, family in ux.sensors.items():
        fields = ux.sample_fields(name)
        s = ux.sample(name)
        listed = {f[0] for f in fields}
        assert set(s) - {"name", "type"} == listed, f"{name} ({family}): sample {sorted(s)} vs fields {sorted(listed)}"
        for key, _unit, dtype, shape in fields:
            value = s[key]
            if shape == ():
                assert np.isscalar(value), f"{name}.{key}: {value!r} is not a scalar"
            else:
                assert value.dtype == np.dtype(dtype) and value.shape == shape, f"{name}.{key}"
        seen.add(family)
    assert {
        "imu",
        "dvl",
        "pressure",
        "msis",
        "m3",
        "sls",
        "camera",
        "water_probe",
        "magnetometer",
        "gamma_counter",
        "water_sampler",
    } <= seen


def test_the_imaging_sonar_and_the_side_scan_give_their_images_in_process():
    team = ["ux1", "bluerov2_heavy", "remus100"]
    w = World("tank_team", vehicles=team, sensors="imaging_sonar,side_scan", seed=2)
    assert w.robots == team_names(team)
    rov, auv = w.robot("ROV_1"), w.robot("AUV_1")
    sonar = next(n for n, f in rov.sensors.items() if f == "imaging_sonar")
    side = next(n for n, f in auv.sensors.items() if f == "side_scan")
    w.run_for(1.0)
    polar = rov.sample(sonar)
    assert polar["built"] and polar["count"] >= 1
    assert polar["polar"].dtype == np.uint8
    assert polar["polar"].shape == (polar["bin_ranges"].size, polar["beam_azimuths"].size)
    assert polar["polar"].max() > 0, "the tank's walls echo in the imaging sonar"
    ping = auv.sample(side)
    assert ping["built"] and ping["waterfall"].shape[1] == 2 * ping["port"].size
    assert ping["waterfall"].shape[0] >= 1 and ping["waterfall"].dtype == np.uint8


def test_a_team_longer_than_three_runs_in_process():
    """Any team list the launch files allow (mine_team_any.test's), a robot the world does not list placed by it."""
    team = ["bluerov2_heavy", "ux1", "bluerov2_heavy", "remus100"]
    w = World("mine", vehicles=team, sensors="none", seed=4)
    assert w.robots == ["ROV_1", "UX_1", "ROV_2", "AUV_1"]
    assert w.step(10) == pytest.approx(10 * w.dt)
    positions = [w.robot(n).state()["position"] for n in w.robots]
    gaps = [np.linalg.norm(a - b) for i, a in enumerate(positions) for b in positions[i + 1 :]]
    assert min(gaps) > 0.5, f"two robots spawned on top of each other: {gaps}"

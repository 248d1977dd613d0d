"""The UX-1's water-quality probe through unexmin.core, without ROS (docs/water_probe.md): its sample's fields with
their units, and its readings in a tank whose water is one row of a water column (the probe settled to it at the
first step, its noise and resolution the description's) and in the shipped tank without a column (fresh water at
10 degC, the column's defaults)."""

import math

import numpy as np
import pytest
import yaml

from unexmin.core import World

FIELDS = [
    ("time", "s"),
    ("count", ""),
    ("temperature", "degC"),
    ("conductivity", "uS/cm"),
    ("conductivity_25", "uS/cm"),
    ("ph", "pH"),
    ("redox", "mV"),
    ("oxygen", "mg/L"),
    ("pressure", "Pa"),
]
WATER = {"temperature": 14.0, "conductivity": 800.0, "ph": 6.5, "redox": 150.0, "oxygen": 7.0}


def tank_with_water(tmp_path):
    from unexmin.worlds.files import PACKAGE_DIR, link_meshes

    source = PACKAGE_DIR / "worlds" / "tank.world"
    world = yaml.safe_load(source.read_text())
    link_meshes(world["meshes"], str(source.parent), str(tmp_path))
    world["water"] = {"surface_z": 0.0, "profile": [dict(depth=0.0, **WATER)]}
    path = tmp_path / "probe.world"
    path.write_text(yaml.safe_dump(world))
    return str(path)


def test_the_probe_lists_its_fields_and_reads_the_water_of_the_column(tmp_path):
    w = World(tank_with_water(tmp_path), sensors="water_probe", seed=4)
    ux = w.robot("UX_1")
    name = next(n for n, f in ux.sensors.items() if f == "water_probe")
    assert [(f[0], f[1]) for f in ux.sample_fields(name)] == FIELDS
    w.run_for(3.0)  # 1 Hz: 3 samples
    s = ux.sample(name)
    assert s["count"] == 3 and s["time"] == pytest.approx(3.0)
    # one row: uniform water, so the lag holds the settled value; noise and resolution of urdf/properties.xacro
    assert s["temperature"] == pytest.approx(WATER["temperature"], abs=5 * 0.01 + 0.001)
    assert s["conductivity"] == pytest.approx(WATER["conductivity"], abs=5 * 1.0 + 1.0)
    assert s["ph"] == pytest.approx(WATER["ph"], abs=5 * 0.01 + 0.01 + 0.01)
    assert s["redox"] == pytest.approx(WATER["redox"], abs=5 * 1.0 + 0.1 + 0.1)
    assert s["oxygen"] == pytest.approx(WATER["oxygen"], abs=5 * 0.02 + 0.01)
    ec25 = s["conductivity"] / (1.0 + 0.02 * (s["temperature"] - 25.0))
    assert s["conductivity_25"] == pytest.approx(ec25, abs=0.5 + 1e-9)  # rounded to the 1 uS/cm resolution
    depth = -ux.state()["position"][2]
    assert 101325.0 + 990.0 * 9.81 * (depth - 0.5) < s["pressure"] < 101325.0 + 1010.0 * 9.81 * (depth + 0.5)
    assert all(isinstance(s[k], float) and math.isfinite(s[k]) for k, _ in FIELDS[2:])


def test_without_a_column_the_probe_reads_fresh_water_at_ten_degrees():
    w = World("tank", sensors="water_probe", seed=4)
    ux = w.robot("UX_1")
    name = next(n for n, f in ux.sensors.items() if f == "water_probe")
    w.run_for(1.0)
    s = ux.sample(name)
    got = np.array([s["temperature"], s["conductivity"], s["ph"], s["redox"], s["oxygen"]])
    tolerance = np.array([0.06, 6.0, 0.07, 5.2, 0.11])  # 5 sigma of the description's noise plus its resolution
    assert np.all(np.abs(got - [10.0, 0.0, 7.0, 200.0, 10.0]) <= tolerance), got

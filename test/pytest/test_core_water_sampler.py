"""The UX-1's water sampler through unexmin.core, without ROS (docs/water_sampler.md): its sample description gives
every field with its unit, Robot.fire fills one bottle over the fill time with the water of the world's column at
the intake, the robot carries that water, and a sampler that cannot fire (one bottle filling, all full) or a family
that has nothing to fire raises ValueError naming it.

The world: the 4 m test box (its free surface 100 m above the centre) with a linear water column, 10 degC and pH 7.5 at
the surface to 14 degC and pH 6.5 at 200 m: the intake, 0.3 m sin 60 deg below the hull centre, is at a depth of
100.26 m, where the column gives 12.005 degC and pH 7.0 (the robot moves far less than a centimetre in the fill).
"""

import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from unexmin.core import World
from unexmin.description import ROBOT_FILE, expand

REPO = Path(__file__).resolve().parents[2]
FIELDS = {
    "time": "s",
    "count": "",
    "bottles": "",
    "bottles_left": "",
    "filling": "",
    "fill_fraction": "-",
    "carried_mass": "kg",
    "intake_depth": "m",
    "result_trigger": "-",
    "result_start_time": "s",
    "result_end_time": "s",
    "result_position": "m",
    "result_depth": "m",
    "result_temperature": "degC",
    "result_salinity": "PSU",
    "result_conductivity": "uS/cm",
    "result_ph": "pH",
    "result_redox": "mV",
    "result_oxygen": "mg/L",
    "result_turbidity": "NTU",
    "result_density": "kg/m^3",
    "result_volume": "L",
    "result_mass": "kg",
}


def column(depth):
    """The test column's temperature [degC] and pH at `depth` [m]."""
    return 10.0 + 4.0 * depth / 200.0, 7.5 - depth / 200.0


@pytest.fixture(scope="module")
def world(tmp_path_factory):
    box = (REPO / "worlds" / "test_box.world").read_text()
    box = box.replace(
        "water: {density: 1000.0, surface_z: 100.0}",
        "water: {surface_z: 100.0, profile: [{depth: 0, temperature: 10, ph: 7.5}, "
        "{depth: 200, temperature: 14, ph: 6.5}]}",
    )
    folder = tmp_path_factory.mktemp("sampler")
    (folder / "meshes").mkdir()
    shutil.copy(REPO / "worlds" / "meshes" / "test_box.stl", folder / "meshes")
    path = folder / "layered_box.world"
    path.write_text(box)
    return World(str(path), seed=1, sensors="water_sampler,pressure", descriptions={"UX_1": expand(ROBOT_FILE, "UX_1")})


def test_the_sampler_fills_a_bottle_with_the_water_at_its_intake(world):
    world.reset(1)
    ux = world.robot("UX_1")
    assert {n: u for n, u, _t, _s in ux.sample_fields("water_sampler")} == FIELDS
    world.step(60)  # past the first check at 0.1 s (10 Hz)
    s = ux.sample("water_sampler")
    assert s["bottles"] == 4 and s["bottles_left"] == 4 and not s["filling"] and s["result_position"].shape == (0, 3)
    assert s["intake_depth"] == pytest.approx(100.0 + 0.3 * math.sin(math.radians(60.0)), abs=2e-3)
    t0 = world.time
    assert ux.fire("water_sampler") == "filling bottle 1 of 4"
    with pytest.raises(ValueError, match="UX_1/water_sampler: bottle 1 of 4 is filling"):
        ux.fire("water_sampler")
    world.step(500)  # 1 s: half the fill time
    s = ux.sample("water_sampler")
    assert s["filling"] and s["bottles_left"] == 3 and s["fill_fraction"] == pytest.approx(0.5, abs=1e-9)
    world.step(550)
    s = ux.sample("water_sampler")
    assert not s["filling"] and s["bottles_left"] == 3 and s["result_temperature"].shape == (1,)
    depth = 100.0 + 0.3 * math.sin(math.radians(60.0))
    temperature, ph = column(depth)
    assert s["result_depth"][0] == pytest.approx(depth, abs=0.01)
    assert s["result_temperature"][0] == pytest.approx(temperature, abs=1e-3)
    assert s["result_ph"][0] == pytest.approx(ph, abs=1e-3)
    assert s["result_start_time"][0] == pytest.approx(t0, abs=1e-12)
    assert s["result_end_time"][0] == pytest.approx(t0 + 2.0, abs=1e-9)
    assert s["result_trigger"][0] == 0  # manual
    assert s["result_volume"][0] == 0.5
    assert s["result_mass"][0] == pytest.approx(s["result_density"][0] * 0.5e-3, rel=1e-12)
    assert s["carried_mass"] == pytest.approx(s["result_mass"][0], rel=1e-12)
    intake = [0.3 * math.cos(math.radians(60.0)), 0.0, -0.3 * math.sin(math.radians(60.0))]  # on the hull, front
    np.testing.assert_allclose(s["result_position"][0], intake, atol=0.01)


def test_what_cannot_fire_says_why(world):
    world.reset(1)
    ux = world.robot("UX_1")
    for _ in range(4):
        ux.fire("water_sampler")
        world.step(1001)
    with pytest.raises(ValueError, match="UX_1/water_sampler: all 4 bottles are full"):
        ux.fire("water_sampler")
    with pytest.raises(ValueError, match=r"UX_1/pressure \(family pressure\) has nothing to fire"):
        ux.fire("pressure")
    with pytest.raises(KeyError):
        ux.fire("sampler")
    world.reset(1)
    assert ux.sample("water_sampler")["bottles_left"] == 4 and ux.sample("water_sampler")["carried_mass"] == 0.0

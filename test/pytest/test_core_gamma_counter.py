"""The gamma counter through unexmin.core, without ROS (docs/gamma_counter.md): its sample fields and units, the
background only in a world without geology, and above the granite floor of the 4 m test box (the world file given a
geology here) the potassium window's rate against the half-space closed form A eff q / (2 (mu/rho)_rock) E2(mu d)
+ background, E2 by the trapezoidal rule in the test. The detector's area is raised 100 x in the description so that a
few seconds of counts pin the mean to ~2 %.
"""

import math

import numpy as np
import pytest
import yaml

from unexmin.core import World
from unexmin.description import ROBOT_FILE, expand

FIELDS = {
    "integration_time": "s",
    "counts_total": "",
    "counts_potassium": "",
    "counts_uranium": "",
    "counts_thorium": "",
    "rate_total": "cps",
    "rate_potassium": "cps",
    "rate_uranium": "cps",
    "rate_thorium": "cps",
    "dead_time_fraction": "-",
}
AREA = 5410.0  # [cm^2]: 100 x the UX-1's 54.1


@pytest.fixture(scope="module")
def urdf():
    text = expand(ROBOT_FILE, "UX_1")
    old = '<param name="area" value="54.106079476450226"/>'
    assert old in text, "the UX-1's gamma counter area changed: update this test"
    return text.replace(old, f'<param name="area" value="{AREA}"/>')


def gamma_sensor(robot):
    return next(n for n, f in robot.sensors.items() if f == "gamma_counter")


def test_the_sample_gives_every_field_with_its_unit_and_background_only_without_geology(urdf):
    w = World("test_box", robots=1, seed=4, sensors="gamma_counter", descriptions={"UX_1": urdf})
    ux = w.robot("UX_1")
    name = gamma_sensor(ux)
    fields = {f[0]: f[1] for f in ux.sample_fields(name)}
    for key, unit in FIELDS.items():
        assert key in fields, f"{key} missing from {sorted(fields)}"
        if unit:
            assert fields[key] == unit, (key, fields[key])
    w.run_for(20.0)
    s = ux.sample(name)
    assert s["count"] == 20 and s["time"] == pytest.approx(20.0)
    assert s["integration_time"] == pytest.approx(1.0)
    assert s["counts_total"] >= s["counts_potassium"] + s["counts_uranium"] + s["counts_thorium"]
    # test_box.world has no geology: the windows count their backgrounds (0.5, 1.0, 0.1 cps) only
    assert s["rate_potassium"] < 10.0 and s["rate_thorium"] < 10.0


def test_above_a_granite_floor_the_potassium_rate_is_the_half_space_closed_form(urdf, tmp_path):
    from unexmin.worlds.files import PACKAGE_DIR, link_meshes

    source = PACKAGE_DIR / "worlds" / "test_box.world"
    world = yaml.safe_load(source.read_text())
    link_meshes(world["meshes"], str(source.parent), str(tmp_path))
    world["geology"] = {"host": [{"mineral": "granite", "fraction": 1.0}]}  # 3.5 % K (config/minerals.yaml)
    world["robots"] = world["robots"][:1]
    path = tmp_path / "granite_box.world"
    path.write_text(yaml.safe_dump(world))

    w = World(str(path), robots=1, seed=5, sensors="gamma_counter", descriptions={"UX_1": urdf})
    ux = w.robot("UX_1")
    name = gamma_sensor(ux)
    centre_z = -2.0 + 0.35  # the box floor at z = -2, the hull 5 cm above it
    ux.set_pose([0.0, 0.0, centre_z])
    rates = []
    for _ in range(15):
        w.run_for(1.0)
        rates.append(ux.sample(name)["rate_potassium"])
    z = ux.state()["position"][2]
    assert abs(z - centre_z) < 0.01, f"the robot moved: z = {z}"

    # the detector: 0.25 m from the hull centre at elevation -45 deg (urdf/properties.xacro)
    d = z - 0.25 * math.sin(math.radians(45.0)) + 2.0
    k_per_gram = 3.5e-2 * (1.17e-4 * 6.02214076e23 / 39.0983 * math.log(2) / (1.248e9 * 365.25 * 86400)) * 0.1066
    mu_rho = 0.05833  # water at 1.461 MeV [cm^2/g]; fresh water, 1 g/cm^3
    t = np.linspace(1e-9, 1.0, 200001)
    trapezoid = getattr(np, "trapezoid", None) or np.trapz  # numpy 2 renamed it
    e2 = trapezoid(np.exp(-mu_rho * 100.0 * d / t), t)
    expected = AREA * 0.20 * k_per_gram / (2.0 * 0.90 * mu_rho) * e2 + 0.5
    mean = float(np.mean(rates))
    sigma = math.sqrt(expected / len(rates))  # Poisson, 1 s per sample
    assert abs(mean - expected) < 4.0 * sigma + 0.02 * expected, f"K rate {mean:.1f} cps, closed form {expected:.1f}"
    # the same floor without the water's attenuation would read far more
    assert mean < 0.5 * (AREA * 0.20 * k_per_gram / (2.0 * 0.90 * mu_rho))

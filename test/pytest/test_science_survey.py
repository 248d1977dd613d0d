"""The science survey (python/unexmin/missions/science.py, docs/science_survey.md) in the shipped mine, in-process:
every sample of the four instruments kept (counts = rate x sim time), the sampler's two bottles above and below the
chemocline holding the world's water there, the magnetic peak within 1 m of the magnetite lens's centre along the
gallery and the uranium zone's edges from the gamma profile within 1 m of where the world's fracture zone crosses
the path (the zone computed here from the world file's plane and thickness), the outputs on disk."""

import json
import math

import numpy as np
import pytest
import yaml

from unexmin.missions import science
from unexmin.worlds.files import world_path


def true_channel(rows, depth, channel):
    """The profile's `channel` at `depth` [m], linear between rows (of two rows at one depth the deeper holds there),
    as the simulator's water column without its boundary's heave (a few cm over a survey of minutes)."""
    depths = np.array([r["depth"] for r in rows], dtype=float)
    values = np.array([r.get(channel, np.nan) for r in rows], dtype=float)
    k = int(np.searchsorted(depths, depth, side="right"))
    if k == 0:
        return float(values[0])
    if k == len(rows):
        return float(values[-1])
    d0, d1 = depths[k - 1], depths[k]
    if d1 <= d0:
        return float(values[k])
    return float(values[k - 1] + (values[k] - values[k - 1]) * (depth - d0) / (d1 - d0))


RATES = {"water_probe": 1.0, "magnetometer": 50.0, "gamma_counter": 1.0, "water_sampler": 10.0}  # urdf/properties.xacro


@pytest.fixture(scope="module")
def survey(tmp_path_factory):
    out = tmp_path_factory.mktemp("science")
    return out, science.run(out, "mine", seed=3)


def test_every_sample_is_kept_and_the_outputs_are_on_disk(survey):
    out, s = survey
    for sensor, rate in RATES.items():
        assert abs(s["counts"][sensor] - rate * s["sim_time_s"]) <= 1, sensor
    for name in (
        "water_profile.csv",
        "water_profile.png",
        "samples.csv",
        "magnetic_profile.png",
        "magnetic_map.png",
        "gamma_profile.png",
        "gamma_cloud.ply",
        "trajectory.csv",
        "science_summary.json",
    ):
        assert (out / name).stat().st_size > 100, name
    assert json.loads((out / "science_summary.json").read_text())["pass"] == s["pass"]


def test_the_samples_hold_the_worlds_water_above_and_below_the_chemocline(survey):
    _, s = survey
    world = yaml.safe_load(open(world_path("mine")))
    surface, rows = science.world_water(world)
    above, below = s["samples"][:2]
    cline = s["route"]["chemocline_depth"]
    assert above["depth_m"] < cline - 1.0 and below["depth_m"] > cline + 1.0
    for r in (above, below):  # the robot holds still while a bottle fills: the water where it is
        for c in science.CHANNELS:
            truth = true_channel(rows, r["depth_m"], c)
            assert r[c] == pytest.approx(truth, rel=0.01, abs=0.02), (r["bottle"], c)
    assert below["conductivity"] > 4 * above["conductivity"] and below["ph"] < above["ph"] - 2


def test_magnetic_peak_and_uranium_zone_are_where_the_geology_puts_them(survey):
    _, s = survey
    world = yaml.safe_load(open(world_path("mine")))
    bodies = {b["name"]: b for b in world["geology"]["bodies"]}
    m, g = s["magnetics"], s["gamma"]
    assert m["lens_x_m"] == bodies["magnetite_lens"]["xyz"][0]
    assert abs(m["peak_x_m"] - m["lens_x_m"]) <= 1.0
    assert abs(m["peak_anomaly_nT"]) > 500.0  # far above the fluxgate's noise and the robot's ripple
    zone = bodies["uranium_fractures"]
    n = [v / math.sqrt(sum(c * c for c in zone["normal"])) for v in zone["normal"]]
    x0, x1 = g["zone_true_m"]
    assert (x1 - x0) * abs(n[0]) == pytest.approx(zone["thickness"], rel=1e-6)  # the slab's width along the path
    found = g["zone_found_m"]
    assert abs(found[0] - x0) <= 1.0 and abs(found[1] - x1) <= 1.0
    assert g["uranium_peak_cps"] > 4 * g["uranium_background_cps"]
    assert all(s["pass"].values())

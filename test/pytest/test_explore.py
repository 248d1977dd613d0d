"""The explorer (python -m unexmin.missions.explore; docs/explore.md) through the simulator, lockstep, on two small
mines built with the mine generator's construction (unexmin.missions.explore.course):

- `branch` (a 26 m gallery with a crosscut and a stub): within its time budget (BRANCH_BUDGET: it turns for home
  on the budget, not for want of frontiers) the robot knows >= 80 % of the volume its hull's centre can reach
  (ground truth: at least the hull radius from the rock, connected to the start),
  comes back to its start (true position within 1 m), never touches the rock (true clearance above the hull
  radius all the way), reports no contact; its map is the world's (precision) and the decoder reads the map as
  OctoMap's bt2vrml does;
- `dead_end` (one closed gallery): it knows the whole gallery, stops for lack of frontiers, long before its
  budget, and returns.

Run: /work/main_ws/venv/bin/python -m pytest test/pytest/test_explore.py
"""

import json
import sys

import numpy as np
import pytest

from unexmin.map_quality import read_bt
from unexmin.missions.explore import course
from unexmin.missions.explore.octree import leaf_centres, read_leaves

HULL_RADIUS = 0.3  # [m]
# [s] of sim time: the robot knows 80 % of the course at about 100 s and 89 % at 150 s, when from the far end the way
# home (1.5 x 26 m at 0.3 m/s + 20 s) no longer fits: it returns on the budget
BRANCH_BUDGET = 300.0


def explore(runs, tmp_path, kind, time_s, timeout):
    world = course.build(kind, tmp_path / "course")
    lo, hi = course.bounds(kind)
    out = tmp_path / "out"
    args = [sys.executable, "-m", "unexmin.missions.explore", "--out", str(out), "--world-file", str(world)]
    args += ["--time", str(time_s), "--visibility", "none", "--bounds", *map(str, [*lo, *hi])]
    proc, _ = runs.start(args, tmp_path)
    assert proc.wait(timeout=timeout) == 0, (tmp_path / "out.log").read_text()[-3000:]
    return out, json.loads((out / "summary.json").read_text())


@pytest.mark.long
def test_explores_a_branching_level_and_comes_home(runs, tmp_path):
    out, s = explore(runs, tmp_path, "branch", BRANCH_BUDGET, 600)
    r = s["robot"]["UX_1"]
    assert s["coverage"] >= 0.8, s["timeline"][-3:]
    assert r["why"].startswith("budget time"), s["events"]
    assert s["all_home"] and r["home_error_m"] < 1.0
    assert s["contacts"] == 0 and r["min_clearance_m"] > HULL_RADIUS
    assert s["sim_time_s"] <= BRANCH_BUDGET + 60.0
    assert s["quality"]["precision"] >= 0.9
    assert r["flown_m"] > 26.0  # at least out along the gallery and back over most of it
    for name in ("explore_map.png", "explore_timeline.png", "map_quality.png", "trajectory.csv"):
        assert (out / name).stat().st_size > 1000, name
    # the map as the explorer reads it = as OctoMap's bt2vrml reads it
    res, keys, sizes, occupied = read_leaves(out / "explore_map.bt")
    centres, edges = leaf_centres(res, keys, sizes)
    ours = {tuple(v) for v in np.round(np.c_[centres[occupied], edges[occupied]] * 1000).astype(int).tolist()}
    ref, ref_sizes = read_bt(str(out / "explore_map.bt"))
    theirs = {tuple(v) for v in np.round(np.c_[ref, ref_sizes] * 1000).astype(int).tolist()}
    assert ours == theirs and len(ours) > 1000


def test_stops_in_a_dead_end_and_returns(runs, tmp_path):
    _, s = explore(runs, tmp_path, "dead_end", 900.0, 600)
    r = s["robot"]["UX_1"]
    assert r["why"].startswith("explored"), s["events"]
    assert s["coverage"] >= 0.95, s["timeline"][-3:]  # it had explored the gallery
    assert s["all_home"] and r["home_error_m"] < 1.0
    assert s["sim_time_s"] < 600.0  # the budget was 900 s: it stopped for want of frontiers
    assert s["contacts"] == 0 and r["min_clearance_m"] > HULL_RADIUS
    returns = [e for e in s["events"] if e["kind"] == "return"]
    assert len(returns) == 1


if __name__ == "__main__":
    sys.exit(pytest.main([__file__, "-q"]))

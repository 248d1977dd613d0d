"""The explorer's ROS-free parts (python/unexmin/missions/explore; docs/explore.md) against closed forms: the OctoMap
stream decoder on hand-made trees, the grid made of its leaves, frontiers and paths in a corridor of known shape,
dead reckoning of a circle, the budget's turn-for-home rule. A few seconds, no ROS.

Run: /work/main_ws/venv/bin/python -m pytest test/pytest/test_explore_plan.py
"""

import math

import numpy as np
import pytest

from unexmin.geometry import rpy_matrix
from unexmin.missions.explore.budget import Budget, power
from unexmin.missions.explore.grid import FREE, OCCUPIED, UNKNOWN, Grid, empty_grid, grid_from_leaves
from unexmin.missions.explore.navigation import DeadReckoning
from unexmin.missions.explore.octree import KEY_OFFSET, leaf_centres, leaves, read_bt
from unexmin.missions.explore.plan import Graph, PlanOptions, choose_goals, frontiers, gain_map, path_to, traversable

HALF = 1 << 15  # a child of the root spans 32768 keys


def test_a_root_with_two_leaves():
    # child 0 (x-, y-, z-) occupied leaf: code 2 in bits 0-1; child 7 (x+, y+, z+) free leaf: code 1 in bits 6-7
    keys, sizes, occupied = leaves(bytes([0b10, 0b01 << 6]))
    assert keys.tolist() == [[0, 0, 0], [HALF, HALF, HALF]]
    assert sizes.tolist() == [HALF, HALF]
    assert occupied.tolist() == [True, False]


def test_depth_first_order_and_child_keys():
    # root: child 1 (x+) inner, child 2 (y+) occupied leaf; child 1: child 4 (z+) inner and child 0 free; that
    # inner node: child 3 (x+, y+) occupied. Stream: root, child 1, child 1's child 4.
    data = bytes([(3 << 2) | (2 << 4), 0, 1, 3, 2 << 6, 0])
    keys, sizes, occupied = leaves(data)
    quarter, eighth = HALF >> 1, HALF >> 2
    expected = {
        (0, HALF, 0, HALF, True),
        (HALF, 0, 0, quarter, False),
        (HALF + eighth, eighth, quarter, eighth, True),
    }
    assert {(*k, s, o) for k, s, o in zip(keys.tolist(), sizes.tolist(), occupied.tolist())} == expected
    with pytest.raises(ValueError, match="ends inside a node"):
        leaves(data[:-2])
    with pytest.raises(ValueError, match="two bytes per node"):
        leaves(data[:-1])
    with pytest.raises(ValueError, match="bytes left"):
        leaves(data + b"\0\0")


def test_leaf_centres_and_header(tmp_path):
    c, e = leaf_centres(0.1, np.array([[KEY_OFFSET, KEY_OFFSET - 2, KEY_OFFSET]]), np.array([2]))
    np.testing.assert_allclose(c, [[0.1, -0.1, 0.1]])
    np.testing.assert_allclose(e, [0.2])
    bad = tmp_path / "x.bt"
    bad.write_bytes(b"not a map\n")
    with pytest.raises(ValueError, match="not an OctoMap"):
        read_bt(bad)
    good = tmp_path / "y.bt"
    good.write_bytes(b"# Octomap OcTree binary file\nid OcTree\nsize 3\nres 0.05\ndata\n" + bytes([2, 0]))
    res, data = read_bt(good)
    assert res == 0.05 and data == bytes([2, 0])


def test_grid_from_leaves_occupied_wins():
    g = empty_grid((0, 0, 0), (0.8, 0.8, 0.8), 0.1, 4)
    assert g.shape == (2, 2, 2) and g.cell == pytest.approx(0.4)
    k = KEY_OFFSET
    keys = np.array([[k, k, k], [k + 1, k, k], [k + 4, k, k], [k, k + 4, k + 4]])
    sizes = np.array([1, 1, 1, 4])
    occupied = np.array([True, False, False, False])
    grid_from_leaves(g, 0.1, keys, sizes, occupied, 4)
    assert g.states[0, 0, 0] == OCCUPIED  # an occupied and a free voxel: occupied
    assert g.states[1, 0, 0] == FREE
    assert g.states[0, 1, 1] == FREE
    assert (g.states == UNKNOWN).sum() == 5
    # a free leaf of 8 voxels covers 8 cells
    grid_from_leaves(g, 0.1, np.array([[k, k, k]]), np.array([8]), np.array([False]), 4)
    assert (g.states == FREE).all()


def corridor():
    """An L corridor of free cells (0.4 m) 7 cells across: along x from x = 0 to 8 m, then along y to y = 8 m,
    rock around it, its y end unknown (the frontier)."""
    g = Grid(np.array([-2.0, -2.0, -2.0]), 0.4, np.full((30, 30, 10), OCCUPIED, np.uint8))
    idx = np.stack(np.meshgrid(*[np.arange(n) for n in g.shape], indexing="ij"), -1)
    c = g.centre(idx)
    leg_x = (c[..., 0] >= -1.4) & (c[..., 0] <= 9.4) & (np.abs(c[..., 1]) <= 1.4)
    leg_y = (np.abs(c[..., 0] - 8.0) <= 1.4) & (c[..., 1] >= -1.4) & (c[..., 1] <= 9.4)
    inside = (leg_x | leg_y) & (np.abs(c[..., 2]) <= 1.4)
    g.states[inside] = FREE
    g.states[inside & (c[..., 1] > 6.0)] = UNKNOWN
    return g


def test_frontier_goal_and_path_round_the_corner():
    g, po = corridor(), PlanOptions()
    mask = traversable(g, po, surface_z=10.0)
    centres = g.centre(np.argwhere(mask))
    # every traversable centre is clear of the rock and of the unknown by the rules' distances
    occ = g.centre(np.argwhere(g.states == OCCUPIED))
    unk = g.centre(np.argwhere(g.states == UNKNOWN))
    d_occ = np.min(np.linalg.norm(centres[:, None] - occ[None], axis=2), axis=1)
    d_unk = np.min(np.linalg.norm(centres[:, None] - unk[None], axis=2), axis=1)
    assert d_occ.min() >= po.clear_occupied(g.cell) - 1e-9 and d_unk.min() >= po.clear_unknown - 1e-9
    front = frontiers(g, 10.0, po)
    fc = g.centre(np.argwhere(front))
    assert len(fc) and np.allclose(fc[:, 1], 5.8)  # the last free layer before the unknown
    graph = Graph(g, mask)
    start = graph.nearest_node((0.2, 0.2, 0.2))
    search = graph.distances(start)
    goals = choose_goals(graph, g, front, gain_map(g, po), {"UX_1": search}, [], po)
    goal, path, length = goals["UX_1"]
    assert goal[1] >= 5.8 - po.goal_reach - 1e-9  # near the frontier
    # round the corner: the straight line is blocked; the grid path is at least as long as the straight line and
    # the shortened path's legs are no longer than the grid path
    start_c = graph.grid.centre(graph.cells[start])
    assert not graph.line_clear(start_c, goal)
    assert length >= np.linalg.norm(goal - start_c)
    assert np.linalg.norm(np.diff(path, axis=0), axis=1).sum() <= length + 1e-9
    assert all(graph.line_clear(a, b) for a, b in zip(path[:-1], path[1:]))
    assert 2 <= len(path) <= 5  # shortened: a few straight legs
    home = path_to(graph, graph.distances(graph.nearest_node(goal)), (0.2, 0.2, 0.2))
    assert home is not None and np.allclose(home[0][-1], (0.2, 0.2, 0.2))
    # a second robot is sent elsewhere when there is another frontier; here there is none: it shares
    second = choose_goals(graph, g, front, gain_map(g, po), {"UX_2": search}, [goal], po)
    assert "UX_2" in second


def test_no_frontier_no_goal():
    g, po = corridor(), PlanOptions()
    g.states[g.states == UNKNOWN] = OCCUPIED  # the corridor closed: a dead end
    assert not frontiers(g, 10.0, po).any()
    graph = Graph(g, traversable(g, po, 10.0))
    search = graph.distances(graph.nearest_node((0.2, 0.2, 0.2)))
    assert choose_goals(graph, g, frontiers(g, 10.0, po), gain_map(g, po), {"UX_1": search}, [], po) == {}


def test_dead_reckoning_of_a_straight_line_flown_turning():
    """The explorer's motion: 0.3 m/s along +x in the world while the heading turns at 0.2 rad/s. The DVL (8 Hz)
    measures the velocity in its own frame, turning; held in the world frame between pings the estimate is exact:
    x = v t, y = 0, the yaw w t."""
    v, w, dt = 0.3, 0.2, 0.002
    dvl_R = rpy_matrix((math.pi, 0.0, 0.0))  # the UX-1's DVL: x forward, y starboard, z down
    nav = DeadReckoning((0, 0, -5.0), np.eye(3), 0.0, dvl_R, (0, 0, -0.3), 1000.0, 9.81)
    nav.pressure(2e5)
    t = 0.0
    for k in range(int(20.0 / dt)):
        if k % 62 == 0:  # a ping: the world velocity in the DVL frame at this heading
            body = rpy_matrix((0.0, 0.0, w * t)).T @ np.array([v, 0.0, 0.0])
            nav.dvl(True, dvl_R.T @ body)
        t += dt
        nav.rates([(t, (0.0, 0.0, w))])
    np.testing.assert_allclose(nav.p[:2], [v * t, 0.0], atol=1e-6)
    assert math.remainder(nav.yaw - w * t, 2 * math.pi) == pytest.approx(0.0, abs=1e-9)
    np.testing.assert_allclose(nav.R @ nav.v_body, [v, 0.0, 0.0], atol=1e-9)
    nav.pressure(2e5 + 1000.0 * 9.81 * 2.0)  # 2 m deeper
    assert nav.p[2] == pytest.approx(-7.0)
    nav.dvl(False, (math.nan,) * 3)  # no bottom: the velocity decays with coast_tau
    nav.rates([(t + 4.0, (0.0, 0.0, 0.0))])
    assert np.linalg.norm(nav.v_body) == pytest.approx(v * math.exp(-1.0))
    assert nav.lock_lost_s == pytest.approx(4.0)


def test_budget_turns_for_home_when_the_way_back_no_longer_fits():
    b = Budget(time_s=300.0, energy_j=1000.0, reserve=1.5, margin_s=20.0)
    # 30 m home at 0.3 m/s: 1.5 x 100 s + 20 s = 170 s needed
    assert not b.must_return(129.0, 0.0, 30.0, 0.3, 1.0)[0]
    go, why = b.must_return(130.0, 0.0, 30.0, 0.3, 1.0)
    assert go and why.startswith("time")
    go, why = b.must_return(0.0, 955.0, 30.0, 0.3, 1.0)  # 45 J needed at 1 J/m
    assert go and why.startswith("energy")
    assert power((10.0, 0.0, 0.0), (0.3, 0.0, 0.0), 2.0, -0.5) == pytest.approx(4.0)
    with pytest.raises(ValueError, match="reserve"):
        Budget(reserve=0.5).check()
    with pytest.raises(ValueError, match="time_s"):
        Budget(time_s=0.0).check()

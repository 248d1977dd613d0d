"""The mapper's live map as the explorer reads it (e: the Explorer): wait until the mapper has every cloud, save the
map, read it into the coarse grid."""

import numpy as np

from unexmin.missions.explore.grid import FREE, OCCUPIED, grid_from_leaves
from unexmin.missions.explore.octree import read_leaves
from unexmin.missions.explore.plan import ball_mask

SLS_UNITS = 4  # per robot: the M3 sends 40 clouds a second, each SLS unit 10


def caught_up(e, timeout=60.0):
    """Waits (at most `timeout` [s] of wall time) until the mapper has inserted every cloud of the sim time so far."""
    from unexmin.scripting.launcher import wait_for

    expected = int(round(e.sim.time * 40.0)) + int(round(e.sim.time * 10.0)) * SLS_UNITS
    expected *= len(e.agents)
    slack = 5 * (1 + SLS_UNITS) * len(e.agents)

    def done():
        m = e.stats.get("last")
        return (
            m is not None
            and m.clouds_inserted + m.clouds_dropped >= m.clouds_received
            and m.pending == 0
            and m.clouds_received >= expected - slack
        )

    try:
        wait_for(done, timeout, "the mapper to insert every cloud")
    except TimeoutError as err:
        e.event(e.sim.time, "mapper", "lagging", str(err))


def save(e, path):
    """The mapper's map as it is now, once it has caught up, to the .bt file `path`."""
    caught_up(e)
    res = e.save_map(path=path, robot="")
    if not res.success:
        raise RuntimeError(f"/mapper/save_map {path} failed: {res.message}")


def read(e):
    """The live map into the explorer's grid: the robots' own cells free, the M3 guard's echoes occupied."""
    save(e, e.live_path)
    res, keys, sizes, occupied = read_leaves(e.live_path)
    if abs(res - e.o.resolution) > 1e-9:
        raise RuntimeError(f"the mapper's resolution is {res} m, expected {e.o.resolution} m")
    grid_from_leaves(e.grid, res, keys, sizes, occupied, e.o.cell_voxels)
    for a in e.agents:
        # where a robot is, is water: its own cell is not mapped at the start, and its teammates' sensors map
        # its hull as occupied
        near = ball_mask(e.grid, a.nav.p, 0.7)
        e.grid.states[near & (e.grid.states != FREE)] = FREE
    if e.sonar_points:
        idx = e.grid.index(np.array(e.sonar_points))
        idx = idx[e.grid.inside(idx)]
        e.grid.states[tuple(idx.T)] = OCCUPIED

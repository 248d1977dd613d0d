"""The explorer's picture of the world: a coarse 3-D grid over a box, each cell unknown, free or occupied, made
from the mapper's OctoMap (no ROS).

A cell is `OCCUPIED` when any occupied leaf of the map touches it, else `FREE` when a free leaf does, else
`UNKNOWN`. Cells are aligned with the map's voxels: a cell is `ratio` voxels on a side.
"""

from dataclasses import dataclass

import numpy as np

from unexmin.missions.explore.octree import KEY_OFFSET

UNKNOWN, FREE, OCCUPIED = 0, 1, 2


@dataclass
class Grid:
    """states[i, j, k] of the cell whose lower corner is origin + (i, j, k) * cell [m]."""

    origin: np.ndarray  # [m] lower corner of cell (0, 0, 0), world frame
    cell: float  # [m] edge of a cell
    states: np.ndarray  # uint8, UNKNOWN / FREE / OCCUPIED

    @property
    def shape(self):
        return self.states.shape

    def index(self, points):
        """Cell indices (N x 3 int) of world points [m] (may be outside the grid)."""
        return np.floor((np.asarray(points, float) - self.origin) / self.cell).astype(np.int64)

    def centre(self, idx):
        """World centres [m] of cells given by indices."""
        return self.origin + (np.asarray(idx, float) + 0.5) * self.cell

    def inside(self, idx):
        idx = np.asarray(idx)
        return np.all((idx >= 0) & (idx < np.array(self.shape)), axis=-1)

    def known_volume(self, mask=None):
        """[m3] of the known (free or occupied) cells, within `mask` if given."""
        known = self.states != UNKNOWN
        if mask is not None:
            known &= mask
        return float(known.sum()) * self.cell**3


def empty_grid(lo, hi, res, ratio):
    """An all-unknown grid covering the box lo..hi [m], cells of ratio x res [m] aligned with the map's voxels."""
    cell = res * ratio
    lo_k = np.floor(np.asarray(lo, float) / cell).astype(np.int64)
    hi_k = np.ceil(np.asarray(hi, float) / cell).astype(np.int64)
    if np.any(hi_k <= lo_k):
        raise ValueError(f"explore bounds {lo} .. {hi}: expected lo < hi on every axis")
    return Grid(lo_k * cell, cell, np.zeros(tuple(hi_k - lo_k), np.uint8))


def grid_from_leaves(grid, res, keys, sizes, occupied, ratio):
    """Fill `grid` (made by empty_grid with the same res and ratio) from OctoMap leaves (octree.leaves)."""
    states = np.zeros(grid.shape, np.uint8)
    k0 = np.rint(grid.origin / res).astype(np.int64) + KEY_OFFSET  # key of the grid's lower corner
    shape = np.array(grid.shape)
    for size in np.unique(sizes):
        sel = sizes == size
        lo = (keys[sel] - k0) // ratio  # first cell each leaf touches
        n = max(1, int(size) // ratio)  # cells per side a leaf covers
        value = np.where(occupied[sel], OCCUPIED, FREE).astype(np.uint8)
        if n > 1:
            off = np.stack(np.meshgrid(*[np.arange(n)] * 3, indexing="ij"), -1).reshape(-1, 3)
            lo = (lo[:, None, :] + off[None]).reshape(-1, 3)
            value = np.repeat(value, len(off))
        ok = np.all((lo >= 0) & (lo < shape), axis=1)
        lo, value = lo[ok], value[ok]
        np.maximum.at(states, (lo[:, 0], lo[:, 1], lo[:, 2]), value)
    grid.states = states
    return grid

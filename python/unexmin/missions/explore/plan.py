"""Where to go and how: traversable cells, frontiers, shortest paths on the grid (no ROS).

- Traversable: a FREE cell whose centre is at least `clear_occupied` [m] from every OCCUPIED cell centre and
  `clear_unknown` [m] from every UNKNOWN one (the hull radius plus a margin plus half a cell: the wall lies
  somewhere in an occupied cell), inside the box, under the water surface less `surface_margin`.
- Frontier: a FREE cell with an UNKNOWN face neighbour and no OCCUPIED cell among its 26 neighbours (a gap in a
  mapped wall is not a frontier: what lies behind it is rock).
- Paths: Dijkstra over the traversable cells, 26-connected, edge cost the centre-to-centre distance [m]; the path
  is then shortened by straight segments that stay on traversable cells.
- Goals: traversable cells within `goal_reach` [m] of a frontier, scored gain x exp(-distance / `distance_scale`),
  gain = unknown cells with a free face neighbour within `gain_radius` [m] (a box filter), at least `min_gain`;
  goals of other robots push a goal away by `separation` [m].
"""

from dataclasses import dataclass

import numpy as np
from scipy import ndimage, sparse
from scipy.sparse.csgraph import dijkstra

from unexmin.missions.explore.grid import FREE, OCCUPIED, UNKNOWN

_OFFSETS = np.array([(i, j, k) for i in (-1, 0, 1) for j in (-1, 0, 1) for k in (-1, 0, 1) if (i, j, k) > (0, 0, 0)])


@dataclass
class PlanOptions:
    hull_radius: float = 0.3  # [m]
    margin: float = 0.3  # [m] more water kept between the hull and a mapped wall
    clear_unknown: float = 0.5  # [m] from a cell centre to the nearest unknown cell centre (unknown may be rock)
    surface_margin: float = 0.8  # [m] the hull's centre stays this far under the water surface
    goal_reach: float = 1.6  # [m] a goal lies within this of a frontier cell
    gain_radius: float = 2.0  # [m] half edge of the box whose unknown cells count as a goal's gain
    min_gain: float = 6.0  # unknown cells on the edge of the free space in that box for a goal to count
    distance_scale: float = 20.0  # [m] utility falls by e per this much path
    separation: float = 6.0  # [m] a goal this near another robot's goal loses its gain

    def clear_occupied(self, cell):
        return self.hull_radius + self.margin + 0.5 * cell

    def check(self):
        for name in ("hull_radius", "goal_reach", "gain_radius", "distance_scale"):
            if not getattr(self, name) > 0:
                raise ValueError(f"explore option {name} = {getattr(self, name)}: expected > 0")
        for name in ("margin", "clear_unknown", "surface_margin", "separation"):
            if not getattr(self, name) >= 0:
                raise ValueError(f"explore option {name} = {getattr(self, name)}: expected >= 0")
        if not self.min_gain >= 1:
            raise ValueError(f"explore option min_gain = {self.min_gain}: expected >= 1 cell")


def traversable(grid, options, surface_z, free_spheres=()):
    """Boolean mask of the cells the hull's centre may cross. free_spheres: (centre [m], radius [m]) where the
    robots are (water, whatever the map says: a robot's own cell is not yet mapped at the start)."""
    states = grid.states.copy()
    for c, r in free_spheres:
        states[ball_mask(grid, c, r) & (states == UNKNOWN)] = FREE
    cell = grid.cell
    d_occ = ndimage.distance_transform_edt(states != OCCUPIED) * cell
    d_unk = ndimage.distance_transform_edt(states != UNKNOWN) * cell
    ok = (states == FREE) & (d_occ >= options.clear_occupied(cell)) & (d_unk >= options.clear_unknown)
    z = grid.centre(np.stack(np.meshgrid(*[np.arange(n) for n in grid.shape], indexing="ij"), -1))[..., 2]
    ok &= z <= surface_z - options.surface_margin
    for c, r in free_spheres:  # a robot's own cell and its neighbours stay usable for leaving it
        ok |= ball_mask(grid, c, min(r, cell)) & (d_occ >= options.hull_radius)
    return ok


def ball_mask(grid, centre, radius):
    """Boolean mask of the cells whose centre is within radius [m] of centre [m]."""
    idx = np.stack(np.meshgrid(*[np.arange(n) for n in grid.shape], indexing="ij"), -1)
    return np.linalg.norm(grid.centre(idx) - np.asarray(centre, float), axis=-1) <= radius


def frontiers(grid, surface_z, options):
    """Boolean mask of the frontier cells."""
    s = grid.states
    unknown = s == UNKNOWN
    near_unknown = ndimage.binary_dilation(unknown, ndimage.generate_binary_structure(3, 1))
    near_occupied = ndimage.binary_dilation(s == OCCUPIED, ndimage.generate_binary_structure(3, 3))
    f = (s == FREE) & near_unknown & ~near_occupied
    z = grid.origin[2] + (np.arange(grid.shape[2]) + 0.5) * grid.cell
    f &= (z <= surface_z - options.surface_margin)[None, None, :]
    return f


def gain_map(grid, options):
    """Number of unknown cells with a free face neighbour (the edge of what the sensors have seen through; unknown
    rock behind a mapped wall does not count) in the box of half edge gain_radius around each cell."""
    n = 2 * max(1, int(round(options.gain_radius / grid.cell))) + 1
    edge = (grid.states == UNKNOWN) & ndimage.binary_dilation(
        grid.states == FREE, ndimage.generate_binary_structure(3, 1)
    )
    return ndimage.uniform_filter(edge.astype(np.float32), size=n, mode="constant") * n**3


class Graph:
    """Dijkstra over the traversable cells of a grid."""

    def __init__(self, grid, mask):
        self.grid = grid
        self.mask = mask
        self.cells = np.argwhere(mask)
        self.node = np.full(mask.shape, -1, np.int64)
        self.node[tuple(self.cells.T)] = np.arange(len(self.cells))
        rows, cols, w = [], [], []
        shape = np.array(mask.shape)
        for off in _OFFSETS:
            nb = self.cells + off
            ok = np.all((nb >= 0) & (nb < shape), axis=1)
            a = np.flatnonzero(ok)
            b = self.node[tuple(nb[ok].T)]
            keep = b >= 0
            rows.append(a[keep])
            cols.append(b[keep])
            w.append(np.full(int(keep.sum()), np.linalg.norm(off) * grid.cell))
        n = len(self.cells)
        self.matrix = sparse.csr_matrix(
            (np.concatenate(w) if w else [], (np.concatenate(rows), np.concatenate(cols))), shape=(n, n)
        )

    def nearest_node(self, point, max_distance=1.5):
        """Node of the traversable cell nearest to a point [m] (within max_distance), or -1."""
        if not len(self.cells):
            return -1
        d = np.linalg.norm(self.grid.centre(self.cells) - np.asarray(point, float), axis=1)
        i = int(np.argmin(d))
        return i if d[i] <= max_distance else -1

    def distances(self, source):
        """(distances [m] to every node, predecessors) from node `source`."""
        d, pred = dijkstra(self.matrix, directed=False, indices=source, return_predecessors=True)
        return d, pred

    def path(self, pred, target):
        """World points [m] of the nodes from the source to `target` (predecessors of distances())."""
        out = []
        while target >= 0:
            out.append(target)
            target = pred[target]
        return self.grid.centre(self.cells[out[::-1]])

    def line_clear(self, a, b):
        """True when the segment a-b [m] stays on traversable cells (sampled every quarter cell)."""
        n = max(2, int(np.ceil(np.linalg.norm(np.asarray(b) - np.asarray(a)) / (0.25 * self.grid.cell))) + 1)
        pts = np.linspace(a, b, n)
        idx = self.grid.index(pts)
        if not np.all(self.grid.inside(idx)):
            return False
        return bool(np.all(self.mask[tuple(idx.T)]))

    def shorten(self, points):
        """The path as few straight segments as stay on traversable cells (greedy: farthest visible point)."""
        if len(points) <= 2:
            return np.asarray(points)
        out, i = [points[0]], 0
        while i < len(points) - 1:
            j = len(points) - 1
            while j > i + 1 and not self.line_clear(points[i], points[j]):
                j -= 1
            out.append(points[j])
            i = j
        return np.asarray(out)


def choose_goals(graph, grid, frontier, gain, searches, busy, options, avoid=()):
    """Goal and path for each robot of `searches` ({name: (distances, predecessors)} from its node, Graph.distances),
    greedily in turn: each takes the best goal (utility gain x exp(-d / distance_scale)) not within `separation`
    [m] of a goal taken before it or of a point in `busy` (goals of robots keeping theirs), nor within goal_reach / 2
    of a point in `avoid` (goals given up: reached or unreachable). Returns {name: (goal point, path points, path
    length [m])} for the robots that have a goal."""
    if not len(graph.cells):
        return {}
    d_frontier = ndimage.distance_transform_edt(~frontier) * grid.cell
    cells = graph.cells
    centres = grid.centre(cells)
    g = gain[tuple(cells.T)]
    candidate = (d_frontier[tuple(cells.T)] <= options.goal_reach) & (g >= options.min_gain)
    for p in avoid:
        candidate &= np.linalg.norm(centres - np.asarray(p, float), axis=1) > 0.5 * options.goal_reach
    taken = [np.asarray(p, float) for p in busy]
    out = {}
    for name, (d, pred) in searches.items():
        ok = candidate & np.isfinite(d)
        alone = ok.copy()
        for p in taken:
            alone &= np.linalg.norm(centres - p, axis=1) > options.separation
        if alone.any():  # every goal near another robot's: share rather than stop
            ok = alone
        if not ok.any():
            continue
        utility = np.where(ok, g * np.exp(-d / options.distance_scale), -np.inf)
        target = int(np.argmax(utility))
        out[name] = (centres[target], graph.shorten(graph.path(pred, target)), float(d[target]))
        taken.append(centres[target])
    return out


def path_to(graph, search, point, max_distance=3.0):
    """(path points [m] ending at `point`, length [m]) to the traversable cell nearest `point` within max_distance,
    from the source of `search` (Graph.distances), or None when it cannot be reached."""
    target = graph.nearest_node(point, max_distance)
    if target < 0 or not np.isfinite(search[0][target]):
        return None
    pts = graph.shorten(graph.path(search[1], target))
    return np.vstack([pts, np.asarray(point, float)[None]]), float(search[0][target])


__all__ = [
    "FREE",
    "Graph",
    "PlanOptions",
    "ball_mask",
    "choose_goals",
    "frontiers",
    "gain_map",
    "path_to",
    "traversable",
]

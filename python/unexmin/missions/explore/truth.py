"""Ground truth for scoring only (the explorer never steers by it): the distance from a point to the world's
rock and the volume the robot could reach (no ROS)."""

import numpy as np
from scipy import ndimage
from scipy.spatial import cKDTree

from unexmin.worlds.files import world_triangles


class Truth:
    """The world's collision triangles near a box lo..hi [m], area-sampled every `spacing` [m] with the normals of
    their faces (the meshes face the water)."""

    def __init__(self, world_file, lo, hi, spacing=0.05, reach=2.0, seed=0):
        tris = world_triangles(world_file)
        lo, hi = np.asarray(lo, float) - reach, np.asarray(hi, float) + reach
        near = np.any(np.all((tris >= lo) & (tris <= hi), axis=2), axis=1)
        tris = tris[near]
        if not len(tris):
            raise ValueError(f"{world_file}: no collision triangle within {reach} m of the box {lo} .. {hi}")
        rng = np.random.default_rng(seed)
        a, b, c = tris[:, 0], tris[:, 1], tris[:, 2]
        n = np.cross(b - a, c - a)
        area = 0.5 * np.linalg.norm(n, axis=1)
        counts = np.floor(area / spacing**2 + rng.random(len(tris))).astype(np.int64) + 1
        idx = np.repeat(np.arange(len(tris)), counts)
        u, v = rng.random(len(idx)), rng.random(len(idx))
        flip = u + v > 1.0
        u[flip], v[flip] = 1.0 - u[flip], 1.0 - v[flip]
        self.points = a[idx] + u[:, None] * (b[idx] - a[idx]) + v[:, None] * (c[idx] - a[idx])
        self.normals = n[idx] / np.linalg.norm(n[idx], axis=1, keepdims=True)
        self.tree = cKDTree(self.points)
        self.spacing = spacing

    def clearance(self, points, reach=2.0):
        """Signed distance [m] from points to the rock, positive in the water (nearest sample: overestimates the
        true distance by at most about the spacing); +inf for points farther than `reach` [m] from every sample."""
        points = np.atleast_2d(np.asarray(points, float))
        d, i = self.tree.query(points, distance_upper_bound=reach)
        near = np.isfinite(d)
        side = np.ones(len(points))
        side[near] = np.einsum("ij,ij->i", points[near] - self.points[i[near]], self.normals[i[near]])
        return np.where(side >= 0, d, -d)

    def reachable(self, grid, start, min_clearance, surface_z, surface_margin):
        """Boolean mask of the grid's cells where the hull's centre can be: at least min_clearance [m] from the
        rock, under the surface less surface_margin, connected to the start [m] (26-neighbours). Cells farther than
        2 m from the rock count as water here: one in the rock is walled off from the start by cells within 2 m of
        the rock on its side."""
        idx = np.stack(np.meshgrid(*[np.arange(n) for n in grid.shape], indexing="ij"), -1).reshape(-1, 3)
        centres = grid.centre(idx)
        ok = (self.clearance(centres) >= min_clearance) & (centres[:, 2] <= surface_z - surface_margin)
        ok = ok.reshape(grid.shape)
        labels, _ = ndimage.label(ok, ndimage.generate_binary_structure(3, 3))
        s = grid.index(np.asarray(start, float)[None])[0]
        if not grid.inside(s):
            raise ValueError(f"start {start} is outside the explored box")
        label = labels[tuple(s)]
        if label == 0:  # the start's own cell too near the rock: the nearest reachable cell's component
            near = ndimage.distance_transform_edt(labels == 0, return_indices=True)[1]
            label = labels[tuple(near[:, s[0], s[1], s[2]])]
        return labels == label

"""Map quality figures: occupied voxel centres against a world's triangles (precision, recall, F-score,
distances; Tanks-and-Temples style at a distance tau). numpy and scipy, no I/O."""

import math

import numpy as np

from unexmin.worlds.meshes import sample_surface


def expand(centres, sizes):
    """Centres of the finest voxels (edge: the smallest size) that the (possibly pruned, larger) leaves hold."""
    if not len(sizes):
        return centres, sizes
    res = float(sizes.min())
    out = []
    for n in np.unique(np.rint(sizes / res).astype(int)):
        sel = np.rint(sizes / res).astype(int) == n
        offsets = (np.arange(n) - (n - 1) / 2.0) * res
        grid = np.stack(np.meshgrid(offsets, offsets, offsets, indexing="ij"), -1).reshape(-1, 3)
        out.append((centres[sel][:, None, :] + grid[None, :, :]).reshape(-1, 3))
    centres = np.concatenate(out)
    return centres, np.full(len(centres), res)


def near_path(tris, path, reach):
    """Triangles with a vertex or the centroid within reach [m] of a path point."""
    from scipy.spatial import cKDTree

    tree = cKDTree(path)
    pts = np.concatenate([tris, tris.mean(axis=1, keepdims=True)], axis=1).reshape(-1, 3)
    d, _ = tree.query(pts, distance_upper_bound=reach)
    return np.isfinite(d).reshape(len(tris), 4).any(axis=1)


def seen_surface(tris, tau, path=None, sensor_range=10.0, seed=0):
    """The surface recall counts: (samples M x 3, their area [m2], their spacing [m]): the triangles within
    sensor_range of the path (all of them without a path), area-sampled at tau/2 or coarser (at most about 4
    million samples), less the samples farther than sensor_range from every path point."""
    from scipy.spatial import cKDTree

    seen_tris = tris if path is None else tris[near_path(tris, path, sensor_range + 1.0)]
    area = (
        0.5
        * np.linalg.norm(np.cross(seen_tris[:, 1] - seen_tris[:, 0], seen_tris[:, 2] - seen_tris[:, 0]), axis=1).sum()
    )
    seen_spacing = max(tau / 2.0, math.sqrt(area / 4e6)) if area > 0 else tau / 2.0
    seen, seen_area = sample_surface(seen_tris, seen_spacing, seed + 1)
    if path is not None and len(seen):
        d_path, _ = cKDTree(path).query(seen)
        seen_area *= float(np.mean(d_path <= sensor_range))
        seen = seen[d_path <= sensor_range]
    return seen, seen_area, seen_spacing


def recall_of(centres, seen, tau):
    """Fraction of the surface samples `seen` within tau of an occupied voxel centre."""
    from scipy.spatial import cKDTree

    if not len(seen) or not len(centres):
        return 0.0
    d_seen, _ = cKDTree(centres).query(seen, distance_upper_bound=tau * (1.0 + 1e-9))
    return float(np.mean(d_seen <= tau))


def evaluate(centres, tris, tau, path=None, sensor_range=10.0, seed=0):
    """The quality figures (dict) of occupied voxel centres against the triangles, and the per-voxel distances."""
    from scipy.spatial import cKDTree

    spacing = tau / 4.0
    # Precision: each voxel centre against a dense sample of the triangles near the voxels.
    wide_tris = tris[near_path(tris, centres, 2.0 * tau + 1.0)] if len(centres) else tris[:0]
    wide, _ = sample_surface(wide_tris, spacing, seed)
    # Recall: the surface within sensor range of the path.
    seen, seen_area, seen_spacing = seen_surface(tris, tau, path, sensor_range, seed)
    result = {
        "tau_m": tau,
        "occupied_voxels": int(len(centres)),
        "surface_samples": int(len(seen)),
        "surface_area_m2": round(seen_area, 3),
        "sample_spacing_m": spacing,
        "recall_sample_spacing_m": seen_spacing,
        "sensor_range_m": sensor_range if path is not None else None,
    }
    dist = np.full(len(centres), np.inf)
    if len(centres) and len(wide):
        dist, _ = cKDTree(wide).query(centres)
    precision = float(np.mean(dist <= tau)) if len(centres) else 0.0
    recall = recall_of(centres, seen, tau)
    finite = dist[np.isfinite(dist)]
    result.update(
        {
            "precision": precision,
            "recall": recall,
            "f_score": 2 * precision * recall / (precision + recall) if precision + recall > 0 else 0.0,
            "mean_distance_m": float(finite.mean()) if len(finite) else None,
            "p95_distance_m": float(np.percentile(finite, 95)) if len(finite) else None,
        }
    )
    return result, dist

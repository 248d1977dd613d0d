"""Stage evaluate: how far the scan lies from the collision mesh (a sample drawn from the tile files) and the
water held below the water level."""

import os

import numpy as np

from unexmin.worlds.from_scan.surface import distances, flooded_volume
from unexmin.worlds.from_scan.tiles import record_dtype

EVAL_POINTS = 1_000_000  # scan points measured against the collision mesh at most


def evaluation_sample(layout, count, seed):
    """Up to `count` scan points [m] drawn evenly from the tile files, each from its own tile's core."""
    rng = np.random.default_rng(seed)
    dtype = record_dtype(layout["normals"], layout["rgb"])
    axis = layout["axis"]
    total = sum(t.get("points", 0) for t in layout["tiles"])
    out = []
    for tile in layout["tiles"]:
        n = tile.get("points", 0)
        if n == 0 or not os.path.isfile(tile["file"]) or os.path.getsize(tile["file"]) < n * dtype.itemsize:
            continue
        rec = np.memmap(tile["file"], dtype=dtype, mode="r", shape=(n,))
        take = np.sort(rng.choice(n, size=min(n, max(1, int(count * n / total))), replace=False))
        p = np.asarray(rec["p"][take], dtype=np.float64)
        del rec
        lo, hi = tile["core"]
        p = p[np.isfinite(p).all(axis=1) & (p[:, axis] >= lo) & (p[:, axis] < hi)]
        out.append(p)
    return np.concatenate(out) if out else np.zeros((0, 3))


def evaluate(b):
    """Fills b.probe (up to EVAL_POINTS scan points), b.distances [m] (theirs to the collision mesh; one zero when
    there are none) and b.flooded [m^3] (None when the surface is not closed)."""
    with b.progress.stage("evaluate", "evaluate") as bar:
        b.probe = evaluation_sample(b.layout, EVAL_POINTS, b.options.seed)
        b.distances = distances(b.scene, b.probe) if len(b.probe) else np.zeros(1)
        b.flooded = flooded_volume(*b.collision, b.surface_z) if b.closed else None
        bar.update(1)
    return b

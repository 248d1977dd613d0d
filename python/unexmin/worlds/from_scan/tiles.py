"""The scan cut into overlapping tiles on disk, in two streaming passes (docs/world_from_scan.md#tiles).

1. survey(): one pass over the file: point count, bounds, spread, whether every point has a normal or a
   colour, and the set of occupied cells of CELL_RES resolutions (the surface's extent, whatever the
   scan's density).
2. plan(): slabs across the scan's longest axis, each holding (with its overlap on both sides) at most
   the points a tile's memory allows; each seam where the occupied cells per layer vary least within
   two layers (the surface crosses it, no wall runs along it).
3. bin_scan(): a second pass appends every point to the file of each tile whose overlapped slab holds it.
   load_tile() reads one back. Records: position [m] float64, normal float32 (when the scan has them),
   colour uint8 RGB (when it has them: the visual mesh's colours travel with the points).
Units: [m].
"""

import json
import math
from pathlib import Path

import numpy as np

from unexmin.worlds.from_scan.errors import ScanError
from unexmin.worlds.from_scan.stream import iter_chunks

CELL_RES = 4.0  # survey cells: this many resolutions (at least 0.5 m)
BITS = 21  # per axis in a packed cell key: +-2^20 cells around the scan's first point
PER_POINT_BYTES = 1500.0  # a tile's peak memory per down-sampled point, with a margin (docs/world_from_scan.md#memory)
TILE_BASE_BYTES = 0.45e9  # a tile worker's memory before its points (Python, NumPy, Open3D, Dask)
SEAM_LAYERS = 2  # survey layers on each side of a seam in which no wall should run along it
SEAM_FROM = 0.7  # a seam lies in the last 30 % of the widest slab the budget allows: tiles near their budget
DRIVER_BYTES = 0.6e9  # the driving process while the tiles build (Dask's scheduler and nannies, the survey)


def survey_cell(resolution):
    """[m] edge of the survey cells."""
    return max(CELL_RES * resolution, 0.5)


def _pack(ijk):
    off = 1 << (BITS - 1)
    if (np.abs(ijk) >= off).any():
        raise ScanError(f"the scan spans more than {off} survey cells along an axis (expected one mine)")
    i = (ijk + off).astype(np.int64)
    return (i[:, 0] << (2 * BITS)) | (i[:, 1] << BITS) | i[:, 2]


def _unpack(keys):
    off, mask = 1 << (BITS - 1), (1 << BITS) - 1
    return np.column_stack([(keys >> (2 * BITS)) & mask, (keys >> BITS) & mask, keys & mask]) - off


def survey(path, resolution, progress=None, min_voxels=200):
    """One streaming pass over the scan: a dict of count, finite, lo, hi [m], cov (3 x 3 [m^2]), normals
    and rgb (every point has them), origin [m] and cell [m] of the occupied survey cells (keys, packed),
    and voxels: occupied `resolution` voxels, counted up to `min_voxels` (enough to tell a usable scan)."""
    cell = survey_cell(resolution)
    count = finite = 0
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    origin = None
    s1, s2 = np.zeros(3), np.zeros((3, 3))
    keys = np.zeros(0, np.int64)
    voxels = np.zeros(0, np.int64)
    normals = rgb = True
    for c in iter_chunks(path):
        count += len(c.points)
        normals &= c.normals is not None
        rgb &= c.rgb is not None
        ok = np.isfinite(c.points).all(axis=1)
        p = c.points[ok]
        if c.normals is not None:
            length = np.linalg.norm(c.normals[ok], axis=1)
            normals &= bool((np.isfinite(length) & (length > 0.5)).all())
        if progress is not None:
            progress.update(c.done - progress.n)
        if len(p) == 0:
            continue
        if origin is None:
            origin = np.floor(p[0] / cell) * cell
        finite += len(p)
        lo, hi = np.minimum(lo, p.min(axis=0)), np.maximum(hi, p.max(axis=0))
        d = p - origin
        s1 += d.sum(axis=0)
        s2 += d.T @ d
        keys = np.union1d(keys, _pack(np.floor(d / cell).astype(np.int64)))
        if len(voxels) < min_voxels:
            voxels = np.union1d(voxels, _pack(np.floor(d / resolution).astype(np.int64)))
    if finite == 0:
        raise ScanError(f"{path}: no finite point (expected a point cloud of the mine's walls)")
    mean = s1 / finite
    cov = s2 / finite - np.outer(mean, mean)
    return {
        "count": count,
        "finite": finite,
        "lo": lo,
        "hi": hi,
        "cov": cov,
        "normals": bool(normals),
        "rgb": bool(rgb),
        "origin": origin,
        "cell": cell,
        "keys": keys,
        "voxels": int(len(voxels)),
    }


def overlap(resolution, max_gap):
    """[m] each tile reaches this far past its seams: Poisson's closing bubble over a tile's cut end, left
    within `max_gap` of the data by the trimming, and its looser fit there, both fall outside the core."""
    return 1.5 * max_gap + 4.0 * resolution


def tile_points_budget(memory_gb, workers):
    """Down-sampled points one tile may hold so that `workers` tiles at once and the driver fit in
    `memory_gb` [GB]."""
    per_tile = (memory_gb * 1e9 - DRIVER_BYTES) / max(1, workers) - TILE_BASE_BYTES
    return int(max(per_tile, 0.0) / PER_POINT_BYTES)


def plan(s, resolution, max_gap, max_points):
    """Tiles of a surveyed scan `s` (survey()): slabs across the longest axis of its bounds, the fewest
    for which every slab with its overlap holds at most `max_points` down-sampled points (estimated
    as occupied survey cells x (cell / resolution)^2). Returns a dict: axis, seams [m] (K - 1 of them),
    overlap [m], tiles [{index, core [lo, hi] along the axis (+-inf at the ends), lo, hi (the
    overlapped box [m]), estimate}] and fits (False when a slab of the least width is over budget)."""
    cell = s["cell"]
    ijk = _unpack(s["keys"])
    axis = int(np.argmax(s["hi"] - s["lo"]))
    layer = ijk[:, axis] - ijk[:, axis].min()
    base = s["origin"][axis] + ijk[:, axis].min() * cell  # [m] the first layer's low side
    per_layer = np.bincount(layer).astype(float) * (cell / resolution) ** 2
    n = len(per_layer)
    cum = np.concatenate([[0.0], np.cumsum(per_layer)])
    m = overlap(resolution, max_gap)
    reach = int(math.ceil(m / cell))  # layers of overlap on each side

    def estimate(a, b):  # layers [a, b) with their overlaps
        return cum[min(n, b + reach)] - cum[max(0, a - reach)]

    seams, a, fits = [], 0, True
    min_width = max(1, reach)
    while a < n:
        b = a + min_width
        if b >= n:
            seams.append(n)
            break
        if estimate(a, b) > max_points:
            fits = False
        while b < n and estimate(a, b + 1) <= max_points:
            b += 1
        if b >= n:
            seams.append(n)
            break
        lo_b = max(a + min_width, a + int(SEAM_FROM * (b - a)))
        cand = np.arange(lo_b, b + 1)
        # a wall running along the plane (a shaft's side, a gallery's end) fills one layer: a jump in the
        # cells per layer within SEAM_LAYERS of the seam; galleries crossing it keep the count even
        near = [per_layer[max(0, c - SEAM_LAYERS) : c + SEAM_LAYERS] for c in cand]
        near = np.array([w.max() - w.min() + 0.05 * w.sum() for w in near])
        b = int(cand[np.argmin(near)])  # the seam where the least surface runs
        seams.append(b)
        a = b
    seams_m = [base + b * cell for b in seams[:-1]]
    bounds = [-math.inf] + seams_m + [math.inf]
    tiles = []
    edges = [0] + seams
    for k in range(len(bounds) - 1):
        lo, hi = s["lo"].copy(), s["hi"].copy()
        lo[axis] = max(lo[axis], bounds[k] - m)
        hi[axis] = min(hi[axis], bounds[k + 1] + m)
        tiles.append(
            {
                "index": k,
                "core": [bounds[k], bounds[k + 1]],
                "lo": lo.tolist(),
                "hi": hi.tolist(),
                "estimate": int(estimate(edges[k], edges[k + 1])),
            }
        )
    return {"axis": axis, "seams": seams_m, "overlap": m, "tiles": tiles, "fits": fits}


def describe(tile, axis):
    """A tile's bounds in words, for reports and errors: 'tile 3 (x 20.0..40.0 m, overlap to 18.1..41.9 m)'."""
    a = "xyz"[axis]
    c0, c1 = tile["core"]
    core = f"{'-inf' if c0 == -math.inf else f'{c0:.1f}'}..{'inf' if c1 == math.inf else f'{c1:.1f}'}"
    lo, hi = tile["lo"], tile["hi"]
    box = " ".join(f"{'xyz'[i]} {lo[i]:.1f}..{hi[i]:.1f}" for i in range(3))
    return f"tile {tile['index']} ({a} {core} m; points in {box} m)"


def record_dtype(normals, rgb):
    fields = [("p", "<f8", (3,))]
    if normals:
        fields.append(("n", "<f4", (3,)))
    if rgb:
        fields.append(("c", "u1", (3,)))
    return np.dtype(fields)


def bin_scan(path, s, layout, folder, progress=None):
    """Second pass: each finite point appended to the file of every tile whose overlapped slab holds it
    (folder/tile_KKK.bin, records of record_dtype); folder/tiles.json describes them. Returns the
    layout with each tile's file and point count."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    dtype = record_dtype(s["normals"], s["rgb"])
    axis, tiles = layout["axis"], layout["tiles"]
    files = [open(folder / f"tile_{t['index']:03d}.bin", "wb") for t in tiles]
    counts = [0] * len(tiles)
    try:
        for c in iter_chunks(path):
            ok = np.isfinite(c.points).all(axis=1)
            rec = np.zeros(int(ok.sum()), dtype)
            rec["p"] = c.points[ok]
            if s["normals"]:
                rec["n"] = c.normals[ok]
            if s["rgb"]:
                rec["c"] = c.rgb[ok]  # the colours travel with their points into the tiles
            x = rec["p"][:, axis]
            for k, t in enumerate(tiles):
                inside = (x >= t["lo"][axis]) & (x <= t["hi"][axis])
                part = rec[inside]
                part.tofile(files[k])
                counts[k] += len(part)
            if progress is not None:
                progress.update(c.done - progress.n)
    finally:
        for f in files:
            f.close()
    for t, n in zip(tiles, counts):
        t["file"] = str(folder / f"tile_{t['index']:03d}.bin")
        t["points"] = n
    layout = dict(layout, normals=s["normals"], rgb=s["rgb"])
    (folder / "tiles.json").write_text(json.dumps(layout, indent=1) + "\n")
    return layout


def load_tile(tile, normals, rgb):
    """(points N x 3 [m], normals N x 3 or None, colours N x 3 uint8 or None) of a binned tile."""
    path = Path(tile["file"])
    if not path.is_file():
        raise ScanError(f"{path}: tile file missing (a remote worker needs --out on a file system it shares)")
    rec = np.fromfile(path, dtype=record_dtype(normals, rgb))
    return (
        rec["p"].astype(np.float64),
        rec["n"].astype(np.float64) if normals else None,
        rec["c"].copy() if rgb else None,
    )

"""One tile's surface (docs/world_from_scan.md#how), the task each Dask worker runs: its points read back
from the tile file, down-sampled, normals estimated and turned towards the void, screened Poisson,
trimmed, decimated (collision and visual meshes), each clipped to the tile's core slab. Units: [m]."""

import resource
import time

import numpy as np

from unexmin.worlds.from_scan.errors import ScanError
from unexmin.worlds.from_scan.scan import (
    MIN_POINTS,
    downsample,
    estimate_normals,
    orient_towards_void,
    orientation_samples,
    point_spacing,
)
from unexmin.worlds.from_scan.stitch import clip_slab, seam_shifts
from unexmin.worlds.from_scan.surface import (
    boundary_loops,
    close_holes,
    poisson_octree,
    reconstruct,
    rss_with_children,
    simplify,
    trim_unsupported,
)
from unexmin.worlds.from_scan.tiles import describe, load_tile

SPAWN_SAMPLES = 4000  # oriented points per tile handed back for the spawn search


def _cpu():
    """[s] user and system CPU time of this process and of its children that have ended (the decimations)."""
    own, children = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def release_memory():
    """Give the memory this process has freed back to the system: the cyclic garbage (trimesh's meshes and their
    caches) collected, and glibc's heaps trimmed (what Poisson's threads freed in arenas of their own is otherwise
    kept, and a worker's next tile peaks above a fresh process's)."""
    import ctypes
    import gc

    gc.collect()
    try:
        ctypes.CDLL("libc.so.6").malloc_trim(0)
    except (OSError, AttributeError):  # not glibc: its allocator keeps what it keeps
        pass


def _directed_keys(t, n):
    e = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]]).astype(np.int64)
    return e[:, 0] * n + e[:, 1], e[:, 1] * n + e[:, 0]


def folded_edges(t):
    """How many directed edges of the faces `t` appear more than once (0: every edge has at most two faces,
    wound consistently)."""
    _, count = np.unique(_directed_keys(t, int(t.max()) + 1)[0], return_counts=True)
    return int((count > 1).sum())


def manifold_edges(t):
    """True when no directed edge appears twice: every edge has at most two faces, wound consistently."""
    return folded_edges(t) == 0


def _hole_reach(v, loops):
    """[m] the largest distance of a loop's vertex from its loop's centroid."""
    return max(float(np.linalg.norm(v[loop] - v[loop].mean(axis=0), axis=1).max()) for loop in loops)


def _nearest(points, queries, reach):
    """Index of the point of `points` (N x 3) nearest each of `queries` (M x 3): searched among the points
    within `reach` [m] of the queries' bounds (a k-d tree of those few, not of the whole surface); the same
    answer as a search of all of them, to which it falls back when one query's nearest is farther."""
    from scipy.spatial import cKDTree

    lo, hi = queries.min(axis=0) - reach, queries.max(axis=0) + reach
    near = np.nonzero(((points >= lo) & (points <= hi)).all(axis=1))[0]
    if len(near):
        d, i = cKDTree(points[near]).query(queries)
        if (d <= reach).all():  # each query's ball of `reach` lies within the bounds: nothing nearer outside
            return near[i]
    return cKDTree(points).query(queries)[1]


def mended(v, t, fine=None):
    """The surface (v, t) with its folds cut out and patched, or None when that does not make it manifold:
    the faces on a directed edge used twice (a fold, where fast-simplification collapsed an edge across
    another) are removed, then, if that is not enough, every face touching their vertices too; each hole this
    opens (a boundary loop none of whose edges bounded the surface before) is closed by a fan from the vertex
    of `fine` (the surface before decimation, N x 3 [m]) nearest its centroid, or from the centroid. The
    surface's own boundaries (its trimmed edges) stay as they are."""
    n = len(v)
    key, opposite = _directed_keys(t, n)
    _, inverse, count = np.unique(key, return_inverse=True, return_counts=True)
    folded = (count[inverse] > 1).reshape(3, -1).any(axis=0)
    if not folded.any():
        return v, t
    border = set(key[~np.isin(key, opposite)].tolist())  # the surface's own boundary edges
    for cut in (folded, np.isin(t, np.unique(t[folded])).any(axis=1)):
        kept = t[~cut]
        fresh = [
            loop
            for loop in boundary_loops(kept)
            if not any(a * n + b in border for a, b in zip(loop, loop[1:] + loop[:1]))
        ]
        centres = np.array([v[loop].mean(axis=0) for loop in fresh]).reshape(-1, 3)
        if fine is not None and len(fresh):
            centres = fine[_nearest(fine, centres, _hole_reach(v, fresh))]  # the apex on the surface
        mv, mt, _, _, _ = close_holes(v, kept, fresh, centres)
        if manifold_edges(mt):
            return mv, mt
    return None


def decimated(v, t, edge):
    """simplify() to `edge` [m]: fast-simplification, its few folds mended (mended()); Open3D's decimation
    when the mended surface is still not manifold; the surface as it was when both fail."""
    dv, dt = simplify(v, t, edge, "fast")
    if len(dt):
        m = mended(dv, dt, v)
        if m is not None:
            return m
    dv, dt = simplify(v, t, edge, "open3d")
    if len(dt) and manifold_edges(dt):
        return dv, dt
    return v, t


def decimated_pair(v, t, edge, visual_edge):
    """The collision and visual surfaces: decimated() to `edge` and to `visual_edge` [m]; the visual one from the
    collision one (a few times fewer triangles to decimate than the fine surface) when it is no finer than it, else
    from the fine surface `v, t`."""
    dv, dt = decimated(v, t, edge)
    vv, vt = decimated(dv, dt, visual_edge) if visual_edge >= edge else decimated(v, t, visual_edge)
    return (dv, dt), (vv, vt)


def _areas(v, t, tree, near, threads):
    """[m^2] (seen, bridged): the area of the triangles (v, t) whose centroid lies within `near` [m] of a point of
    `tree` (a wall the scan saw), and of the others (a gap bridged)."""
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    d, _ = tree.query((a + b + c) / 3.0, distance_upper_bound=near, workers=threads)
    seen = np.isfinite(d)
    return float(area[seen].sum()), float(area[~seen].sum())


def build_tile(tile, layout, resolution, max_gap, edge, visual_edge, seed, threads=1):
    """The tile's result (a dict): 'collision' and 'visual' (v, t) clipped to its core slab widened by the
    largest seam shift and a resolution on each side (stitch.seam_shifts), facing out of the void;
    poisson_triangles (the fine surface in the core), points read and used, spacing [m], depth,
    decided (fraction of orientation samples that decided), a sample of oriented points (for spawns),
    wall and bridged area [m^2], seconds per stage (wall), cpu_seconds (the process's CPU time over the
    tile, its decimating children's included), peak_rss_mb of the worker (with a decimating child's on top
    while it ran: surface.rss_with_children). `threads`: threads of Poisson and the k-d tree queries (1 on a
    Dask worker: the tiles are the parallelism). A ScanError names the tile and its bounds when its points are
    not finite or too few."""
    from scipy.spatial import cKDTree

    name = describe(tile, layout["axis"])
    times = {}
    cpu0 = _cpu()
    t0 = time.monotonic()
    raw, normals, _rgb = load_tile(tile, layout["normals"], layout["rgb"])  # _rgb: per-point colours, if any
    bad = int((~np.isfinite(raw).all(axis=1)).sum())
    if bad:
        raise ScanError(f"{name}: {bad} of {len(raw)} points are not finite (corrupted tile file {tile['file']})")
    points, normals = downsample(raw, normals, resolution)
    read = len(raw)
    del raw
    if len(points) < MIN_POINTS:
        raise ScanError(
            f"{name}: {len(points)} points after down-sampling to {resolution} m (expected at least {MIN_POINTS}; "
            f"the tile file {tile['file']} holds {read})"
        )
    times["read"] = time.monotonic() - t0
    t0 = time.monotonic()
    tree = cKDTree(points)  # one k-d tree of the tile's points: spacing, trimming, areas
    if normals is None:
        normals = estimate_normals(points, resolution)
    spacing = point_spacing(points, seed, tree=tree)
    normals, decided = orient_towards_void(
        points, normals, resolution, seed=seed, samples=orientation_samples(len(points), spacing), threads=threads
    )
    times["normals"] = time.monotonic() - t0
    t0 = time.monotonic()
    depth, scale = poisson_octree(points, max(resolution, spacing))
    v, t = reconstruct(points, normals, depth, threads, scale)
    release_memory()
    times["poisson"] = time.monotonic() - t0
    t0 = time.monotonic()
    v, t = trim_unsupported(v, t, points, max_gap, tree, threads)
    release_memory()
    if len(t) == 0:
        raise ScanError(f"{name}: no usable surface: nothing of the reconstruction lies within --max-gap {max_gap} m")
    times["trim"] = time.monotonic() - t0
    t0 = time.monotonic()
    axis, (lo, hi) = layout["axis"], tile["core"]
    (dv, dt), (vv, vt) = decimated_pair(v, t, edge, visual_edge)
    # the meshes reach past the core as far as a seam may move (stitch.choose_seams), the fine surface not
    reach = max(seam_shifts(layout["overlap"], resolution)) + resolution
    cv, ct = clip_slab(dv, dt, axis, lo - reach, hi + reach)
    vv, vt = clip_slab(vv, vt, axis, lo - reach, hi + reach)
    fv, ft = clip_slab(v, t, axis, lo, hi)
    del v, t, dv, dt
    release_memory()
    times["decimate"] = time.monotonic() - t0
    wall_area, bridged_area = _areas(fv, ft, tree, 3.0 * resolution, threads)
    fine_triangles = len(ft)
    del fv, ft, tree
    release_memory()
    x = points[:, axis]
    core = (x >= lo) & (x < hi)
    rng = np.random.default_rng(seed + tile["index"])
    idx = np.nonzero(core)[0]
    pick = idx[rng.choice(len(idx), size=min(SPAWN_SAMPLES, len(idx)), replace=False)] if len(idx) else idx
    return {
        "index": tile["index"],
        "collision": (cv, ct),
        "visual": (vv, vt),
        "poisson_triangles": int(fine_triangles),
        "points_read": read,
        "points_used": int(core.sum()),
        "spacing": spacing,
        "depth": depth,
        "decided": decided,
        "samples": (points[pick], normals[pick]),
        "wall_area": wall_area,
        "bridged_area": bridged_area,
        "seconds": {k: round(s, 2) for k, s in times.items()},
        "cpu_seconds": round(_cpu() - cpu0, 2),
        "peak_rss_mb": round(rss_with_children() / 2**20, 1),
    }

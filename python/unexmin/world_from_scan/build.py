"""A surveyed point cloud of a mine (laser, sonar, the robots' own maps) to a simulator world in one
command (docs/world_from_scan.md): what the thesis did by hand for Kaatiala (5.2) with MeshLab.

    python -m unexmin.world_from_scan SCAN --out DIR [--resolution 0.1] [--memory-gb 8] [--scheduler ADDR]

Stages: survey (one streaming pass: bounds, extent of the surface), tiles (overlapping slabs sized by the
memory budget; a second pass bins the points into tile files), each tile on Dask (down-sampling, normals
turned to face the void, screened Poisson, trimming, decimation, clipping to its slab), stitching (the
tiles' seams zipped, holes closed: one closed surface), spawn points, evaluation, the world files and a
report. The whole cloud is never in memory. Units: [m]; frame: the scan's own, taken as the world frame.
"""

import argparse
import json
import math
import os
import resource
import shutil
import signal
import sys
import time
from pathlib import Path

import numpy as np

from unexmin.world_from_scan.cluster import run_tiles
from unexmin.world_from_scan.colours import streamed_vertex_colours
from unexmin.world_from_scan.errors import ScanError
from unexmin.world_from_scan.scan import MIN_POINTS
from unexmin.world_from_scan.stitch import choose_seams, clip_parts, seam_shifts, stitch
from unexmin.world_from_scan.stream import scan_size
from unexmin.world_from_scan.surface import (
    HULL_RADIUS,
    close_holes,
    closed_surface,
    distances,
    find_spawns,
    flooded_volume,
    raycasting_scene,
)
from unexmin.world_from_scan.tile import folded_edges, mended
from unexmin.world_from_scan.tiles import DRIVER_BYTES, bin_scan, plan, record_dtype, survey, tile_points_budget
from unexmin.worlds.meshes import write_ply
from unexmin.worlds.schema import read_world

EVAL_POINTS = 1_000_000  # scan points measured against the collision mesh at most


# ------------------------------------------------------------------------------------------ outputs
def world_yaml(name, surface_z, visibility, current_speed, meshes, spawns, source):
    """The world file's text; `meshes`: (entry name, file, collision, visual, extra keys) per mesh."""
    lines = [
        f"# World made from the scan {source} by python -m unexmin.world_from_scan (docs/world_from_scan.md).",
        "# Schema: docs/worlds.md. Units: SI; world frame = the scan's frame (ENU, z up).",
        f"name: {name}",
        "gravity: 9.81                                 # [m/s^2]",
        f"water: {{density: 1000.0, surface_z: {surface_z:.4f}}}   # [kg/m^3]; [m] the water level",
        "atmospheric_pressure: 101325.0                # [Pa] at the free surface",
        f"visibility: {{level: {visibility}, colour: [0.32, 0.28, 0.18]}}   # suspended sediment: brownish murk",
        "ray_caster: embree",
        "current:                                      # bounded Gauss-Markov per variable",
        f"  speed: {{mean: {current_speed}, min: 0.0, max: {max(0.1, 2 * current_speed)}, noise: "
        f"{0.1 * current_speed:.4g}, mu: 0.02}}   # [m/s]",
        "  horizontal_angle: {mean: 0.0, min: -3.1416, max: 3.1416, noise: 0.0, mu: 0.01}   # [rad]",
        "  vertical_angle: {mean: 0.0, min: -0.15, max: 0.15, noise: 0.0, mu: 0.05}        # [rad]",
        "meshes:                                       # together a closed surface, faces towards the water",
    ]
    for entry, file, collision, visual, extra in meshes:
        lines.append(
            f"  - {{name: {entry}, file: {file}, scale: [1, 1, 1], xyz: [0, 0, 0], rpy: [0, 0, 0], "
            f"collision: {str(collision).lower()}, visual: {str(visual).lower()}{extra}}}"
        )
    lines.append("robots:                                       # checked: in the water, clearance [m] to the walls")
    for k, (xyz, room) in enumerate(spawns):
        lines.append(
            f"  - {{name: UX_{k + 1}, description: ux1.urdf.xacro, xyz: [{xyz[0]:.3f}, {xyz[1]:.3f}, "
            f"{xyz[2]:.3f}], rpy: [0, 0, 0]}}   # clearance {room:.2f} m"
        )
    return "\n".join(lines) + "\n"


def mend_folds(v, t):
    """(v, t, folds): the stitched surface with any edge that zip strips or caps use the same way twice (folds)
    cut out and closed again (tile.mended); as it was when it has none or when that does not make it manifold."""
    folds = folded_edges(t) if len(t) else 0
    m = mended(v, t) if folds else None
    return (v, t, 0) if m is None else (m[0], m[1], folds)


def split_parts(v, t, axis, seams):
    """The surface's triangles by tile (the slab holding each centroid): a list of (v, t) compacted."""
    k = np.searchsorted(np.asarray(seams, dtype=float), v[t].mean(axis=1)[:, axis], side="right")
    parts = []
    for i in range(len(seams) + 1):
        tk = t[k == i]
        used = np.unique(tk)
        remap = np.full(len(v), -1, dtype=np.int64)
        remap[used] = np.arange(len(used))
        parts.append((v[used], remap[tk]))
    return parts


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


def _check_options(resolution, edge, visual_edge, max_gap, visibility, memory_gb, workers, retries):
    if not resolution > 0:
        raise ScanError(f"--resolution must be > 0 [m], got {resolution}")
    if not (edge > 0 and visual_edge > 0):
        raise ScanError(f"--edge and --visual-edge must be > 0 [m], got {edge} and {visual_edge}")
    if not max_gap > resolution:
        raise ScanError(f"--max-gap must exceed the resolution {resolution} m, got {max_gap}")
    if visibility not in ("none", "low", "medium", "high"):
        raise ScanError(f"--visibility must be none, low, medium or high, got {visibility!r}")
    if not memory_gb > 0:
        raise ScanError(f"--memory-gb must be > 0 [GB], got {memory_gb}")
    if workers is not None and workers < 0:
        raise ScanError(f"--workers must be >= 0, got {workers}")
    if retries < 0:
        raise ScanError(f"--retries must be >= 0, got {retries}")


def build_world(
    scan,
    out,
    name=None,
    resolution=0.1,
    water_level=None,
    max_gap=1.0,
    clearance=0.6,
    edge=0.3,
    visual_edge=1.0,
    visibility="medium",
    current_speed=0.0,
    seed=0,
    quiet=False,
    memory_gb=8.0,
    workers=None,
    scheduler=None,
    retries=1,
    keep_tiles=False,
):
    """The whole pipeline; returns the report (dict), also written as <out>/<name>.json. Tiles that fail
    are listed in the report's `failed_tiles` (the world is built from the others)."""
    from tqdm import tqdm

    _check_options(resolution, edge, visual_edge, max_gap, visibility, memory_gb, workers, retries)
    scan = Path(scan)
    name = name or scan.stem
    out = Path(out)
    times = {}
    t_all = time.monotonic()
    workers = (os.cpu_count() or 1) if workers is None else workers

    def stage(label, total=1, unit="step"):
        return tqdm(
            total=total,
            desc=f"{label:<12}",
            unit=unit,
            unit_scale=unit in ("point", "B"),
            disable=quiet,
            file=sys.stderr,
            leave=True,
        )

    def note(text):
        if not quiet:
            print(f"world_from_scan: note: {text}", file=sys.stderr)

    # 1. survey: one streaming pass
    total, unit = scan_size(scan)
    t0 = time.monotonic()
    with stage("survey", total, unit) as bar:
        s = survey(scan, resolution, progress=bar)
    times["survey"] = round(time.monotonic() - t0, 2)
    if s["voxels"] < MIN_POINTS:
        raise ScanError(
            f"{scan}: no usable surface: {s['voxels']} points after down-sampling to "
            f"{resolution} m (expected at least {MIN_POINTS}: a denser scan or a finer --resolution)"
        )
    spread = np.sqrt(np.maximum(np.linalg.eigvalsh(s["cov"]), 0.0))  # ascending [m]
    if spread[1] < 5 * resolution:
        raise ScanError(
            f"{scan}: no usable surface: the points lie along a line (spread {spread[2]:.3g} x "
            f"{spread[1]:.3g} x {spread[0]:.3g} m; expected walls around a void)"
        )
    # 2. tiles: planned from the memory budget, the points binned on disk (second pass)
    local_workers = 0 if scheduler else workers
    budget = tile_points_budget(memory_gb, max(1, local_workers))
    layout = plan(s, resolution, max_gap, budget)
    if len(layout["tiles"]) == 1 and not scheduler:
        local_workers = 0  # one tile: built in this process, no cluster to start (its budget holds all the more)
    if not layout["fits"]:
        note(
            f"a slab of the least width holds more than the {budget:,} points a tile may hold in "
            f"--memory-gb {memory_gb}: the run may take more memory"
        )
    work = out / f"{name}_tiles"
    created = not out.exists()
    if work.exists():
        shutil.rmtree(work)
    try:
        t0 = time.monotonic()
        with stage("tile files", total, unit) as bar:
            layout = bin_scan(scan, s, layout, work, progress=bar)
        times["bin"] = round(time.monotonic() - t0, 2)
        # 3. each tile on Dask
        options = {
            "resolution": resolution,
            "max_gap": max_gap,
            "edge": edge,
            "visual_edge": visual_edge,
            "seed": seed,
            # a Dask worker runs one tile on one thread (the tiles are the parallelism); in this process: every core
            "threads": 1 if local_workers or scheduler else -1,
        }
        per_worker = (memory_gb * 1e9 - DRIVER_BYTES) / max(1, local_workers)  # [B] each worker's limit
        t0 = time.monotonic()
        with stage("tiles", len(layout["tiles"]), "tile") as bar:
            results, failures = run_tiles(
                layout, options, local_workers, per_worker, scheduler, retries, bar, None if quiet else note
            )
        times["tiles"] = round(time.monotonic() - t0, 2)
        driver_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # this process, up to the tiles' end
        for f in failures:
            print(
                f"world_from_scan: error: {f['tile']} failed after {retries + 1} attempts: {f['error']}",
                file=sys.stderr,
            )
        if not results:
            first = failures[0]["error"] if failures else "no tile"
            raise ScanError(f"{scan}: no usable surface: no tile could be built ({first})")
        spacing = max(r["spacing"] for r in results.values())
        if spacing > resolution:
            note(
                f"the scan's points are {spacing:.3g} m apart, sparser than --resolution {resolution} m: "
                f"the surface is reconstructed at {spacing:.3g} m"
            )
        # 4. stitching: the seams zipped, the remaining holes closed, the surface turned to face the void
        t0 = time.monotonic()
        axis = layout["axis"]
        order = [results.get(t["index"]) for t in layout["tiles"]]
        with stage("stitch", 2) as bar:
            collision, tolerance = [r and r["collision"] for r in order], 2.0 * edge + resolution
            # each seam where the two tiles' surfaces cross it in loops that pair up, the visual mesh's the same
            shifts = seam_shifts(layout["overlap"], resolution)
            seams = choose_seams(collision, axis, layout["seams"], tolerance, shifts)
            v, t, zipped, left = stitch(clip_parts(collision, axis, seams), axis, seams, tolerance)
            if len(t) == 0:
                raise ScanError(f"{scan}: no usable surface: nothing of the reconstruction lies within --max-gap")
            v, t, holes, hole_area, _ = close_holes(v, t)
            v, t, folds = mend_folds(v, t)
            bar.update(1)
            visual = clip_parts([r and r["visual"] for r in order], axis, seams)
            vv, vt, _, _ = stitch(visual, axis, seams, 2.0 * visual_edge + resolution)
            vv, vt, _, _, _ = close_holes(vv, vt)
            vv, vt, _ = mend_folds(vv, vt)
            bar.update(1)
        times["stitch"] = round(time.monotonic() - t0, 2)
        import trimesh

        closed = closed_surface(v, t)
        signed = float(trimesh.Trimesh(v, t, process=False).volume) if closed else float("nan")
        if closed and signed > 0:  # faces must point into the void: the enclosed volume is then negative
            t, vt, signed = t[:, ::-1].copy(), vt[:, ::-1].copy(), -signed
        volume = -signed if closed else float("nan")
        if closed and volume < (4 / 3) * math.pi * (HULL_RADIUS + clearance) ** 3:
            raise ScanError(
                f"{scan}: no usable surface: the closed surface holds {volume:.3g} m^3 of water, not "
                f"room for one robot (expected walls around a void)"
            )
        # 5. spawns, evaluation
        surface_z = float(s["hi"][2]) if water_level is None else float(water_level)
        scene = raycasting_scene(v, t)
        t0 = time.monotonic()
        with stage("spawns") as bar:
            sp = np.concatenate([r["samples"][0] for r in results.values()])
            sn = np.concatenate([r["samples"][1] for r in results.values()])
            spawns = find_spawns(scene, sp, sn, surface_z, clearance, seed=seed)
            bar.update(1)
        times["spawns"] = round(time.monotonic() - t0, 2)
        if not spawns:
            raise ScanError(
                f"{scan}: no point of the water (below z = {surface_z:.2f} m) has {clearance} m of "
                "clearance to the walls: no room for a robot"
            )
        t0 = time.monotonic()
        with stage("evaluate") as bar:
            probe = evaluation_sample(layout, EVAL_POINTS, seed)
            d = distances(scene, probe) if len(probe) else np.zeros(1)
            flooded = flooded_volume(v, t, surface_z) if closed else None
            bar.update(1)
        times["evaluate"] = round(time.monotonic() - t0, 2)
        # 6. files: the whole meshes, the parts per tile, two world files
        out.mkdir(parents=True, exist_ok=True)
        collision_file, visual_file = f"{name}_collision.ply", f"{name}_visual.ply"
        comment = f"unexmin world_from_scan {scan.name} resolution {resolution}"
        write_ply(out / collision_file, v, t, comment + " collision", inward=False)
        # the scan's RGB onto the visual mesh's vertices, the scan read again in chunks (colours.py)
        visual_colours = streamed_vertex_colours(scan, vv) if layout["rgb"] else None
        write_ply(out / visual_file, vv, vt, comment + " visual", inward=False, colours=visual_colours)
        parts = []
        whole_visual = None  # a part's vertices are the whole visual mesh's: their colours are found in it
        if visual_colours is not None:
            from scipy.spatial import cKDTree

            whole_visual = cKDTree(vv)
        for k, ((pv, pt), (qv, qt)) in enumerate(zip(split_parts(v, t, axis, seams), split_parts(vv, vt, axis, seams))):
            files = (f"{name}_collision_{k:03d}.ply", f"{name}_visual_{k:03d}.ply")
            write_ply(out / files[0], pv, pt, f"{comment} collision tile {k}", inward=False)
            part_colours = None if whole_visual is None else visual_colours[whole_visual.query(qv, k=1)[1]]
            write_ply(out / files[1], qv, qt, f"{comment} visual tile {k}", inward=False, colours=part_colours)
            parts.append({"index": k, "collision": files[0], "visual": files[1], "triangles": int(len(pt))})
        world_path, parts_path = out / f"{name}.world", out / f"{name}_parts.world"
        # the cameras see the coloured visual mesh, else the finer collision mesh (docs/worlds.md "Who sees a mesh")
        seen, look = (
            ("", ", material: {kind: vertex_colours}")
            if visual_colours is not None
            else (
                ", seen_by: [cameras, sonars]",
                ", seen_by: []",
            )
        )
        whole = [(name, collision_file, True, False, seen), (f"{name}_visual", visual_file, False, True, look)]
        by_part = [(f"{name}_{p['index']:03d}", p["collision"], True, False, seen) for p in parts]
        by_part += [(f"{name}_visual_{p['index']:03d}", p["visual"], False, True, look) for p in parts]
        for path, meshes in ((world_path, whole), (parts_path, by_part)):
            path.write_text(world_yaml(name, surface_z, visibility, current_speed, meshes, spawns, scan.name))
            read_world(path)  # what the simulator will read follows the schema
        if not keep_tiles:
            shutil.rmtree(work, ignore_errors=True)
        rep = {
            "scan": str(scan),
            "points_read": int(s["count"]),
            "points_finite": int(s["finite"]),
            "points_used": int(sum(r["points_used"] for r in results.values())),
            "normals": "read" if s["normals"] else "estimated",
            "orientation_samples_decided": round(float(np.mean([r["decided"] for r in results.values()])), 3),
            "resolution": resolution,
            "point_spacing": round(spacing, 4),
            "poisson_depth": int(max(r["depth"] for r in results.values())),
            "max_gap": max_gap,
            "poisson_triangles": int(sum(r["poisson_triangles"] for r in results.values())),
            "collision": {"file": collision_file, "triangles": int(len(t)), "vertices": int(len(v)), "edge": edge},
            "visual": {
                "file": visual_file,
                "triangles": int(len(vt)),
                "vertices": int(len(vv)),
                "edge": visual_edge,
                "colours": visual_colours is not None,
            },
            "world": world_path.name,
            "parts_world": parts_path.name,
            "tiles": {
                "axis": "xyz"[axis],
                "seams": [round(x, 3) for x in seams],
                "overlap": round(layout["overlap"], 3),
                "count": len(layout["tiles"]),
                "budget_points": budget,
                "zipped_loops": zipped,
                "open_loops": left,
                "parts": parts,
                "built": [
                    {
                        "index": r["index"],
                        "points_read": r["points_read"],
                        "points_used": r["points_used"],
                        "estimate": layout["tiles"][r["index"]]["estimate"],
                        "peak_rss_mb": r["peak_rss_mb"],
                        "seconds": r["seconds"],
                        "cpu_seconds": r["cpu_seconds"],
                    }
                    for r in sorted(results.values(), key=lambda r: r["index"])
                ],
            },
            "failed_tiles": failures,
            "closed": closed,
            "volume": round(volume, 3) if closed else None,
            "flooded_volume": round(flooded, 3) if flooded is not None else None,
            "water_level": surface_z,
            "wall_area": round(sum(r["wall_area"] for r in results.values()), 3),
            "bridged_area": round(sum(r["bridged_area"] for r in results.values()), 3),
            "holes_closed": holes,
            "seam_folds": folds,
            "holes_area": round(hole_area, 3),
            "scan_to_mesh": {
                "mean": round(float(d.mean()), 4),
                "p95": round(float(np.percentile(d, 95)), 4),
                "max": round(float(d.max()), 4),
                "points": int(len(probe)),
            },
            "bbox_min": [round(x, 3) for x in v.min(axis=0)],
            "bbox_max": [round(x, 3) for x in v.max(axis=0)],
            "spawns": [{"xyz": [round(float(x), 3) for x in p], "clearance": round(c, 3)} for p, c in spawns],
            "seconds": times,
            "total_seconds": round(time.monotonic() - t_all, 2),
            "peak_rss_mb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1),
            "workers_peak_rss_mb": round(max(r["peak_rss_mb"] for r in results.values()), 1),
            "peak_rss_bound_mb": round(
                max(
                    driver_mb + local_workers * max(r["peak_rss_mb"] for r in results.values()),
                    resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
                ),
                1,
            ),
            "memory_gb": memory_gb,
            "workers": local_workers if not scheduler else None,
            "scheduler": scheduler,
        }
        (out / f"{name}.json").write_text(json.dumps(rep, indent=1) + "\n")
        return rep
    except BaseException:  # nothing left behind by a run that stops: no tile files, no empty folder
        shutil.rmtree(work, ignore_errors=True)
        if created and out.is_dir() and not any(out.iterdir()):
            out.rmdir()
        raise


def report(rep):
    s = rep["scan_to_mesh"]
    vol = f"{rep['volume']:,.1f}" if rep["volume"] is not None else "n/a (not closed)"
    flooded = f"{rep['flooded_volume']:,.1f}" if rep["flooded_volume"] is not None else "n/a"
    return "\n".join(
        [
            f"world '{rep['world']}' from {rep['scan']}: {rep['points_read']:,} points read, {rep['points_used']:,} at "
            f"{rep['resolution']} m, normals {rep['normals']}, Poisson depth {rep['poisson_depth']}, "
            f"{rep['total_seconds']} s, peak {rep['peak_rss_mb']:.0f} MB",
            f"  collision: {rep['collision']['triangles']:,} triangles "
            f"(edge {rep['collision']['edge']} m, from Poisson's "
            f"{rep['poisson_triangles']:,}), {rep['collision']['file']}",
            f"  visual:    {rep['visual']['triangles']:,} triangles, {rep['visual']['file']}",
            f"  closed: {rep['closed']}, void volume {vol} m^3, flooded (below z = {rep['water_level']:.2f}) "
            f"{flooded} m^3, "
            f"wall area {rep['wall_area']:,.1f} m^2 (and {rep['bridged_area']:,.1f} m^2 bridged over gaps)",
            f"  holes closed: {rep['holes_closed']} ({rep['holes_area']:,.1f} m^2); tiles: {rep['tiles']['count']} "
            f"along {rep['tiles']['axis']}, {rep['tiles']['zipped_loops']} seam loops zipped, "
            f"{len(rep['failed_tiles'])} failed; parts in {rep['parts_world']}",
            f"  scan to mesh: mean {s['mean'] * 100:.1f} cm, 95th percentile {s['p95'] * 100:.1f} cm, "
            f"max {s['max']:.2f} m",
            "  spawns: " + ", ".join(f"{sp['xyz']} (clearance {sp['clearance']:.2f} m)" for sp in rep["spawns"]),
        ]
    )


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m unexmin.world_from_scan", description=__doc__.split("\n\n")[0])
    ap.add_argument("scan", help="point cloud: .ply .pcd .xyz .xyzn .xyzrgb .pts .txt .asc .csv .las .laz [m]")
    ap.add_argument("--out", required=True, help="output folder (created)")
    ap.add_argument("--name", help="world and file name prefix (default: the scan's file name)")
    ap.add_argument("--resolution", type=float, default=0.1, help="[m] voxel size and Poisson cell (default 0.1)")
    ap.add_argument("--water-level", type=float, help="[m] z of the water surface (default: the scan's top)")
    ap.add_argument(
        "--max-gap",
        type=float,
        default=1.0,
        help="[m] surface farther than this from every scan point is trimmed (default 1.0)",
    )
    ap.add_argument(
        "--clearance",
        type=float,
        default=0.6,
        help="[m] least distance from a spawn point to the walls (default 0.6: hull 0.3 + 0.3)",
    )
    ap.add_argument("--visibility", default="medium", help="none|low|medium|high (default medium)")
    ap.add_argument("--current-speed", type=float, default=0.0, help="[m/s] mean water current (default 0)")
    ap.add_argument(
        "--edge",
        type=float,
        default=0.3,
        help="[m] triangle edge of the collision mesh, decimated from Poisson's (default 0.3)",
    )
    ap.add_argument("--visual-edge", type=float, default=1.0, help="[m] triangle edge of the visual mesh (default 1.0)")
    ap.add_argument("--seed", type=int, default=0, help="seed of the samplings (default 0)")
    ap.add_argument("--quiet", action="store_true", help="no progress bars")
    ap.add_argument(
        "--memory-gb",
        type=float,
        default=8.0,
        help="[GB] memory of the whole run: sizes the tiles (default 8)",
    )
    where = ap.add_mutually_exclusive_group()
    where.add_argument(
        "--workers",
        type=int,
        help="worker processes of the local Dask cluster (default: one per core; 0: no Dask, in this process)",
    )
    where.add_argument("--scheduler", help="address of a running Dask scheduler, e.g. tcp://10.0.0.5:8786")
    ap.add_argument("--retries", type=int, default=1, help="attempts after a tile's first failure (default 1)")
    ap.add_argument("--keep-tiles", action="store_true", help="keep the tile files (DIR/NAME_tiles/)")
    args = ap.parse_args(argv)
    # a SIGTERM unwinds like an exception: the local cluster's workers are stopped, the tile files removed
    signal.signal(signal.SIGTERM, lambda signum, frame: sys.exit(128 + signum))
    try:
        rep = build_world(
            args.scan,
            args.out,
            args.name,
            args.resolution,
            args.water_level,
            args.max_gap,
            args.clearance,
            args.edge,
            args.visual_edge,
            args.visibility,
            args.current_speed,
            args.seed,
            args.quiet,
            args.memory_gb,
            args.workers,
            args.scheduler,
            args.retries,
            args.keep_tiles,
        )
    except ScanError as e:
        print(f"world_from_scan: error: {e}", file=sys.stderr)
        return 2
    print(report(rep))
    return 3 if rep["failed_tiles"] else 0

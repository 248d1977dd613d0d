"""A surveyed point cloud of a mine (laser, sonar, the robots' own maps) to a simulator world in one
command (docs/world_from_scan.md): what the thesis did by hand for Kaatiala (5.2) with MeshLab.

    python -m unexmin.worlds.from_scan SCAN --out DIR [--resolution 0.1] [--memory-gb 8] [--scheduler ADDR]

build_world passes one build record (record.Build) through the stages of stages/, in this order: survey (one
streaming pass: bounds, extent of the surface), tiling (overlapping slabs sized by the memory budget; a second pass
bins the points into tile files), tiles (each on Dask: down-sampling, normals turned to face the void, screened
Poisson, trimming, decimation, clipping to its slab), stitching (the tiles' seams zipped, holes closed: one closed
surface, turned to face the void), spawns, evaluation, the files (meshes, world files) and the report. The whole
cloud is never in memory. Units: [m]; frame: the scan's own, taken as the world frame.
"""

import argparse
import os
import shutil
import signal
import sys
import time
from contextlib import contextmanager
from dataclasses import fields
from pathlib import Path

from unexmin.worlds.from_scan.errors import ScanError
from unexmin.worlds.from_scan.record import Build, Options, Progress
from unexmin.worlds.from_scan.stages.evaluation import evaluate
from unexmin.worlds.from_scan.stages.files import write_meshes, write_worlds
from unexmin.worlds.from_scan.stages.report import write_report
from unexmin.worlds.from_scan.stages.spawns import place_spawns
from unexmin.worlds.from_scan.stages.stitching import orient_surface, stitch_tiles
from unexmin.worlds.from_scan.stages.survey import survey_scan
from unexmin.worlds.from_scan.stages.tiles import build_tiles
from unexmin.worlds.from_scan.stages.tiling import bin_tiles, plan_tiles, remove_tiles

# the stages that write into the output folder: a run that stops in one of them leaves no tile files, no empty folder
WRITING_STAGES = (
    bin_tiles,
    build_tiles,
    stitch_tiles,
    orient_surface,
    place_spawns,
    evaluate,
    write_meshes,
    write_worlds,
    remove_tiles,
    write_report,
)


def build_world(scan, out, name=None, **options):
    """The whole pipeline; `options`: the fields of record.Options (resolution, water_level, max_gap, clearance,
    edge, visual_edge, visibility, current_speed, seed, quiet, memory_gb, workers, scheduler, retries,
    keep_tiles). Returns the report (dict), also written as <out>/<name>.json. Tiles that fail are listed in the
    report's `failed_tiles` (the world is built from the others)."""
    b = start(scan, out, name, Options(**options))
    survey_scan(b)
    plan_tiles(b)
    with nothing_left_on_failure(b):
        for stage in WRITING_STAGES:
            stage(b)
    return b.report


def start(scan, out, name, options):
    """The build record of a run, its options checked (ScanError names a wrong one)."""
    options.check()
    scan = Path(scan)
    workers = (os.cpu_count() or 1) if options.workers is None else options.workers
    return Build(
        scan=scan,
        out=Path(out),
        name=name or scan.stem,
        options=options,
        progress=Progress(options.quiet),
        started=time.monotonic(),
        workers=workers,
    )


@contextmanager
def nothing_left_on_failure(b):
    """Removes the tile files left by an earlier run; if the body stops (an error, Ctrl-C, SIGTERM), removes this
    run's tile files and the output folder when it made it and it is empty."""
    created = not b.out.exists()
    if b.work.exists():
        shutil.rmtree(b.work)
    try:
        yield
    except BaseException:
        shutil.rmtree(b.work, ignore_errors=True)
        if created and b.out.is_dir() and not any(b.out.iterdir()):
            b.out.rmdir()
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
    ap = argparse.ArgumentParser(prog="python -m unexmin.worlds.from_scan", description=__doc__.split("\n\n")[0])
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
        rep = build_world(args.scan, args.out, args.name, **{f.name: getattr(args, f.name) for f in fields(Options)})
    except ScanError as e:
        print(f"world_from_scan: error: {e}", file=sys.stderr)
        return 2
    print(report(rep))
    return 3 if rep["failed_tiles"] else 0

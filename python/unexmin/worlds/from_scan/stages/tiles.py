"""Stage build_tiles: each tile's surfaces (fine, collision, visual, clipped to its slab) on Dask, or in this
process for a single tile (cluster.run_tiles, tile.py)."""

import resource
import sys

from unexmin.worlds.from_scan.cluster import run_tiles
from unexmin.worlds.from_scan.errors import ScanError
from unexmin.worlds.from_scan.tiles import DRIVER_BYTES


def build_tiles(b):
    """Fills b.results, b.failures (each also printed), b.driver_mb and b.spacing. Raises ScanError when no tile
    could be built; notes a scan sparser than --resolution."""
    o, progress = b.options, b.progress
    options = {
        "resolution": o.resolution,
        "max_gap": o.max_gap,
        "edge": o.edge,
        "visual_edge": o.visual_edge,
        "seed": o.seed,
        # a Dask worker runs one tile on one thread (the tiles are the parallelism); in this process: every core
        "threads": 1 if b.local_workers or o.scheduler else -1,
    }
    per_worker = (o.memory_gb * 1e9 - DRIVER_BYTES) / max(1, b.local_workers)  # [B] each worker's limit
    note = None if progress.quiet else progress.note
    with progress.stage("tiles", "tiles", len(b.layout["tiles"]), "tile") as bar:
        tiles = run_tiles(b.layout, options, b.local_workers, per_worker, o.scheduler, o.retries, bar, note)
    b.results, b.failures = tiles
    b.driver_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # this process, up to the tiles' end
    for f in b.failures:
        print(
            f"world_from_scan: error: {f['tile']} failed after {o.retries + 1} attempts: {f['error']}",
            file=sys.stderr,
        )
    if not b.results:
        first = b.failures[0]["error"] if b.failures else "no tile"
        raise ScanError(f"{b.scan}: no usable surface: no tile could be built ({first})")
    b.spacing = max(r["spacing"] for r in b.results.values())
    if b.spacing > o.resolution:
        progress.note(
            f"the scan's points are {b.spacing:.3g} m apart, sparser than --resolution {o.resolution} m: "
            f"the surface is reconstructed at {b.spacing:.3g} m"
        )
    return b

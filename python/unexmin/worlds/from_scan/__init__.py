"""A surveyed point cloud of a mine to a simulator world (docs/world_from_scan.md):
`python -m unexmin.worlds.from_scan SCAN --out DIR`. build.py: build_world (the stages in order) and the
command line; record.py: the build record the stages pass along; stages/: one module per stage (survey,
tiling, tiles, stitching, spawns, evaluation, files, report). What the stages call: stream.py: reading in
chunks; tiles.py: the survey pass, the tile plan, the tile files; tile.py: one tile's surface (a Dask task;
scan.py: down-sampling, normals and their orientation; surface.py: Poisson, trimming, decimation, hole
closing, spawn points); cluster.py: the tiles on Dask; stitch.py: clipping and zipping the tiles into one
surface; colours.py: the scan's colours onto the visual mesh."""

from unexmin.worlds.from_scan.build import build_world, main
from unexmin.worlds.from_scan.errors import ScanError
from unexmin.worlds.from_scan.scan import orient_towards_void, read_scan, sample_scan, write_xyz
from unexmin.worlds.from_scan.surface import close_holes, distances, raycasting_scene

__all__ = [
    "ScanError",
    "build_world",
    "close_holes",
    "distances",
    "main",
    "orient_towards_void",
    "raycasting_scene",
    "read_scan",
    "sample_scan",
    "write_xyz",
]

"""A surveyed point cloud of a mine to a simulator world (docs/world_from_scan.md):
`python -m unexmin.world_from_scan SCAN --out DIR`. scan.py: reading, down-sampling and orienting the points;
surface.py: reconstruction, trimming, hole closing, spawns; build.py: build_world, the report, the command line."""

from unexmin.world_from_scan.build import build_world, main
from unexmin.world_from_scan.scan import ScanError, orient_towards_void, read_scan, sample_scan, write_xyz
from unexmin.world_from_scan.surface import close_holes, distances, raycasting_scene

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

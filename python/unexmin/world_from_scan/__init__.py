"""A surveyed point cloud of a mine to a simulator world (docs/world_from_scan.md):
`python -m unexmin.world_from_scan SCAN --out DIR`. stream.py: reading in chunks; tiles.py: the survey
pass, the tile plan, the tile files; tile.py: one tile's surface (a Dask task; scan.py: down-sampling,
normals and their orientation; surface.py: Poisson, trimming, decimation); cluster.py: the tiles on
Dask; stitch.py: clipping and zipping the tiles into one surface; build.py: build_world (hole closing,
spawns, evaluation, the world files, the report), the command line."""

from unexmin.world_from_scan.build import build_world, main
from unexmin.world_from_scan.errors import ScanError
from unexmin.world_from_scan.scan import orient_towards_void, read_scan, sample_scan, write_xyz
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

"""A surveyed point cloud of a mine to a simulator world (docs/world_from_scan.md):
`python -m unexmin.world_from_scan SCAN --out DIR`. The stages and the command line are in build.py."""

from unexmin.world_from_scan.build import ScanError, build_world, main, read_scan, sample_scan

__all__ = ["ScanError", "build_world", "main", "read_scan", "sample_scan"]

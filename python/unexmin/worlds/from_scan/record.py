"""The build record that build_world passes through its stages (stages/): what the run was told (Options), where
it writes, the progress it shows, and what each stage leaves for the next. Units: [m], [s], [MB]."""

import sys
import time
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

from unexmin.worlds.from_scan.errors import ScanError
from unexmin.worlds.schema import visibility_levels

VISIBILITY = visibility_levels()


@dataclass
class Options:
    """What build_world is told (the command line's options, docs/world_from_scan.md)."""

    resolution: float = 0.1  # [m] voxel size and Poisson cell
    water_level: float | None = None  # [m] z of the water surface (None: the scan's top)
    max_gap: float = 1.0  # [m] surface farther than this from every scan point is trimmed
    clearance: float = 0.6  # [m] least distance from a spawn point to the walls
    edge: float = 0.3  # [m] triangle edge of the collision mesh
    visual_edge: float = 1.0  # [m] triangle edge of the visual mesh
    visibility: str = "medium"  # the world's water visibility level
    current_speed: float = 0.0  # [m/s] mean water current
    seed: int = 0  # seed of the samplings
    quiet: bool = False  # no progress bars, no notes
    memory_gb: float = 8.0  # [GB] memory of the whole run: sizes the tiles
    workers: int | None = None  # local Dask workers (None: one per core; 0: no Dask, in this process)
    scheduler: str | None = None  # address of a running Dask scheduler (then no local workers)
    retries: int = 1  # attempts after a tile's first failure
    keep_tiles: bool = False  # keep the tile files (OUT/NAME_tiles/)

    def check(self):
        """Raises ScanError naming the option, its value and what it must be."""
        if not self.resolution > 0:
            raise ScanError(f"--resolution must be > 0 [m], got {self.resolution}")
        if not (self.edge > 0 and self.visual_edge > 0):
            raise ScanError(f"--edge and --visual-edge must be > 0 [m], got {self.edge} and {self.visual_edge}")
        if not self.max_gap > self.resolution:
            raise ScanError(f"--max-gap must exceed the resolution {self.resolution} m, got {self.max_gap}")
        if self.visibility not in VISIBILITY:
            raise ScanError(f"--visibility must be none, low, medium or high, got {self.visibility!r}")
        if not self.memory_gb > 0:
            raise ScanError(f"--memory-gb must be > 0 [GB], got {self.memory_gb}")
        if self.workers is not None and self.workers < 0:
            raise ScanError(f"--workers must be >= 0, got {self.workers}")
        if self.retries < 0:
            raise ScanError(f"--retries must be >= 0, got {self.retries}")


class Progress:
    """One progress bar per stage on stderr (tqdm; none when quiet), notes, and each stage's wall time [s]."""

    def __init__(self, quiet):
        self.quiet = quiet
        self.times = {}  # stage key -> [s] wall, in the order the stages ran

    @contextmanager
    def stage(self, key, label, total=1, unit="step"):
        """A bar of `total` `unit`s for the stage `label`, its time kept as times[key] when it ends without error."""
        from tqdm import tqdm

        t0 = time.monotonic()
        bar = tqdm(
            total=total,
            desc=f"{label:<12}",
            unit=unit,
            unit_scale=unit in ("point", "B"),
            disable=self.quiet,
            file=sys.stderr,
            leave=True,
        )
        with bar:
            yield bar
        self.times[key] = round(time.monotonic() - t0, 2)

    def note(self, text):
        if not self.quiet:
            print(f"world_from_scan: note: {text}", file=sys.stderr)


@dataclass
class Build:
    """One run of the pipeline. The stages fill the fields below `started` in the order they run."""

    scan: Path  # the point cloud
    out: Path  # the output folder
    name: str  # world and file name prefix
    options: Options
    progress: Progress
    started: float  # [s] time.monotonic() at the start
    workers: int  # local Dask workers asked for (the option, or one per core)
    # survey: the first pass over the file (tiles.survey) and the file's size (stream.scan_size)
    survey: dict | None = None
    size: tuple = (0, "point")  # (total, unit) of a pass over the file, for the bars
    # tiling: the plan (tiles.plan), then with the tile files (tiles.bin_scan)
    layout: dict | None = None
    budget: int = 0  # down-sampled points a tile may hold
    local_workers: int = 0  # local Dask workers started (0: the tiles in this process, or on --scheduler)
    work: Path | None = None  # the tile files' folder
    # tiles: each tile's surfaces and figures (cluster.run_tiles)
    results: dict = field(default_factory=dict)  # tile index -> the tile's result
    failures: list = field(default_factory=list)  # the tiles that failed: {tile, bounds, error}
    driver_mb: float = 0.0  # [MB] this process's peak up to the tiles' end
    spacing: float = 0.0  # [m] the scan's point spacing (the largest of the tiles')
    # stitching: one closed surface, collision and visual, faces into the void
    seams: list = field(default_factory=list)  # [m] where the tiles were cut, along layout["axis"]
    collision: tuple = ()  # (vertices V x 3 [m], triangles T x 3)
    visual: tuple = ()  # (vertices, triangles)
    zipped: int = 0  # seam loops zipped
    open_loops: int = 0  # seam loops left for the hole closing
    holes: int = 0  # holes closed
    hole_area: float = 0.0  # [m^2]
    folds: int = 0  # folded edges mended after stitching
    closed: bool = False
    volume: float = float("nan")  # [m^3] enclosed water (nan when not closed)
    # spawns
    surface_z: float = 0.0  # [m] the water level
    scene: object = None  # the collision mesh's ray-casting scene (surface.raycasting_scene)
    spawns: list = field(default_factory=list)  # (xyz [m], clearance [m]) per robot
    # evaluation
    probe: object = None  # scan points [m] measured against the collision mesh
    distances: object = None  # [m] their distances to it
    flooded: float | None = None  # [m^3] water below the water level
    # files
    visual_colours: object = None  # RGB per visual vertex (None: the scan has no colours)
    parts: list = field(default_factory=list)  # the meshes by tile: {index, collision, visual, triangles}
    collision_file: str = ""
    visual_file: str = ""
    world_path: Path | None = None
    parts_path: Path | None = None
    report: dict | None = None

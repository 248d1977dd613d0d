"""Stages plan_tiles, bin_tiles and remove_tiles: slabs sized by the memory budget (tiles.plan), the second pass
over the scan that writes each slab's points to a file of its own (tiles.bin_scan), and those files removed at the
end."""

import shutil

from unexmin.worlds.from_scan.tiles import bin_scan, plan, tile_points_budget


def plan_tiles(b):
    """Fills b.local_workers, b.budget and b.layout (axis, seams, overlap, the tiles); notes a slab too large for
    the budget."""
    o = b.options
    b.local_workers = 0 if o.scheduler else b.workers
    b.budget = tile_points_budget(o.memory_gb, max(1, b.local_workers))
    b.layout = plan(b.survey, o.resolution, o.max_gap, b.budget)
    if len(b.layout["tiles"]) == 1 and not o.scheduler:
        b.local_workers = 0  # one tile: built in this process, no cluster to start (its budget holds all the more)
    if not b.layout["fits"]:
        b.progress.note(
            f"a slab of the least width holds more than the {b.budget:,} points a tile may hold in "
            f"--memory-gb {o.memory_gb}: the run may take more memory"
        )
    b.work = b.out / f"{b.name}_tiles"
    return b


def bin_tiles(b):
    """Writes the tile files into b.work; b.layout then names them and their point counts."""
    with b.progress.stage("bin", "tile files", *b.size) as bar:
        b.layout = bin_scan(b.scan, b.survey, b.layout, b.work, progress=bar)
    return b


def remove_tiles(b):
    """Removes the tile files once the world is written, unless --keep-tiles."""
    if not b.options.keep_tiles:
        shutil.rmtree(b.work, ignore_errors=True)
    return b

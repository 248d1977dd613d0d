"""Stage place_spawns: the robots' start points (surface.find_spawns), in the water and clear of the walls."""

import numpy as np

from unexmin.worlds.from_scan.errors import ScanError
from unexmin.worlds.from_scan.surface import find_spawns, raycasting_scene


def place_spawns(b):
    """Fills b.surface_z (the water level [m]: the option, else the scan's top), b.scene (the collision mesh's
    ray-casting scene) and b.spawns. Raises ScanError when no point of the water has --clearance."""
    o = b.options
    b.surface_z = float(b.survey["hi"][2]) if o.water_level is None else float(o.water_level)
    b.scene = raycasting_scene(*b.collision)
    with b.progress.stage("spawns", "spawns") as bar:
        sp = np.concatenate([r["samples"][0] for r in b.results.values()])
        sn = np.concatenate([r["samples"][1] for r in b.results.values()])
        b.spawns = find_spawns(b.scene, sp, sn, b.surface_z, o.clearance, seed=o.seed)
        bar.update(1)
    if not b.spawns:
        raise ScanError(
            f"{b.scan}: no point of the water (below z = {b.surface_z:.2f} m) has {o.clearance} m of "
            "clearance to the walls: no room for a robot"
        )
    return b

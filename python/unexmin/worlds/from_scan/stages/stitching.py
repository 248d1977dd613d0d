"""Stages stitch_tiles and orient_surface: the tiles' surfaces zipped at their seams into one (stitch.py), the holes
left closed (surface.close_holes), folds mended (tile.mended); then the surface checked closed and turned so that
its faces point into the void."""

import math

from unexmin.worlds.from_scan.errors import ScanError
from unexmin.worlds.from_scan.stitch import choose_seams, clip_parts, seam_shifts, stitch
from unexmin.worlds.from_scan.surface import HULL_RADIUS, close_holes, closed_surface
from unexmin.worlds.from_scan.tile import folded_edges, mended


def mend_folds(v, t):
    """(v, t, folds): the stitched surface with any edge that zip strips or caps use the same way twice (folds)
    cut out and closed again (tile.mended); as it was when it has none or when that does not make it manifold."""
    folds = folded_edges(t) if len(t) else 0
    m = mended(v, t) if folds else None
    return (v, t, 0) if m is None else (m[0], m[1], folds)


def stitch_tiles(b):
    """Fills b.seams (each where the two tiles' surfaces cross it in loops that pair up), b.collision and b.visual
    (one surface each), b.zipped, b.open_loops, b.holes, b.hole_area and b.folds. Raises ScanError when nothing of
    the reconstruction is left."""
    o, axis = b.options, b.layout["axis"]
    order = [b.results.get(t["index"]) for t in b.layout["tiles"]]
    with b.progress.stage("stitch", "stitch", 2) as bar:
        collision, tolerance = [r and r["collision"] for r in order], 2.0 * o.edge + o.resolution
        shifts = seam_shifts(b.layout["overlap"], o.resolution)
        b.seams = choose_seams(collision, axis, b.layout["seams"], tolerance, shifts)
        v, t, b.zipped, b.open_loops = stitch(clip_parts(collision, axis, b.seams), axis, b.seams, tolerance)
        if len(t) == 0:
            raise ScanError(f"{b.scan}: no usable surface: nothing of the reconstruction lies within --max-gap")
        v, t, b.holes, b.hole_area, _ = close_holes(v, t)
        v, t, b.folds = mend_folds(v, t)
        b.collision = (v, t)
        bar.update(1)
        visual = clip_parts([r and r["visual"] for r in order], axis, b.seams)
        vv, vt, _, _ = stitch(visual, axis, b.seams, 2.0 * o.visual_edge + o.resolution)
        vv, vt, _, _, _ = close_holes(vv, vt)
        vv, vt, _ = mend_folds(vv, vt)
        b.visual = (vv, vt)
        bar.update(1)
    return b


def orient_surface(b):
    """Fills b.closed and b.volume [m^3]; a closed surface's faces (collision and visual) are turned to point into
    the void (its enclosed volume is then negative). Raises ScanError when it holds no room for one robot."""
    import trimesh

    (v, t), (vv, vt) = b.collision, b.visual
    b.closed = closed_surface(v, t)
    signed = float(trimesh.Trimesh(v, t, process=False).volume) if b.closed else float("nan")
    if b.closed and signed > 0:
        t, vt, signed = t[:, ::-1].copy(), vt[:, ::-1].copy(), -signed
        b.collision, b.visual = (v, t), (vv, vt)
    b.volume = -signed if b.closed else float("nan")
    if b.closed and b.volume < (4 / 3) * math.pi * (HULL_RADIUS + b.options.clearance) ** 3:
        raise ScanError(
            f"{b.scan}: no usable surface: the closed surface holds {b.volume:.3g} m^3 of water, not "
            f"room for one robot (expected walls around a void)"
        )
    return b

"""The colours of a coloured scan on the world's visual mesh (docs/world_from_scan.md, "Colours"): each vertex of
the reconstructed surface takes the RGB of its nearest scan point; the simulator's cameras then see them through a
material of kind vertex_colours (docs/worlds.md). Colours are 8-bit sRGB codes, as scans and PLY files store them."""

from pathlib import Path

import numpy as np


def read_scan_colours(path):
    """(points N x 3 [m] float64, colours N x 3 uint8) of a PLY or PCD scan with RGB, or a LAS/LAZ scan with RGB;
    None when the scan has no colours (or its format carries none: XYZ, PTS, TXT, CSV). Rows with a non-finite
    coordinate are dropped, as read_scan drops them."""
    path = Path(path)
    ext = path.suffix.lower()
    if ext in (".ply", ".pcd"):
        import open3d as o3d

        cloud = o3d.io.read_point_cloud(str(path), format="auto")
        if not cloud.has_colors():
            return None
        points = np.asarray(cloud.points, dtype=np.float64)
        rgb = np.rint(np.clip(np.asarray(cloud.colors), 0.0, 1.0) * 255.0)
    elif ext in (".las", ".laz"):
        import laspy

        las = laspy.read(str(path))
        if "red" not in las.point_format.dimension_names:
            return None
        points = np.column_stack([np.asarray(las.x), np.asarray(las.y), np.asarray(las.z)]).astype(np.float64)
        rgb = np.column_stack([np.asarray(las.red), np.asarray(las.green), np.asarray(las.blue)]).astype(np.float64)
        if rgb.max(initial=0) > 255:  # LAS stores 16-bit colour
            rgb = np.rint(rgb / 257.0)
    else:
        return None
    ok = np.isfinite(points).all(axis=1)
    return points[ok], rgb[ok].astype(np.uint8)


def vertex_colours(vertices, points, colours):
    """Colour (M x 3 uint8) of each vertex (M x 3 [m]): that of its nearest point of `points` (N x 3 [m]), whose
    colours are `colours` (N x 3 uint8)."""
    from scipy.spatial import cKDTree

    _, nearest = cKDTree(points).query(np.asarray(vertices, dtype=np.float64), k=1, workers=-1)
    return np.asarray(colours, dtype=np.uint8)[nearest]


def streamed_vertex_colours(path, vertices, chunk=None):
    """Colour (M x 3 uint8) of each vertex (M x 3 [m]) from the scan `path` read in chunks of `chunk` points
    (stream.iter_chunks; default stream.CHUNK), so that memory holds one chunk and the vertices, whatever the scan's
    size: each vertex keeps the colour of the nearest point over all chunks. None when the scan carries no colours."""
    from scipy.spatial import cKDTree

    from unexmin.worlds.from_scan.stream import CHUNK, iter_chunks

    vertices = np.asarray(vertices, dtype=np.float64)
    best = np.full(len(vertices), np.inf)
    colours = np.zeros((len(vertices), 3), dtype=np.uint8)
    for part in iter_chunks(path, chunk or CHUNK):
        if part.rgb is None:
            return None
        ok = np.isfinite(part.points).all(axis=1)
        if not ok.any():
            continue
        d, nearest = cKDTree(part.points[ok]).query(vertices, k=1, workers=-1)
        closer = d < best
        best[closer] = d[closer]
        colours[closer] = np.asarray(part.rgb, dtype=np.uint8)[ok][nearest[closer]]
    return colours if np.isfinite(best).all() else None

"""The scan side of a world from a scan: reading point clouds (PLY, PCD, XYZ/TXT, LAS/LAZ), synthetic scans of
a mesh for tests, voxel down-sampling, normals and their orientation towards the void. Units: [m]."""

import math

import numpy as np

from unexmin.worlds.from_scan.errors import ScanError
from unexmin.worlds.meshes import sample_surface

MIN_POINTS = 200  # fewer points after down-sampling: no surface to speak of


REACH = 20.0  # [m] orientation rays' length


SAMPLE_AREA = 1.0  # [m^2] of wall per orientation sample


CONE = ((0.0, 1), (math.radians(30.0), 6), (math.radians(60.0), 6))  # orientation rays: (angle from n, count)


# ---------------------------------------------------------------------------------------------- read
def read_scan(path):
    """(points N x 3 [m] float64, normals N x 3 or None) of a whole cloud (stream.py's formats), for small
    scans and tests: the tool itself streams (tiles.py). Rows with a non-finite coordinate are dropped."""
    from unexmin.worlds.from_scan.stream import iter_chunks

    points, normals, complete = [], [], True
    for c in iter_chunks(path):
        ok = np.isfinite(c.points).all(axis=1)
        points.append(c.points[ok])
        if c.normals is None:
            complete = False
        else:
            normals.append(c.normals[ok])
    points = np.concatenate(points) if points else np.zeros((0, 3))
    normals = np.concatenate(normals) if complete and normals else None
    if normals is not None:
        lengths = np.linalg.norm(normals, axis=1)
        if not (np.isfinite(lengths) & (lengths > 0.5)).all():
            normals = None  # partial or broken normals: estimate them all
    if len(points) == 0:
        raise ScanError(f"{path}: no finite point (expected a point cloud of the mine's walls)")
    return points, normals


def write_xyz(path, points, normals=None):
    """A scan as text: x y z [nx ny nz] per line [m]."""
    cols = points if normals is None else np.hstack([points, normals])
    np.savetxt(path, cols, fmt="%.4f")


def sample_scan(tris, spacing, noise, holes=0, hole_radius=0.5, seed=0):
    """A synthetic scan of triangles (T x 3 x 3 [m]), for tests and benchmarks: area-uniform points, one
    per spacing^2 [m] on average, Gaussian noise of sd `noise` [m] on each coordinate, and `holes` missing
    patches (every point within `hole_radius` [m] of a random scan point removed). Seeded: N x 3 [m]."""
    from scipy.spatial import cKDTree

    points, _ = sample_surface(tris, spacing, seed)
    rng = np.random.default_rng(seed + 1)
    points = points + rng.normal(0.0, noise, points.shape)
    if holes:
        centres = points[rng.choice(len(points), holes, replace=False)]
        gone = cKDTree(centres).query(points, distance_upper_bound=hole_radius, workers=-1)[0]
        points = points[~np.isfinite(gone)]
    return points


# ---------------------------------------------------------------------------- down-sampling, normals
def downsample(points, normals, resolution):
    """One point per occupied voxel of `resolution` [m]: the centroid of its points (and their mean normal)."""
    import open3d as o3d

    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points))
    if normals is not None:
        cloud.normals = o3d.utility.Vector3dVector(normals)
    cloud = cloud.voxel_down_sample(resolution)
    p = np.asarray(cloud.points)
    n = np.asarray(cloud.normals) if normals is not None else None
    if n is not None:
        n = n / np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-12)
    return p, n


def check_usable(points, resolution, source):
    """Stop with one clear line when the down-sampled cloud cannot describe a surface."""
    if len(points) < MIN_POINTS:
        raise ScanError(
            f"{source}: no usable surface: {len(points)} points after down-sampling to "
            f"{resolution} m (expected at least {MIN_POINTS}: a denser scan or a finer --resolution)"
        )
    spread = np.sqrt(np.maximum(np.linalg.eigvalsh(np.cov(points.T)), 0.0))  # ascending [m]
    if spread[1] < 5 * resolution:
        raise ScanError(
            f"{source}: no usable surface: the points lie along a line (spread {spread[2]:.3g} x "
            f"{spread[1]:.3g} x {spread[0]:.3g} m; expected walls around a void)"
        )


def estimate_normals(points, resolution):
    """Unit normals of the local tangent planes (PCA of the neighbours within 3 resolutions), unoriented."""
    import open3d as o3d

    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points))
    cloud.estimate_normals(o3d.geometry.KDTreeSearchParamHybrid(radius=3.0 * resolution, max_nn=30))
    return np.asarray(cloud.normals).copy()


def orientation_cell(extent, resolution):
    """[m] voxel of the orientation grid: 4 resolutions, coarser when the grid would pass ~120M cells."""
    return max(4.0 * resolution, float(np.prod(extent + 1e-9) / 1.2e8) ** (1 / 3))


def orientation_steps(extent, cell, reach=REACH):
    """Distances [m] along each orientation ray: from 3 cells (off the wall) to `reach`, every 0.8 cell."""
    return np.arange(3.0 * cell, min(reach, float(np.linalg.norm(extent))) + 0.8 * cell, 0.8 * cell)


def _cone(normals):
    """Directions (S x K x 3) in a cone around each normal: the normal, rings at 30 and 60 degrees."""
    n = normals
    helper = np.where(np.abs(n[:, :1]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]])
    u = np.cross(n, helper)
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    v = np.cross(n, u)
    dirs = []
    for angle, count in CONE:
        for k in range(count):
            phi = 2 * math.pi * k / count + angle  # rings staggered
            dirs.append(math.cos(angle) * n + math.sin(angle) * (math.cos(phi) * u + math.sin(phi) * v))
    return np.stack(dirs, axis=1)


def orientation_samples(count, spacing):
    """How many points cast orientation rays: one per SAMPLE_AREA of wall (the area is about count x
    spacing^2), so that a point's nearest samples lie on its own wall, not across the tunnel (whose
    votes point the other way); between 5 000 and 300 000."""
    return int(np.clip(count * spacing**2 / SAMPLE_AREA, 5000, 300000))


def orient_towards_void(points, normals, resolution, reach=REACH, samples=5000, seed=0, progress=None, threads=-1):
    """Turn each normal towards the void (the water): from a wall, the rays into the void meet the
    other walls, those into the rock meet nothing (or farther walls). A seeded sample of points casts
    a cone of rays both ways through a voxel grid of the scan; the side with more hits within `reach`
    [m] is the void. Every point then takes the side of its 8 nearest samples (weighted by how clear
    their vote was); `threads`: workers of that query. Returns the oriented normals and the fraction of
    samples that could decide."""
    from scipy import ndimage
    from scipy.spatial import cKDTree

    lo, hi = points.min(axis=0), points.max(axis=0)
    cell = orientation_cell(hi - lo, resolution)
    pad = 2
    shape = np.ceil((hi - lo) / cell).astype(int) + 1 + 2 * pad
    occ = np.zeros(shape, dtype=bool)
    ijk = np.floor((points - lo) / cell).astype(int) + pad
    occ[ijk[:, 0], ijk[:, 1], ijk[:, 2]] = True
    occ = ndimage.binary_dilation(occ)  # no ray slips diagonally between two wall voxels
    rng = np.random.default_rng(seed)
    pick = rng.choice(len(points), size=min(samples, len(points)), replace=False)
    p, n = points[pick], normals[pick]
    dirs = _cone(n)  # S x K x 3
    ts = orientation_steps(hi - lo, cell, reach)
    hits = np.zeros((2, len(p), dirs.shape[1]), dtype=bool)
    for s, sign in enumerate((1.0, -1.0)):
        for t in ts:
            q = np.floor((p[:, None, :] + sign * t * dirs - lo) / cell).astype(int) + pad
            inside = ((q >= 0) & (q < shape)).all(axis=2)
            q = np.where(inside[..., None], q, 0)
            hits[s] |= inside & occ[q[..., 0], q[..., 1], q[..., 2]]
            if progress is not None:
                progress.update(1)
    vote = hits[0].sum(axis=1).astype(float) - hits[1].sum(axis=1)
    oriented = n * np.sign(vote)[:, None]
    weight = np.abs(vote)
    tree = cKDTree(p)
    k = min(8, len(p))
    _, nb = tree.query(points, k=k, workers=threads)
    nb = nb.reshape(len(points), k)
    agree = np.einsum("ij,ikj->ik", normals, oriented[nb]) * weight[nb]
    side = np.where(agree.sum(axis=1) < 0.0, -1.0, 1.0)
    return normals * side[:, None], float(np.mean(weight > 0))


def point_spacing(points, seed=0, k=8, tree=None):
    """[m] typical distance between neighbouring scan points, sqrt(1 / areal density): the density from
    the radius r of the k nearest neighbours of up to 20 000 seeded samples, k / (pi r^2) (median).
    `tree`: a cKDTree of `points`, built when not given."""
    from scipy.spatial import cKDTree

    rng = np.random.default_rng(seed)
    probe = points[rng.choice(len(points), size=min(20000, len(points)), replace=False)]
    tree = cKDTree(points) if tree is None else tree
    r = tree.query(probe, k=k + 1, workers=1)[0][:, -1]
    return float(np.median(r) * math.sqrt(math.pi / k))

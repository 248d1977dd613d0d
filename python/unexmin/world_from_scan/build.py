"""A surveyed point cloud of a mine (laser, sonar, the robots' own maps) to a simulator world in one
command (docs/world_from_scan.md): what the thesis did by hand for Kaatiala (5.2) with MeshLab.

    python -m unexmin.world_from_scan SCAN --out DIR [--name NAME] [--resolution 0.1] [--water-level Z]

Stages: read (PLY, PCD, XYZ/TXT, LAS/LAZ), voxel down-sampling to the resolution, normals (estimated
when the scan has none) turned to face the void, screened Poisson reconstruction (Open3D), trimming of
the surface the scan does not support, hole closing (the water volume becomes a closed surface), a
lighter visual mesh, spawn points in the water with clearance, the world file and a report.
Units: [m]; frame: the scan's own, taken as the world frame (ENU, z up).
"""

import argparse
import json
import math
import resource
import sys
import time
from pathlib import Path

import numpy as np

from unexmin.worlds.meshes import sample_surface, write_ply

HULL_RADIUS = 0.3  # [m] the UX-1's sphere (docs/robot_description.md)
MIN_POINTS = 200  # fewer points after down-sampling: no surface to speak of
REACH = 20.0  # [m] orientation rays' length
SAMPLE_AREA = 1.0  # [m^2] of wall per orientation sample
CONE = ((0.0, 1), (math.radians(30.0), 6), (math.radians(60.0), 6))  # orientation rays: (angle from n, count)


class ScanError(ValueError):
    """The scan cannot make a world; the message names the input and what was expected."""


# ---------------------------------------------------------------------------------------------- read
def read_scan(path):
    """(points N x 3 [m] float64, normals N x 3 or None) of a PLY, PCD, XYZ/XYZN/PTS, TXT/CSV (x y z
    [nx ny nz] columns) or LAS/LAZ file; rows with a non-finite coordinate are dropped."""
    path = Path(path)
    if not path.is_file():
        raise ScanError(f"{path}: no such file (expected a point cloud: .ply .pcd .xyz .xyzn .pts .txt .csv .las .laz)")
    ext = path.suffix.lower()
    normals = None
    if ext in (".ply", ".pcd", ".xyz", ".xyzn", ".pts"):
        import open3d as o3d

        cloud = o3d.io.read_point_cloud(str(path), format="auto")
        points = np.asarray(cloud.points, dtype=np.float64)
        if cloud.has_normals():
            normals = np.asarray(cloud.normals, dtype=np.float64)
    elif ext in (".txt", ".csv", ".asc"):
        try:
            table = np.loadtxt(path, delimiter="," if ext == ".csv" else None, ndmin=2, comments=("#", "//"))
        except ValueError as e:
            raise ScanError(f"{path}: expected rows of numbers x y z [nx ny nz] ({e})") from None
        if table.shape[1] not in (3, 4, 6, 7) and table.size:
            raise ScanError(f"{path}: expected 3 (x y z) or 6 (x y z nx ny nz) columns, got {table.shape[1]}")
        points = table[:, :3]
        normals = table[:, 3:6] if table.shape[1] >= 6 else None
    elif ext in (".las", ".laz"):
        import laspy

        las = laspy.read(str(path))
        points = np.column_stack([np.asarray(las.x), np.asarray(las.y), np.asarray(las.z)]).astype(np.float64)
    else:
        raise ScanError(
            f"{path}: unknown point cloud extension '{ext}' (expected .ply .pcd .xyz .xyzn .pts .txt " ".csv .las .laz)"
        )
    ok = np.isfinite(points).all(axis=1)
    if normals is not None:
        lengths = np.linalg.norm(normals, axis=1)
        if not (np.isfinite(lengths) & (lengths > 0.5))[ok].all():
            normals = None  # partial or broken normals: estimate them all
    points = points[ok]
    normals = normals[ok] if normals is not None else None
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


# -------------------------------------------------------------------------------------- the surface
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


def orient_towards_void(points, normals, resolution, reach=REACH, samples=5000, seed=0, progress=None):
    """Turn each normal towards the void (the water): from a wall, the rays into the void meet the
    other walls, those into the rock meet nothing (or farther walls). A seeded sample of points casts
    a cone of rays both ways through a voxel grid of the scan; the side with more hits within `reach`
    [m] is the void. Every point then takes the side of its 8 nearest samples (weighted by how clear
    their vote was). Returns the oriented normals and the fraction of samples that could decide."""
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
    _, nb = tree.query(points, k=k, workers=-1)
    nb = nb.reshape(len(points), k)
    agree = np.einsum("ij,ikj->ik", normals, oriented[nb]) * weight[nb]
    side = np.where(agree.sum(axis=1) < 0.0, -1.0, 1.0)
    return normals * side[:, None], float(np.mean(weight > 0))


def point_spacing(points, seed=0, k=8):
    """[m] typical distance between neighbouring scan points, sqrt(1 / areal density): the density from
    the radius r of the k nearest neighbours of up to 20 000 seeded samples, k / (pi r^2) (median)."""
    from scipy.spatial import cKDTree

    rng = np.random.default_rng(seed)
    probe = points[rng.choice(len(points), size=min(20000, len(points)), replace=False)]
    r = cKDTree(points).query(probe, k=k + 1, workers=-1)[0][:, -1]
    return float(np.median(r) * math.sqrt(math.pi / k))


def poisson_depth(points, resolution):
    """Octree depth whose finest cell is about `resolution` over the scan's largest extent (x 1.1)."""
    extent = float((points.max(axis=0) - points.min(axis=0)).max()) * 1.1
    return int(np.clip(math.ceil(math.log2(max(extent / resolution, 2.0))), 5, 13))


def reconstruct(points, normals, depth):
    """Screened Poisson (Open3D, Kazhdan & Hoppe 2013) of the void as the solid: `normals` face the void
    and are reversed, so the indicator's "inside" is the small void and its "outside" the rock that
    fills the rest of the octree (a small solid in a large empty box, Poisson's usual case). Returns vertices V x 3 and
    triangles T x 3 facing out of the void (build_world turns them)."""
    import open3d as o3d

    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points))
    cloud.normals = o3d.utility.Vector3dVector(-normals)
    mesh, _ = o3d.geometry.TriangleMesh.create_from_point_cloud_poisson(
        cloud, depth=depth, scale=1.1, linear_fit=False, n_threads=-1
    )
    return np.asarray(mesh.vertices).copy(), np.asarray(mesh.triangles).astype(np.int64)


def trim_unsupported(v, t, points, max_gap):
    """Drop the triangles with a vertex farther than `max_gap` [m] from every scan point (an empty ball
    of that radius: no scan density there, the surface would be invented), then the small pieces
    (under 1 % of the triangles) that remain apart. Returns (v, t) compacted."""
    import trimesh
    from scipy.spatial import cKDTree

    d, _ = cKDTree(points).query(v, distance_upper_bound=max_gap, workers=-1)
    keep = np.isfinite(d)[t].all(axis=1)
    t = t[keep]
    if len(t) == 0:
        return v[:0], t
    labels = trimesh.graph.connected_component_labels(
        trimesh.Trimesh(v, t, process=False).face_adjacency, node_count=len(t)
    )
    sizes = np.bincount(labels)
    t = t[sizes[labels] >= 0.01 * len(t)]
    used = np.unique(t)
    remap = np.full(len(v), -1)
    remap[used] = np.arange(len(used))
    return v[used], remap[t]


def boundary_loops(t):
    """Closed loops of directed boundary edges (edges with no opposite half-edge), as vertex lists."""
    e = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    n = int(t.max()) + 1
    key = e[:, 0] * n + e[:, 1]
    border = e[~np.isin(key, e[:, 1] * n + e[:, 0])]
    nxt = {}
    for a, b in border:
        nxt.setdefault(int(a), []).append(int(b))
    loops = []
    while nxt:
        start = next(iter(nxt))
        loop, a = [start], start
        while True:
            b = nxt[a].pop()
            if not nxt[a]:
                del nxt[a]
            if b == start or b not in nxt:
                break
            loop.append(b)
            a = b
        if len(loop) >= 3:
            loops.append(loop)
    return loops


def close_holes(v, t):
    """Close every boundary loop with a fan from its centroid, wound against the loop's edges so the
    surface stays consistently oriented. Returns (v, t, number of holes, area closed [m^2], the cap
    triangles' mask)."""
    loops = boundary_loops(t) if len(t) else []
    new_v, new_t = [v], [t]
    nv, area = len(v), 0.0
    for loop in loops:
        ring = np.asarray(loop)
        centre = v[ring].mean(axis=0)
        a, b = ring, np.roll(ring, -1)
        fan = np.column_stack([b, a, np.full(len(ring), nv)])
        area += 0.5 * float(np.linalg.norm(np.cross(v[a] - centre, v[b] - centre), axis=1).sum())
        new_v.append(centre[None])
        new_t.append(fan)
        nv += 1
    cap = np.zeros(sum(len(x) for x in new_t), dtype=bool)
    cap[len(t) :] = True
    return np.concatenate(new_v), np.concatenate(new_t), len(loops), area, cap


def simplify(v, t, edge):
    """Quadric-error decimation (Open3D, Garland & Heckbert) to triangles of about `edge` [m] (equilateral
    ones of that edge tiling the same area); the mesh as it is when it has fewer already."""
    import open3d as o3d

    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    area = 0.5 * float(np.linalg.norm(np.cross(b - a, c - a), axis=1).sum())
    target = max(1000, int(area / (edge**2 * math.sqrt(3) / 4)))
    if target >= len(t):
        return v, t
    mesh = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(v), o3d.utility.Vector3iVector(t.astype(np.int32)))
    mesh = mesh.simplify_quadric_decimation(target_number_of_triangles=target)
    mesh.remove_degenerate_triangles()
    mesh.remove_unreferenced_vertices()
    return np.asarray(mesh.vertices).copy(), np.asarray(mesh.triangles).astype(np.int64)


def raycasting_scene(v, t):
    import open3d as o3d

    scene = o3d.t.geometry.RaycastingScene()
    scene.add_triangles(o3d.core.Tensor(v.astype(np.float32)), o3d.core.Tensor(t.astype(np.uint32)))
    return scene


def distances(scene, points, chunk=1_000_000):
    """Unsigned distance [m] from each point to the scene's triangles."""
    import open3d as o3d

    out = [
        scene.compute_distance(o3d.core.Tensor(points[i : i + chunk].astype(np.float32))).numpy()
        for i in range(0, len(points), chunk)
    ]
    return np.concatenate(out) if out else np.zeros(0)


def inside(scene, points):
    """True where the point is enclosed by the (closed) surface: in the void, the water."""
    import open3d as o3d

    return scene.compute_occupancy(o3d.core.Tensor(points.astype(np.float32)), nsamples=3).numpy() > 0.5


def find_spawns(scene, points, normals, surface_z, clearance, count=3, spacing=1.5, seed=0):
    """Up to `count` robot positions [m] in the water: inside the closed surface, at least `clearance`
    [m] from every wall, the hull (R 0.3 m) at least 0.4 m under the surface, `spacing` [m] apart and
    within 15 m of the first (the one with the most room). Candidates are scan points moved 0.5..6 m
    along their normal into the void. Returns a list of (xyz, clearance)."""
    rng = np.random.default_rng(seed)
    pick = rng.choice(len(points), size=min(4000, len(points)), replace=False)
    cand = np.concatenate([points[pick] + d * normals[pick] for d in (0.5, 1.0, 2.0, 3.0, 6.0)])
    cand = cand[cand[:, 2] <= surface_z - HULL_RADIUS - 0.4]
    if len(cand) == 0:
        return []
    room = distances(scene, cand)
    ok = (room >= clearance) & inside(scene, cand)
    cand, room = cand[ok], room[ok]
    order = np.argsort(-room, kind="stable")
    chosen = []
    for i in order:
        c = cand[i]
        if chosen and (
            np.linalg.norm(c - chosen[0][0]) > 15.0 or min(np.linalg.norm(c - s) for s, _ in chosen) < spacing
        ):
            continue
        chosen.append((c, float(room[i])))
        if len(chosen) == count:
            break
    return chosen


def flooded_volume(v, t, surface_z):
    """[m^3] of the void (enclosed by faces pointing into it) below z = surface_z (manifold3d), or None
    when the surface is not a closed 2-manifold."""
    import manifold3d

    solid = manifold3d.Manifold(
        manifold3d.Mesh(vert_properties=v.astype(np.float32), tri_verts=t[:, ::-1].astype(np.uint32))
    )
    if solid.status() != manifold3d.Error.NoError:
        return None
    return float(solid.trim_by_plane((0.0, 0.0, -1.0), -surface_z).volume())


# ------------------------------------------------------------------------------------------ outputs
def world_yaml(name, surface_z, visibility, current_speed, collision_file, visual_file, spawns, source):
    lines = [
        f"# World made from the scan {source} by python -m unexmin.world_from_scan (docs/world_from_scan.md).",
        "# Schema: docs/worlds.md. Units: SI; world frame = the scan's frame (ENU, z up).",
        f"name: {name}",
        "gravity: 9.81                                 # [m/s^2]",
        f"water: {{density: 1000.0, surface_z: {surface_z:.4f}}}   # [kg/m^3]; [m] the water level",
        "atmospheric_pressure: 101325.0                # [Pa] at the free surface",
        f"visibility: {{level: {visibility}, colour: [0.32, 0.28, 0.18]}}   # suspended sediment: brownish murk",
        "ray_caster: embree",
        "current:                                      # bounded Gauss-Markov per variable",
        f"  speed: {{mean: {current_speed}, min: 0.0, max: {max(0.1, 2 * current_speed)}, noise: "
        f"{0.1 * current_speed:.4g}, mu: 0.02}}   # [m/s]",
        "  horizontal_angle: {mean: 0.0, min: -3.1416, max: 3.1416, noise: 0.0, mu: 0.01}   # [rad]",
        "  vertical_angle: {mean: 0.0, min: -0.15, max: 0.15, noise: 0.0, mu: 0.05}        # [rad]",
        "meshes:                                       # closed surface, faces towards the water",
        f"  - {{name: {name}, file: {collision_file}, scale: [1, 1, 1], xyz: [0, 0, 0], rpy: [0, 0, 0], "
        "collision: true, visual: false}",
        f"  - {{name: {name}_visual, file: {visual_file}, scale: [1, 1, 1], xyz: [0, 0, 0], rpy: [0, 0, 0], "
        "collision: false, visual: true}",
        "robots:                                       # checked: in the water, clearance [m] to the walls",
    ]
    for k, (xyz, room) in enumerate(spawns):
        lines.append(
            f"  - {{name: UX_{k + 1}, description: ux1.urdf.xacro, xyz: [{xyz[0]:.3f}, {xyz[1]:.3f}, "
            f"{xyz[2]:.3f}], rpy: [0, 0, 0]}}   # clearance {room:.2f} m"
        )
    return "\n".join(lines) + "\n"


def scanned_area(mesh, cap, points, reach):
    """([m^2] of the surface whose triangle centroids lie within `reach` [m] of a scan point: the walls
    the scan saw; [m^2] of the rest of the Poisson surface: gaps it bridged), hole caps left out."""
    from scipy.spatial import cKDTree

    d, _ = cKDTree(points).query(mesh.triangles_center, distance_upper_bound=reach, workers=-1)
    area = mesh.area_faces
    seen = np.isfinite(d)
    return float(area[seen & ~cap].sum()), float(area[~seen & ~cap].sum())


def closed_surface(v, t):
    """True when the triangles make a closed, consistently wound surface (trimesh, vertices as given)."""
    import trimesh

    mesh = trimesh.Trimesh(v, t, process=False)
    return bool(mesh.is_watertight and mesh.is_winding_consistent)


def build_world(
    scan,
    out,
    name=None,
    resolution=0.1,
    water_level=None,
    max_gap=1.0,
    clearance=0.6,
    edge=0.3,
    visual_edge=1.0,
    visibility="medium",
    current_speed=0.0,
    seed=0,
    quiet=False,
):
    """The whole pipeline; returns the report (dict), also written as <out>/<name>.json."""
    from tqdm import tqdm

    if not resolution > 0:
        raise ScanError(f"--resolution must be > 0 [m], got {resolution}")
    if not (edge > 0 and visual_edge > 0):
        raise ScanError(f"--edge and --visual-edge must be > 0 [m], got {edge} and {visual_edge}")
    if not max_gap > resolution:
        raise ScanError(f"--max-gap must exceed the resolution {resolution} m, got {max_gap}")
    if visibility not in ("none", "low", "medium", "high"):
        raise ScanError(f"--visibility must be none, low, medium or high, got {visibility!r}")
    scan = Path(scan)
    name = name or scan.stem
    out = Path(out)
    times = {}
    t_all = time.monotonic()

    def stage(label, total=1, unit="step"):
        return tqdm(total=total, desc=f"{label:<12}", unit=unit, disable=quiet, file=sys.stderr, leave=True)

    def timed(key, label, fn, *args, total=1, unit="step", **kw):
        t0 = time.monotonic()
        with stage(label, total, unit) as bar:
            result = fn(*args, **kw, **({"progress": bar} if total > 1 else {}))
            bar.update(bar.total - bar.n)
        times[key] = round(time.monotonic() - t0, 2)
        return result

    raw, raw_normals = timed("read", "read", read_scan, scan)
    points, normals = timed("downsample", "downsample", downsample, raw, raw_normals, resolution)
    check_usable(points, resolution, scan)
    if normals is None:
        normals = timed("normals", "normals", estimate_normals, points, resolution)
    extent = points.max(axis=0) - points.min(axis=0)
    steps = 2 * len(orientation_steps(extent, orientation_cell(extent, resolution)))
    spacing = point_spacing(points, seed)
    normals, decided = timed(
        "orient",
        "orient",
        orient_towards_void,
        points,
        normals,
        resolution,
        seed=seed,
        samples=orientation_samples(len(points), spacing),
        total=steps,
        unit="ray step",
    )
    if spacing > resolution and not quiet:
        print(
            f"world_from_scan: note: the scan's points are {spacing:.3g} m apart, sparser than --resolution "
            f"{resolution} m: the surface is reconstructed at {spacing:.3g} m",
            file=sys.stderr,
        )
    depth = poisson_depth(points, max(resolution, spacing))
    v, t = timed("poisson", "poisson", reconstruct, points, normals, depth)
    v, t = timed("trim", "trim", trim_unsupported, v, t, points, max_gap)
    if len(t) == 0:
        raise ScanError(
            f"{scan}: no usable surface: nothing of the reconstruction lies within --max-gap "
            f"{max_gap} m of the scan"
        )
    v, t, holes, hole_area, cap = timed("holes", "close holes", close_holes, v, t)
    import trimesh

    mesh = trimesh.Trimesh(v, t, process=False)
    wall_area, bridged_area = scanned_area(mesh, cap, points, 3.0 * resolution)
    fine_triangles = len(t)
    closed = closed_surface(v, t)
    signed = float(mesh.volume) if closed else float("nan")
    if closed and signed > 0:  # faces must point into the void: the enclosed volume is then negative
        t, signed = t[:, ::-1].copy(), -signed
    cv, ct = timed("decimate", "decimate", simplify, v, t, edge)
    if closed and not closed_surface(cv, ct):  # the decimation opened the surface: keep the fine one
        cv, ct = v, t
    v, t = cv, ct
    volume = -float(trimesh.Trimesh(v, t, process=False).volume) if closed else float("nan")
    if closed and volume < (4 / 3) * math.pi * (HULL_RADIUS + clearance) ** 3:
        raise ScanError(
            f"{scan}: no usable surface: the closed surface holds {volume:.3g} m^3 of water, not "
            f"room for one robot (expected walls around a void)"
        )
    surface_z = float(points[:, 2].max()) if water_level is None else float(water_level)
    scene = raycasting_scene(v, t)
    t0 = time.monotonic()
    with stage("spawns") as bar:
        spawns = find_spawns(scene, points, normals, surface_z, clearance, seed=seed)
        bar.update(1)
    times["spawns"] = round(time.monotonic() - t0, 2)
    if not spawns:
        raise ScanError(
            f"{scan}: no point of the water (below z = {surface_z:.2f} m) has {clearance} m of "
            "clearance to the walls: no room for a robot"
        )
    vv, vt = timed("visual", "visual mesh", simplify, v, t, visual_edge)
    t0 = time.monotonic()
    with stage("evaluate") as bar:
        rng = np.random.default_rng(seed)
        probe = raw if len(raw) <= 1_000_000 else raw[rng.choice(len(raw), 1_000_000, replace=False)]
        d = distances(scene, probe)
        flooded = flooded_volume(v, t, surface_z) if closed else None
        bar.update(1)
    times["evaluate"] = round(time.monotonic() - t0, 2)
    out.mkdir(parents=True, exist_ok=True)
    collision_file, visual_file = f"{name}_collision.ply", f"{name}_visual.ply"
    comment = f"unexmin world_from_scan {scan.name} resolution {resolution}"
    write_ply(out / collision_file, v, t, comment + " collision", inward=False)
    write_ply(out / visual_file, vv, vt, comment + " visual", inward=False)
    world_path = out / f"{name}.world"
    world_path.write_text(
        world_yaml(name, surface_z, visibility, current_speed, collision_file, visual_file, spawns, scan.name)
    )
    rep = {
        "scan": str(scan),
        "points_read": int(len(raw)),
        "points_used": int(len(points)),
        "normals": "read" if raw_normals is not None else "estimated",
        "orientation_samples_decided": round(decided, 3),
        "resolution": resolution,
        "point_spacing": round(spacing, 4),
        "poisson_depth": depth,
        "max_gap": max_gap,
        "poisson_triangles": int(fine_triangles),
        "collision": {"file": collision_file, "triangles": int(len(t)), "vertices": int(len(v)), "edge": edge},
        "visual": {"file": visual_file, "triangles": int(len(vt)), "vertices": int(len(vv)), "edge": visual_edge},
        "world": world_path.name,
        "closed": closed,
        "volume": round(volume, 3) if closed else None,
        "flooded_volume": round(flooded, 3) if flooded is not None else None,
        "water_level": surface_z,
        "wall_area": round(wall_area, 3),
        "bridged_area": round(bridged_area, 3),
        "holes_closed": holes,
        "holes_area": round(hole_area, 3),
        "scan_to_mesh": {
            "mean": round(float(d.mean()), 4),
            "p95": round(float(np.percentile(d, 95)), 4),
            "max": round(float(d.max()), 4),
            "points": int(len(d)),
        },
        "bbox_min": [round(x, 3) for x in v.min(axis=0)],
        "bbox_max": [round(x, 3) for x in v.max(axis=0)],
        "spawns": [{"xyz": [round(float(x), 3) for x in s], "clearance": round(c, 3)} for s, c in spawns],
        "seconds": times,
        "total_seconds": round(time.monotonic() - t_all, 2),
        "peak_rss_mb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1),
    }
    (out / f"{name}.json").write_text(json.dumps(rep, indent=1) + "\n")
    return rep


def report(rep):
    s = rep["scan_to_mesh"]
    vol = f"{rep['volume']:,.1f}" if rep["volume"] is not None else "n/a (not closed)"
    flooded = f"{rep['flooded_volume']:,.1f}" if rep["flooded_volume"] is not None else "n/a"
    return "\n".join(
        [
            f"world '{rep['world']}' from {rep['scan']}: {rep['points_read']:,} points read, {rep['points_used']:,} at "
            f"{rep['resolution']} m, normals {rep['normals']}, Poisson depth {rep['poisson_depth']}, "
            f"{rep['total_seconds']} s, peak {rep['peak_rss_mb']:.0f} MB",
            f"  collision: {rep['collision']['triangles']:,} triangles "
            f"(edge {rep['collision']['edge']} m, from Poisson's "
            f"{rep['poisson_triangles']:,}), {rep['collision']['file']}",
            f"  visual:    {rep['visual']['triangles']:,} triangles, {rep['visual']['file']}",
            f"  closed: {rep['closed']}, void volume {vol} m^3, flooded (below z = {rep['water_level']:.2f}) "
            f"{flooded} m^3, "
            f"wall area {rep['wall_area']:,.1f} m^2 (and {rep['bridged_area']:,.1f} m^2 bridged over gaps)",
            f"  holes closed: {rep['holes_closed']} ({rep['holes_area']:,.1f} m^2)",
            f"  scan to mesh: mean {s['mean'] * 100:.1f} cm, 95th percentile {s['p95'] * 100:.1f} cm, "
            f"max {s['max']:.2f} m",
            "  spawns: " + ", ".join(f"{sp['xyz']} (clearance {sp['clearance']:.2f} m)" for sp in rep["spawns"]),
        ]
    )


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m unexmin.world_from_scan", description=__doc__.split("\n\n")[0])
    ap.add_argument("scan", help="point cloud: .ply .pcd .xyz .xyzn .pts .txt .csv .las .laz [m]")
    ap.add_argument("--out", required=True, help="output folder (created)")
    ap.add_argument("--name", help="world and file name prefix (default: the scan's file name)")
    ap.add_argument("--resolution", type=float, default=0.1, help="[m] voxel size and Poisson cell (default 0.1)")
    ap.add_argument("--water-level", type=float, help="[m] z of the water surface (default: the scan's top)")
    ap.add_argument(
        "--max-gap",
        type=float,
        default=1.0,
        help="[m] surface farther than this from every scan point is trimmed (default 1.0)",
    )
    ap.add_argument(
        "--clearance",
        type=float,
        default=0.6,
        help="[m] least distance from a spawn point to the walls (default 0.6: hull 0.3 + 0.3)",
    )
    ap.add_argument("--visibility", default="medium", help="none|low|medium|high (default medium)")
    ap.add_argument("--current-speed", type=float, default=0.0, help="[m/s] mean water current (default 0)")
    ap.add_argument(
        "--edge",
        type=float,
        default=0.3,
        help="[m] triangle edge of the collision mesh, decimated from Poisson's (default 0.3)",
    )
    ap.add_argument("--visual-edge", type=float, default=1.0, help="[m] triangle edge of the visual mesh (default 1.0)")
    ap.add_argument("--seed", type=int, default=0, help="seed of the samplings (default 0)")
    ap.add_argument("--quiet", action="store_true", help="no progress bars")
    args = ap.parse_args(argv)
    try:
        rep = build_world(
            args.scan,
            args.out,
            args.name,
            args.resolution,
            args.water_level,
            args.max_gap,
            args.clearance,
            args.edge,
            args.visual_edge,
            args.visibility,
            args.current_speed,
            args.seed,
            args.quiet,
        )
    except ScanError as e:
        print(f"world_from_scan: error: {e}", file=sys.stderr)
        return 2
    print(report(rep))
    return 0

"""The surface side of a world from a scan: screened Poisson reconstruction, trimming what the scan does not
support, closing holes, simplification, ray casting against the result, spawn points and volumes. Units: [m]."""

import math
import os

import numpy as np

HULL_RADIUS = 0.3  # [m] the UX-1's sphere (docs/robot_description.md)


def poisson_octree(points, resolution):
    """(depth, scale) of the Poisson octree whose finest cell is `resolution` [m]: the fewest levels (5..13) whose
    cube holds the points' largest extent x 1.1, and the cube then grown to 2^depth resolutions (`scale`: its edge
    over that extent, Open3D's scale), so that a tile's cell is neither finer than the data asked for (up to twice,
    four times the triangles) nor coarser; past 13 levels the cube is the extent x 1.1 and the cell coarser."""
    extent = max(float((points.max(axis=0) - points.min(axis=0)).max()), 1e-9)
    depth = int(np.clip(math.ceil(math.log2(max(1.1 * extent / resolution, 2.0))), 5, 13))
    return depth, max(1.1, 2.0**depth * resolution / extent)


def reconstruct(points, normals, depth, threads=-1, scale=1.1):
    """Screened Poisson (Open3D, Kazhdan & Hoppe 2013) of the void as the solid: `normals` face the void
    and are reversed, so the indicator's "inside" is the small void and its "outside" the rock that
    fills the rest of the octree (a small solid in a large empty box, Poisson's usual case). `threads`: Open3D's
    n_threads (-1: every core); `scale`: the octree's cube over the points' largest extent (poisson_octree).
    Returns vertices V x 3 and triangles T x 3 facing out of the void (build_world turns them)."""
    import open3d as o3d

    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points))
    cloud.normals = o3d.utility.Vector3dVector(-normals)
    mesh, _ = o3d.geometry.TriangleMesh.create_from_point_cloud_poisson(
        cloud, depth=depth, scale=scale, linear_fit=False, n_threads=threads
    )
    return np.asarray(mesh.vertices).copy(), np.asarray(mesh.triangles).astype(np.int64)


def trim_unsupported(v, t, points, max_gap, tree=None, threads=-1):
    """Drop the triangles with a vertex farther than `max_gap` [m] from every scan point (an empty ball
    of that radius: no scan density there, the surface would be invented), then the small pieces
    (under 1 % of the triangles) that remain apart. `tree`: a cKDTree of `points`, built when not given;
    `threads`: its query's workers. Returns (v, t) compacted."""
    import trimesh
    from scipy.spatial import cKDTree

    tree = cKDTree(points) if tree is None else tree
    d, _ = tree.query(v, distance_upper_bound=max_gap, workers=threads)
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


def _simple_cycles(walk):
    """A closed walk of boundary edges (vertex list, back to its first) cut into simple cycles at the vertices
    it passes twice: two holes that touch at one vertex (a pinch) are two loops, each visiting it once."""
    cycles, path, at = [], [], {}
    for x in walk + walk[:1]:
        if x in at:
            i = at[x]
            cycles.append(path[i:])
            for y in path[i + 1 :]:
                del at[y]
            path = path[: i + 1]
        else:
            at[x] = len(path)
            path.append(x)
    return cycles


def boundary_loops(t):
    """Closed loops of directed boundary edges (edges with no opposite half-edge), as vertex lists; each loop
    passes a vertex once (walks through a pinch vertex are cut there into simple loops)."""
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
        loops += [c for c in _simple_cycles(loop) if len(c) >= 3]
    return loops


def close_holes(v, t, loops=None, centres=None):
    """Close every boundary loop (or only `loops`, vertex lists) with a fan from its centroid (or from
    `centres`, one point [m] per loop), wound against the loop's edges so the surface stays consistently
    oriented. Returns (v, t, number of holes, area closed [m^2], the cap triangles' mask)."""
    if loops is None:
        loops = boundary_loops(t) if len(t) else []
    new_v, new_t = [v], [t]
    nv, area = len(v), 0.0
    for k, loop in enumerate(loops):
        ring = np.asarray(loop)
        centre = v[ring].mean(axis=0) if centres is None else np.asarray(centres[k], dtype=float)
        a, b = ring, np.roll(ring, -1)
        fan = np.column_stack([b, a, np.full(len(ring), nv)])
        area += 0.5 * float(np.linalg.norm(np.cross(v[a] - centre, v[b] - centre), axis=1).sum())
        new_v.append(centre[None])
        new_t.append(fan)
        nv += 1
    cap = np.zeros(sum(len(x) for x in new_t), dtype=bool)
    cap[len(t) :] = True
    return np.concatenate(new_v), np.concatenate(new_t), len(loops), area, cap


def decimation_target(v, t, edge):
    """Triangles of about `edge` [m] (equilateral ones of that edge tiling the surface's area), at least 1000."""
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    area = 0.5 * float(np.linalg.norm(np.cross(b - a, c - a), axis=1).sum())
    return max(1000, int(area / (edge**2 * math.sqrt(3) / 4)))


# fast-simplification's C++ keeps the mesh it decimated in global vectors that are cleared, never freed: a process
# that has decimated a 2M-triangle surface holds ~0.6 GB more from then on, and more after each larger one. A child
# process of its own gives every byte back when it exits (a Dask worker stays at one tile's peak).
_FAST_CHILD = """
import io, sys
import numpy as np
from numpy.lib import format as npy
import fast_simplification
i, o = io.BytesIO(sys.stdin.buffer.read()), io.BytesIO()
v, t, target = npy.read_array(i), npy.read_array(i), int(npy.read_array(i))
del i
dv, dt = fast_simplification.simplify(v, t, target_count=target)
npy.write_array(o, np.ascontiguousarray(dv, dtype=np.float64))
npy.write_array(o, np.ascontiguousarray(dt, dtype=np.int32))
hwm = [l for l in open("/proc/self/status") if l.startswith("VmHWM:")]
npy.write_array(o, np.array(int(hwm[0].split()[1]) * 1024 if hwm else 0))
sys.stdout.buffer.write(o.getbuffer())
"""


# [bytes] the most this process and a decimating child of it held at once (rss_with_children())
_peak_with_children = 0


def _rss():
    """[bytes] this process's resident memory now."""
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def rss_with_children():
    """[bytes] the peak resident memory of this process, or of it and a decimating child at once when that was
    more (the child's own peak, VmHWM, on top of this process's memory while it waited)."""
    import resource

    return max(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024, _peak_with_children)


def fast_simplified(v, t, target):
    """fast_simplification.simplify(v, t, target_count=target) in a child process of its own (the library's
    buffers die with it): (vertices float64, triangles int32). A RuntimeError carries the child's error."""
    global _peak_with_children
    import io
    import subprocess
    import sys

    from numpy.lib import format as npy

    payload = io.BytesIO()
    npy.write_array(payload, np.ascontiguousarray(v, dtype=np.float64))
    npy.write_array(payload, np.ascontiguousarray(t, dtype=np.int32))
    npy.write_array(payload, np.array(int(target)))
    waiting = _rss()
    done = subprocess.run(
        [sys.executable, "-c", _FAST_CHILD], input=payload.getbuffer(), capture_output=True, check=False
    )
    if done.returncode != 0:
        error = done.stderr.decode(errors="replace").strip().splitlines()
        raise RuntimeError(
            f"fast-simplification of {len(t)} triangles to {target} failed (exit {done.returncode}): "
            f"{error[-1] if error else 'no message'}"
        )
    out = io.BytesIO(done.stdout)
    dv, dt, child_peak = npy.read_array(out), npy.read_array(out), int(npy.read_array(out))
    _peak_with_children = max(_peak_with_children, waiting + child_peak)
    return dv, dt


def simplify(v, t, edge, method="fast"):
    """Quadric-error decimation (Garland & Heckbert) to decimation_target(); the mesh as it is when it has
    fewer triangles already. `method`: "fast" (fast-simplification, Fast-Quadric-Mesh-Simplification: a
    threshold on the quadric error instead of a sorted queue of collapses, about ten times faster) or
    "open3d" (Open3D's simplify_quadric_decimation, the exact order of collapses)."""
    target = decimation_target(v, t, edge)
    if target >= len(t):
        return v, t
    if method == "fast":
        dv, dt = fast_simplified(v, t, target)
        keep = (dt[:, 0] != dt[:, 1]) & (dt[:, 1] != dt[:, 2]) & (dt[:, 2] != dt[:, 0])
        dt = dt[keep].astype(np.int64)
        used = np.unique(dt)
        remap = np.full(len(dv), -1, dtype=np.int64)
        remap[used] = np.arange(len(used))
        return np.asarray(dv, dtype=np.float64)[used], remap[dt]
    import open3d as o3d

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

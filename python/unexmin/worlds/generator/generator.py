"""Procedural flooded mine at the scale of Kaatiala (thesis 6.3): levels of galleries joined by
shafts and ramps, chambers, dead ends and rough walls, with the water surface in the entry shaft.

    python -m unexmin.worlds.generator --out worlds/meshes/mine            # full size, seed 7
    python -m unexmin.worlds.generator --preset small --seed 3 --out /tmp/m

Every tunnel is a capsule (a swept superellipse with rounded ends) per polyline segment, tessellated
at a target edge length and displaced along its radial direction by a seeded gradient noise of
several octaves evaluated at world positions (so overlapping tunnels agree). The displaced surface of
one capsule is a height field over the capsule, hence never self-intersecting, and manifold3d's
boolean union of all of them is a closed, oriented 2-manifold: the boundary of the mine's void.
Written with its triangles facing into the void (towards the water), like the tank's walls.

Outputs (docs/mine_world.md): <name>_collision.ply (>= 1M triangles for the full preset),
<name>_visual.ply (the same surface, coarser and without the finest noise octaves) and <name>.json
(seed, generator version, triangle counts, bounding box, volumes, SHA-256 of each file).
Units: [m]; frame: the world frame (ENU, z up), water surface at z = surface_z.
"""

import argparse
import hashlib
import json
import math
import sys
import time
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path

import numpy as np

from unexmin.worlds.meshes import write_ply

GENERATOR_VERSION = 2


@dataclass(frozen=True)
class Preset:
    """Size and resolution of a generated mine; lengths [m]."""

    name: str
    length: float  # extent along x, entry shaft wall to the farthest drift end
    half_width: float  # the footprint is |y| <= half_width
    levels: int  # number of gallery levels
    first_level_z: float  # z of level 0's centreline
    level_spacing: float  # vertical distance between levels
    collar_z: float  # top of the entry shaft (ground level, above the water)
    surface_z: float  # water surface (only the entry shaft reaches above it)
    shaft_half: float  # entry shaft half size (rounded square)
    min_drift_length: float  # shortest main drift of a level below level 0
    ramp_gradient: float  # drop per run of the ramps between levels (1:7 = 0.143)
    chambers: int  # stopes, besides the pump station by the shaft
    raises: int  # internal shafts joining several levels
    edge: float  # collision tessellation edge length
    visual_edge: float  # visual tessellation edge length
    min_triangles: int  # the collision mesh must have at least this many
    octaves: tuple = ((18.0, 0.30), (6.0, 0.16), (2.0, 0.07), (0.9, 0.035))  # (wavelength, amplitude)


# Kaatiala (thesis 6.3): max depth 353 m, max length 620 m, max width 30 m.
FULL = Preset(
    "full",
    length=620.0,
    half_width=15.0,
    levels=9,
    first_level_z=-22.0,
    level_spacing=41.0,
    collar_z=6.0,
    surface_z=0.0,
    shaft_half=3.0,
    min_drift_length=360.0,
    ramp_gradient=1 / 7,
    chambers=5,
    raises=2,
    edge=0.47,
    visual_edge=1.3,
    min_triangles=1_000_000,
)

PRESETS = {
    "full": FULL,
    # Same construction, two levels, coarse: for tests (a few seconds).
    "small": replace(
        FULL,
        name="small",
        length=120.0,
        levels=2,
        level_spacing=12.0,
        min_drift_length=110.0,
        chambers=1,
        raises=1,
        edge=0.6,
        visual_edge=1.2,
        min_triangles=20_000,
    ),
}


@dataclass
class Tunnel:
    """A polyline of capsules. Cross-section: superellipse of half width `a` (horizontal, or along the
    first perpendicular for a vertical axis) and half height `b`, exponent `p_floor` below the axis and
    `p_roof` above (2 = ellipse, larger = squarer); ends: rounded, extent `c` along the axis."""

    kind: str
    points: np.ndarray
    a: float
    b: float
    c: float = None
    p_floor: float = 2.6
    p_roof: float = 2.0

    def __post_init__(self):
        self.points = np.asarray(self.points, dtype=float)
        if self.c is None:
            self.c = 0.5 * (self.a + self.b)


@dataclass
class Layout:
    tunnels: list
    spawns: list  # [(x, y, z)], in the entry shaft, under water
    shaft_xy: tuple
    notes: dict = field(default_factory=dict)


class GradientNoise:
    """Seeded 3-D gradient (Perlin) noise, vectorised; values in about [-1, 1], zero on the lattice."""

    GRADS = np.array(
        [
            [1, 1, 0],
            [-1, 1, 0],
            [1, -1, 0],
            [-1, -1, 0],
            [1, 0, 1],
            [-1, 0, 1],
            [1, 0, -1],
            [-1, 0, -1],
            [0, 1, 1],
            [0, -1, 1],
            [0, 1, -1],
            [0, -1, -1],
        ],
        dtype=float,
    )

    def __init__(self, rng):
        p = rng.permutation(256)
        self.perm = np.concatenate([p, p])

    def __call__(self, pts):
        cell = np.floor(pts)
        f = pts - cell
        i = cell.astype(np.int64) & 255
        u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0)
        perm = self.perm
        out = np.zeros(len(pts))
        for dx in (0, 1):
            px = perm[i[:, 0] + dx]
            wx = u[:, 0] if dx else 1.0 - u[:, 0]
            for dy in (0, 1):
                pxy = perm[px + i[:, 1] + dy]
                wxy = wx * (u[:, 1] if dy else 1.0 - u[:, 1])
                for dz in (0, 1):
                    g = self.GRADS[perm[pxy + i[:, 2] + dz] % 12]
                    dot = g[:, 0] * (f[:, 0] - dx) + g[:, 1] * (f[:, 1] - dy) + g[:, 2] * (f[:, 2] - dz)
                    out += wxy * (u[:, 2] if dz else 1.0 - u[:, 2]) * dot
        return out


class RoughWalls:
    """Sum of noise octaves [(wavelength [m], amplitude [m])]: wall displacement [m] at world points."""

    def __init__(self, octaves, seed):
        rng = np.random.default_rng([seed, 1])
        self.octaves = [(w, amp, GradientNoise(rng), rng.uniform(0, 256, 3)) for w, amp in octaves]

    def max_amplitude(self, min_wavelength=0.0):
        return sum(amp for w, amp, _, _ in self.octaves if w >= min_wavelength)

    def __call__(self, pts, min_wavelength=0.0):
        out = np.zeros(len(pts))
        for w, amp, noise, offset in self.octaves:
            if w >= min_wavelength:
                out += amp * noise(pts / w + offset)
        return out


# ---------------------------------------------------------------------------------------------
# layout: the mine's skeleton, drawn from the seed
# ---------------------------------------------------------------------------------------------
def _drift_y(rng, xs, limit, step_sd=2.5):
    """A wandering centreline across the footprint: bounded random walk in y."""
    y = np.zeros(len(xs))
    for k in range(1, len(xs)):
        y[k] = np.clip(y[k - 1] + rng.normal(0.0, step_sd), -limit, limit)
    return y


def point_on(poly, x):
    """Point of a drift polyline (monotonic in x) at abscissa x (linear interpolation)."""
    return np.array([x, np.interp(x, poly[:, 0], poly[:, 1]), np.interp(x, poly[:, 0], poly[:, 2])])


def make_layout(preset, seed):
    """Skeleton of the mine: entry shaft, level drifts with crosscuts, ramps, raises, chambers."""
    P = preset
    rng = np.random.default_rng([seed, 0])
    amp = sum(a for _, a in P.octaves)
    sx, sy = P.shaft_half + amp, 0.0  # the entry shaft's wall touches x = 0
    x_far = P.length - 2.2 - amp  # farthest drift end (cap extent about 2.2 m)
    y_lim = P.half_width - 2.3 - amp - 3.7  # drift centreline bound: room for crosscuts
    tunnels = []
    level_z = [P.first_level_z - k * P.level_spacing for k in range(P.levels)]
    sump_z = level_z[-1] - 2.0
    tunnels.append(
        Tunnel(
            "shaft",
            [(sx, sy, P.collar_z - P.shaft_half), (sx, sy, sump_z)],
            a=P.shaft_half,
            b=P.shaft_half,
            c=P.shaft_half,
            p_floor=2.6,
            p_roof=2.6,
        )
    )
    drifts = []
    for k, z in enumerate(level_z):
        end = x_far if k == 0 else rng.uniform(max(P.min_drift_length, 0.55 * x_far), x_far)
        xs = np.concatenate([[sx], np.arange(sx + 12.0, end, 22.0), [end]])
        xs[1:-1] += rng.uniform(-4.0, 4.0, len(xs) - 2)
        ys = _drift_y(rng, xs, y_lim)
        ys[0] = sy
        zs = z + 0.004 * (xs - sx) + rng.normal(0.0, 0.25, len(xs))  # drains towards the shaft
        zs[0] = z
        poly = np.column_stack([xs, ys, zs])
        drifts.append(poly)
        tunnels.append(Tunnel("gallery", poly, a=rng.uniform(1.7, 2.3), b=rng.uniform(1.7, 2.1)))
        # Crosscuts: short dead-end side galleries across the footprint.
        x = sx + rng.uniform(20.0, 45.0)
        while x < end - 10.0:
            p0 = point_on(poly, x)
            side = rng.choice([-1.0, 1.0])
            y_end = side * rng.uniform(8.0, P.half_width - 1.8 - amp - 1.5)
            p1 = np.array([x + rng.uniform(-5.0, 5.0), y_end, p0[2] + rng.normal(0.0, 0.4)])
            if abs(p1[1] - p0[1]) > 4.0:
                tunnels.append(Tunnel("crosscut", [p0, p1], a=rng.uniform(1.5, 1.9), b=rng.uniform(1.6, 1.9)))
            x += rng.uniform(35.0, 90.0)
    # Ramps (declines) between consecutive levels, zigzagging along x, off to the side of the drifts.
    run = P.level_spacing / P.ramp_gradient
    for k in range(P.levels - 1):
        upper, lower = drifts[k], drifts[k + 1]
        lo, hi = sx + 12.0, min(upper[-1, 0], lower[-1, 0]) - 6.0
        if hi - lo < run:
            raise ValueError(
                f"preset '{P.name}': levels {k} and {k + 1} overlap over {hi - lo:.0f} m, "
                f"a ramp at gradient {P.ramp_gradient:.3f} needs {run:.0f} m"
            )
        x0 = rng.uniform(lo, hi - run) if k % 2 == 0 else rng.uniform(lo + run, hi)
        x1 = x0 + run if k % 2 == 0 else x0 - run
        a, b = point_on(upper, x0), point_on(lower, x1)
        y_r = (1.0 if k % 2 == 0 else -1.0) * min(y_lim, 9.0)
        n = max(2, int(run // 25.0))
        mid = [(x0 + (x1 - x0) * t, y_r, a[2] + (b[2] - a[2]) * t) for t in np.linspace(0.06, 0.94, n)]
        tunnels.append(Tunnel("ramp", [a, *mid, b], a=2.2, b=2.0))
    # Raises: internal shafts through consecutive levels, following the drifts where they are.
    for _ in range(P.raises):
        top = int(rng.integers(0, max(1, P.levels - 2)))
        bottom = min(P.levels - 1, top + int(rng.integers(1, 4)))
        reach = min(d[-1, 0] for d in drifts[top : bottom + 1]) - 8.0
        x = rng.uniform(max(sx + 30.0, reach - 150.0), reach)
        pts = [point_on(d, x + rng.normal(0.0, 1.5)) for d in drifts[top : bottom + 1]]
        tunnels.append(Tunnel("raise", pts, a=1.6, b=1.6, p_floor=2.4, p_roof=2.4))
    # Chambers: a pump station beside the shaft on level 0, and stopes along the drifts.
    z0 = level_z[0]
    tunnels.append(Tunnel("chamber", [(sx + 8.0, -4.0, z0 + 0.8), (sx + 16.0, -4.0, z0 + 0.8)], a=3.5, b=3.0))
    for _ in range(P.chambers):
        k = int(rng.integers(0, P.levels))
        d = drifts[k]
        length = rng.uniform(14.0, 28.0)
        x = rng.uniform(sx + 40.0, d[-1, 0] - length - 5.0)
        half_w = rng.uniform(4.0, 5.5)
        y = float(np.clip(point_on(d, x)[1], -(P.half_width - half_w - amp - 0.5), P.half_width - half_w - amp - 0.5))
        half_h = rng.uniform(4.0, 7.0)
        zc = point_on(d, x)[2] + half_h - 2.0  # floor near the drift's floor
        tunnels.append(
            Tunnel("chamber", [(x, y, zc), (x + length, y, zc + rng.normal(0.0, 0.5))], a=half_w, b=half_h, c=half_w)
        )
    # Spawn points: three robots in the entry shaft, 2.5 m under water, 1 m from its axis.
    spawn_z = P.surface_z - 2.5
    spawns = [
        (round(sx + math.cos(t), 3), round(sy + math.sin(t), 3), spawn_z) for t in np.radians([180.0, 300.0, 60.0])
    ]
    return Layout(tunnels, spawns, (sx, sy), {"levels_z": level_z, "sump_z": sump_z})


# ---------------------------------------------------------------------------------------------
# tessellation and union
# ---------------------------------------------------------------------------------------------
def _frame(axis):
    """Orthonormal frame (e1 = axis, e2 horizontal when possible, e3 = e1 x e2) as columns."""
    e1 = axis / np.linalg.norm(axis)
    ref = np.array([0.0, 0.0, 1.0]) if abs(e1[2]) < 0.95 else np.array([0.0, -1.0, 0.0])
    e2 = np.cross(ref, e1)
    e2 /= np.linalg.norm(e2)
    return np.column_stack([e1, e2, np.cross(e1, e2)])


def capsule(A, B, tunnel, edge, walls, min_wavelength):
    """Closed, outward-wound triangle mesh of one rough capsule from A to B: (vertices, triangles)."""
    A, B = np.asarray(A, float), np.asarray(B, float)
    length = float(np.linalg.norm(B - A))
    R = _frame(B - A)
    a, b, c = tunnel.a, tunnel.b, tunnel.c
    n_theta = max(8, 4 * math.ceil(math.pi * (a + b) / edge / 4))
    n_len = max(1, math.ceil(length / edge))
    n_cap = max(2, math.ceil(0.5 * math.pi * max(a, b, c) / edge))
    caps = np.linspace(0.0, 0.5 * math.pi, n_cap + 1)[1:-1]  # latitudes strictly inside
    ring_t = np.concatenate([np.zeros(n_cap - 1), np.linspace(0.0, length, n_len + 1), np.full(n_cap - 1, length)])
    ring_phi = np.concatenate([caps[::-1], np.zeros(n_len + 1), caps])
    ring_s = np.concatenate([-np.ones(n_cap - 1), np.zeros(n_len + 1), np.ones(n_cap - 1)])
    theta = 2.0 * math.pi * np.arange(n_theta) / n_theta
    shape = (len(ring_t), n_theta)
    T, PHI, S = (np.broadcast_to(r[:, None], shape) for r in (ring_t, ring_phi, ring_s))
    ct, st = np.cos(theta), np.sin(theta)
    p = np.where(st < 0.0, tunnel.p_floor, tunnel.p_roof)
    r_theta = (np.abs(ct / a) ** p + np.abs(st / b) ** p) ** (-1.0 / p)  # superellipse radius
    dirs = np.stack([S * np.sin(PHI), np.cos(PHI) * ct, np.cos(PHI) * st], axis=-1).reshape(-1, 3)
    L = 1.0 / np.sqrt((np.sin(PHI) / c) ** 2 + (np.cos(PHI) / r_theta) ** 2).reshape(-1)
    centres = np.zeros((len(L), 3))
    centres[:, 0] = T.reshape(-1)
    # the two poles
    dirs = np.vstack([[-1.0, 0.0, 0.0], dirs, [1.0, 0.0, 0.0]])
    L = np.concatenate([[c], L, [c]])
    centres = np.vstack([[0.0, 0.0, 0.0], centres, [length, 0.0, 0.0]])
    base = A + (centres + dirs * L[:, None]) @ R.T
    disp = walls(base, min_wavelength)
    verts = A + (centres + dirs * np.maximum(L + disp, 0.3 * L)[:, None]) @ R.T
    # triangles: pole fans and quads between consecutive rings (outward with theta from e2 to e3)
    m = len(ring_t)
    k = np.arange(n_theta)
    k1 = (k + 1) % n_theta
    ring = 1 + np.arange(m)[:, None] * n_theta
    r0, r1 = (ring[:-1] + k).reshape(-1), (ring[:-1] + k1).reshape(-1)
    q0, q1 = (ring[1:] + k).reshape(-1), (ring[1:] + k1).reshape(-1)
    last = len(verts) - 1
    tris = np.concatenate(
        [
            np.column_stack([np.zeros(n_theta, int), ring[0] + k1, ring[0] + k]),
            np.column_stack([r0, r1, q1]),
            np.column_stack([r0, q1, q0]),
            np.column_stack([ring[-1] + k, ring[-1] + k1, np.full(n_theta, last)]),
        ]
    )
    return verts, tris


def build_solid(layout, edge, walls, min_wavelength, progress=None):
    """Union of every capsule of the layout: a manifold3d.Manifold of the void."""
    import manifold3d as mf

    parts = []
    for tunnel in layout.tunnels:
        for A, B in zip(tunnel.points[:-1], tunnel.points[1:]):
            v, t = capsule(A, B, tunnel, edge, walls, min_wavelength)
            part = mf.Manifold(
                mf.Mesh(
                    vert_properties=np.ascontiguousarray(v, np.float32), tri_verts=np.ascontiguousarray(t, np.uint32)
                )
            )
            if part.status() != mf.Error.NoError or not part.volume() > 0.0:
                raise RuntimeError(
                    f"{tunnel.kind} capsule {A.round(2)}->{B.round(2)}: not a closed outward "
                    f"manifold ({part.status()}, volume {part.volume():.3f} m^3)"
                )
            parts.append(part)
        if progress is not None:
            progress.update(1)
    solid = mf.Manifold.batch_boolean(parts, mf.OpType.Add)
    if solid.status() != mf.Error.NoError:
        raise RuntimeError(f"union of {len(parts)} capsules failed: {solid.status()}")
    return solid


def canonical_mesh(solid):
    """(vertices float32 N x 3, triangles N x 3) of a Manifold, in an order independent of how it was
    computed (vertices sorted by x, y, z; each triangle rotated to start at its smallest index; triangles
    sorted), so the same surface always gives the same bytes."""
    mesh = solid.to_mesh()
    v = np.asarray(mesh.vert_properties)[:, :3].astype(np.float32)
    t = np.asarray(mesh.tri_verts).astype(np.int64)
    order = np.lexsort((v[:, 2], v[:, 1], v[:, 0]))
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    v, t = v[order], rank[t]
    shift = np.argmin(t, axis=1)
    rows = np.arange(len(t))[:, None]
    t = t[rows, (shift[:, None] + np.arange(3)) % 3]
    t = t[np.lexsort((t[:, 2], t[:, 1], t[:, 0]))]
    return v, t


def separate_pinches(v, t, step=1e-3):
    """Where two sheets of the union touch at a point, manifold3d keeps one vertex per sheet at the
    same position. Move each such copy `step` [m] towards the mean of its own 1-ring, so that no two
    vertices share a position and the mesh is closed even when vertices are merged by position."""
    _, inverse, counts = np.unique(v, axis=0, return_inverse=True, return_counts=True)
    shared = np.nonzero(counts[inverse.reshape(-1)] > 1)[0]
    v = v.copy()
    for i in shared:
        ring = np.unique(t[(t == i).any(axis=1)])
        d = v[ring[ring != i]].astype(np.float64).mean(axis=0) - v[i]
        v[i] += (step * d / np.linalg.norm(d)).astype(np.float32)
    return v, len(shared)


def closed_by_position(v, t):
    """True when no two vertices share a position and every edge is used exactly twice, once in each
    direction (closed, consistently wound 2-manifold, whatever a loader merges)."""
    if len(np.unique(v, axis=0)) != len(v):
        return False
    e = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    n = int(t.max()) + 1
    directed = np.unique(e[:, 0] * n + e[:, 1])
    undirected, counts = np.unique(np.sort(e, axis=1) @ np.array([n, 1]), return_counts=True)
    return len(directed) == len(e) and bool((counts == 2).all())


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def surface_stats(solid, surface_z):
    bb = solid.bounding_box()
    below = solid.trim_by_plane((0.0, 0.0, -1.0), -surface_z)
    return {
        "triangles": solid.num_tri(),
        "vertices": solid.num_vert(),
        "genus": solid.genus(),
        "bbox_min": [round(x, 4) for x in bb[:3]],
        "bbox_max": [round(x, 4) for x in bb[3:]],
        "volume": round(solid.volume(), 3),
        "flooded_volume": round(below.volume(), 3),
        "area": round(solid.surface_area(), 3),
    }


def manifest_path(out, name):
    return Path(out) / f"{name}.json"


def is_current(out, name, seed, preset):
    """True when <out>/<name>.json says these files came from this seed, preset and generator
    version and both files are there with the recorded SHA-256."""
    path = manifest_path(out, name)
    try:
        man = json.loads(path.read_text())
        if (man["generator_version"], man["seed"], man["preset"]["name"]) != (GENERATOR_VERSION, seed, preset.name):
            return False
        if man["preset"] != json.loads(json.dumps(asdict(preset))):
            return False
        return all(sha256(Path(out) / m["file"]) == m["sha256"] for m in (man["collision"], man["visual"]))
    except (OSError, KeyError, ValueError, TypeError):
        return False


def generate(out, seed=7, preset="full", name="mine", quiet=False):
    """Generate the mine into folder `out`; returns the manifest (dict), also written as <name>.json."""
    from tqdm import tqdm

    P = PRESETS[preset] if isinstance(preset, str) else preset
    if not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"seed must be a non-negative integer, got {seed!r}")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.monotonic()
    layout = make_layout(P, int(seed))
    walls = RoughWalls(P.octaves, int(seed))
    bar = tqdm(
        total=2 * len(layout.tunnels),
        desc=f"mine '{P.name}' seed {seed}",
        unit="tunnel",
        disable=quiet,
        file=sys.stderr,
    )
    collision = build_solid(layout, P.edge, walls, 0.0, bar)
    visual = build_solid(layout, P.visual_edge, walls, 3.0 * P.visual_edge, bar)
    bar.close()
    stats = surface_stats(collision, P.surface_z)
    if stats["triangles"] < P.min_triangles:
        raise RuntimeError(
            f"preset '{P.name}': collision mesh has {stats['triangles']} triangles, fewer than "
            f"{P.min_triangles}: lower its edge ({P.edge} m)"
        )
    tops = [t.points[:, 2].max() + t.b for t in layout.tunnels if t.kind != "shaft"]
    if max(tops) + walls.max_amplitude() >= P.surface_z:
        raise RuntimeError(f"a tunnel reaches z = {max(tops):.1f} m, above the water surface {P.surface_z} m")
    man = {
        "generator_version": GENERATOR_VERSION,
        "seed": int(seed),
        "preset": asdict(P),
        "surface_z": P.surface_z,
        "shaft_xy": [round(v, 4) for v in layout.shaft_xy],
        "spawns": [list(s) for s in layout.spawns],
        "levels_z": layout.notes["levels_z"],
        "tunnels": {k: sum(t.kind == k for t in layout.tunnels) for k in sorted({t.kind for t in layout.tunnels})},
        "wall_noise_max": round(walls.max_amplitude(), 4),
    }
    from unexmin.worlds.generator.material import material  # the walls' rock for the world file, from the same seed

    man["material"] = material(int(seed), P.name)
    (out / ".gitignore").write_text("# generated by python -m unexmin.worlds.generator (docs/mine_world.md)\n*\n")
    for key, solid, extra in (("collision", collision, stats), ("visual", visual, None)):
        v, t = canonical_mesh(solid)
        v, pinches = separate_pinches(v, t)
        if not closed_by_position(v, t):
            raise RuntimeError(f"{key} mesh is not a closed, consistently wound surface")
        path = out / f"{name}_{key}.ply"
        write_ply(path, v, t, f"unexmin mine_generator v{GENERATOR_VERSION} preset {P.name} seed {seed} {key}")
        man[key] = dict(
            extra or surface_stats(solid, P.surface_z),
            file=path.name,
            sha256=sha256(path),
            bytes=path.stat().st_size,
            edge=P.edge if key == "collision" else P.visual_edge,
            pinches_separated=pinches,
            closed=True,
        )
    man["seconds"] = round(time.monotonic() - t0, 1)
    manifest_path(out, name).write_text(json.dumps(man, indent=1) + "\n")
    return man


def report(man):
    c, v = man["collision"], man["visual"]
    size = np.subtract(c["bbox_max"], c["bbox_min"])
    return "\n".join(
        [
            f"mine '{man['preset']['name']}' seed {man['seed']} (generator v{man['generator_version']}), "
            f"{man['seconds']} s",
            f"  collision: {c['triangles']:,} triangles, {c['bytes'] / 1e6:.1f} MB, {c['file']}",
            f"  visual:    {v['triangles']:,} triangles, {v['bytes'] / 1e6:.1f} MB, {v['file']}",
            f"  bounding box: min {c['bbox_min']} max {c['bbox_max']} m "
            f"(size {size[0]:.1f} x {size[1]:.1f} x {size[2]:.1f} m)",
            f"  void volume {c['volume']:,.0f} m^3, "
            f"flooded (below z = {man['surface_z']}) {c['flooded_volume']:,.0f} m^3, "
            f"wall area {c['area']:,.0f} m^2, genus {c['genus']}",
            f"  tunnels: {man['tunnels']}",
        ]
    )


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m unexmin.worlds.generator", description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, help="output folder (created)")
    ap.add_argument("--seed", type=int, default=7, help="random seed (default 7, the shipped mine.world)")
    ap.add_argument("--preset", choices=sorted(PRESETS), default="full")
    ap.add_argument("--name", default="mine", help="file name prefix (default mine)")
    ap.add_argument("--force", action="store_true", help="regenerate even when the outputs are current")
    ap.add_argument("--quiet", action="store_true", help="no progress bar")
    args = ap.parse_args(argv)
    if args.seed < 0:
        ap.error(f"--seed must be >= 0, got {args.seed}")
    preset = PRESETS[args.preset]
    if not args.force and is_current(args.out, args.name, args.seed, preset):
        man = json.loads(manifest_path(args.out, args.name).read_text())
        print(
            f"mine up to date in {args.out} (seed {args.seed}, preset {args.preset}, "
            f"generator v{GENERATOR_VERSION}): nothing to do"
        )
        print(report(man))
        return 0
    man = generate(args.out, args.seed, preset, args.name, args.quiet)
    print(report(man))
    return 0

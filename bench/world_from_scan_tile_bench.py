"""CPU time of each stage of one world_from_scan tile (docs/benchmarks.md, docs/world_from_scan.md#how).

    python bench/world_from_scan_tile_bench.py --slab 100 125 --points 50000000 --resolution 0.1

A slab of the generated Kaatiala-size mine (worlds/meshes/mine, made by scripts/setup.sh) with the tiles'
overlap on both sides, scanned at the density of a --points scan of the whole mine (noise sd 2 cm, 3 missing
patches of 0.5 m, seeded), then the tile's stages one by one on one thread, each with its CPU time [s] and the
process's peak memory: down-sampling, the k-d tree, normals (PCA), point spacing, orientation, screened Poisson,
trimming; the decimation both ways on the same fine surface (fast-simplification to the collision mesh, its folds
mended, and from it to the visual one, as the tool does; then Open3D's simplify_quadric_decimation of the
collision and the visual mesh from the fine surface), the clipping, the areas. The peak memory after the tool's
decimation is the tile's; Open3D's comes after it. Then the distance from 200 000 scan points of the
slab's core to each collision mesh (mean, 95th percentile), so that the two decimations are compared on
quality as well as time.
"""

import argparse
import math
import os
import resource
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")  # one thread, as on a Dask worker

import numpy as np  # noqa: E402

from unexmin.worlds.from_scan import sample_scan  # noqa: E402
from unexmin.worlds.from_scan.scan import (  # noqa: E402
    downsample,
    estimate_normals,
    orient_towards_void,
    orientation_samples,
    point_spacing,
)
from unexmin.worlds.from_scan.stitch import clip_slab  # noqa: E402
from unexmin.worlds.from_scan.surface import (  # noqa: E402
    distances,
    poisson_octree,
    raycasting_scene,
    reconstruct,
    simplify,
    trim_unsupported,
)
from unexmin.worlds.from_scan.tile import decimated  # noqa: E402
from unexmin.worlds.from_scan.tiles import overlap  # noqa: E402
from unexmin.worlds.meshes import read_mesh  # noqa: E402

REPO = Path(__file__).resolve().parents[1]


def cpu():
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--slab", type=float, nargs=2, default=[100.0, 125.0], help="[m] the tile's core along x")
    ap.add_argument("--points", type=float, default=50e6, help="points of a scan of the whole mine (its density)")
    ap.add_argument("--resolution", type=float, default=0.1, help="[m] (default 0.1)")
    ap.add_argument("--mesh", default=str(REPO / "worlds" / "meshes" / "mine" / "mine_collision.ply"))
    args = ap.parse_args()
    from scipy.spatial import cKDTree

    r = args.resolution
    x0, x1 = args.slab
    v, t = read_mesh(args.mesh)
    tris = v[t]
    area = 0.5 * float(np.linalg.norm(np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]), axis=1).sum())
    m = overlap(r, 1.0)
    centre = tris.mean(axis=1)[:, 0]
    raw = sample_scan(
        tris[(centre > x0 - m - 1) & (centre < x1 + m + 1)], math.sqrt(area / args.points), 0.02, 3, 0.5, 7
    )
    raw = raw[(raw[:, 0] >= x0 - m) & (raw[:, 0] <= x1 + m)]
    times = {}

    def stage(name, c0):
        times[name] = cpu() - c0
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        print(f"  {name}: {times[name]:.2f} s CPU (peak {peak:,.0f} MB)", flush=True)

    print(f"slab x {x0}..{x1} m with {m:.2f} m of overlap: {len(raw):,} scan points", flush=True)
    c0 = cpu()
    p, _ = downsample(raw, None, r)
    stage("down-sampling", c0)
    c0 = cpu()
    tree = cKDTree(p)
    stage("k-d tree", c0)
    c0 = cpu()
    n = estimate_normals(p, r)
    stage("normals", c0)
    c0 = cpu()
    spacing = point_spacing(p, 0, tree=tree)
    stage("spacing", c0)
    c0 = cpu()
    n, _ = orient_towards_void(p, n, r, samples=orientation_samples(len(p), spacing), threads=1)
    stage("orientation", c0)
    c0 = cpu()
    depth, scale = poisson_octree(p, max(r, spacing))
    fv, ft = reconstruct(p, n, depth, 1, scale)
    stage("poisson", c0)
    print(f"  {len(p):,} points at {r} m, Poisson depth {depth} (scale {scale:.3f}): {len(ft):,} triangles")
    c0 = cpu()
    fv, ft = trim_unsupported(fv, ft, p, 1.0, tree, 1)
    stage("trimming", c0)
    c0 = cpu()
    after = decimated(fv, ft, 0.3)
    decimated(*after, 1.0)
    stage("decimation, fast-simplification (collision, then visual from it)", c0)
    c0 = cpu()
    before = simplify(fv, ft, 0.3, "open3d")
    simplify(fv, ft, 1.0, "open3d")
    stage("decimation, Open3D (collision and visual from the fine surface)", c0)
    c0 = cpu()
    clip_slab(*after, 0, x0, x1)
    cv, ct = clip_slab(fv, ft, 0, x0, x1)
    stage("clipping", c0)
    c0 = cpu()
    a, b, c = cv[ct[:, 0]], cv[ct[:, 1]], cv[ct[:, 2]]
    tree.query((a + b + c) / 3.0, distance_upper_bound=3.0 * r, workers=1)
    stage("areas", c0)
    core = raw[(raw[:, 0] >= x0) & (raw[:, 0] <= x1)]
    core = core[np.random.default_rng(0).choice(len(core), min(200_000, len(core)), replace=False)]
    for name, mesh in (("Open3D", before), ("fast-simplification", after)):
        d = distances(raycasting_scene(*mesh), core)
        print(
            f"  scan to collision mesh, {name}: {len(mesh[1]):,} triangles, mean {d.mean() * 100:.2f} cm, "
            f"95th percentile {np.percentile(d, 95) * 100:.2f} cm"
        )
    total = sum(times.values())
    fast = total - times["decimation, Open3D (collision and visual from the fine surface)"]
    slow = total - times["decimation, fast-simplification (collision, then visual from it)"]
    print(
        f"tile CPU: {slow:.1f} s with Open3D's decimation, {fast:.1f} s with fast-simplification "
        f"({fast / len(p) * 1e6:.0f} us per down-sampled point); load average {os.getloadavg()[0]:.2f}"
    )


if __name__ == "__main__":
    main()

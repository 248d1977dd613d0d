"""Throughput of python -m unexmin.worlds.from_scan on scans of the Kaatiala-size mine (docs/benchmarks.md).

    python bench/world_from_scan_bench.py --points 4000000 --memory-gb 4 --out /tmp/wfs_bench
    python bench/world_from_scan_bench.py --points 50000000 --resolution 0.1 --memory-gb 8 --workers 1 2

For each size: a seeded scan of the generated mine's collision mesh (worlds/meshes/mine, made by
scripts/setup.sh) with noise sd 2 cm and 40 missing patches of 0.5 m, written as binary PLY (kept and
reused when it exists); then the tool runs in a child process once per --workers value. Prints points per
second through the whole pipeline, the child's wall and CPU time, the peak resident memory of its
largest process (wait4: the tool or one of its Dask workers) and the bound on all of them at once (the
tool's peak plus each worker's), the tiles, the tool's stage times, the tiles' CPU time (and the best
speed-up two workers could have on them), the scan-to-mesh distances and the void volume against the
generator's mesh, and the load average. Scans of more than 8M points are written triangle chunk by
triangle chunk (streamed_scan), so that generating them holds one chunk in memory.
"""

import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from unexmin.worlds.from_scan import sample_scan
from unexmin.worlds.meshes import read_mesh

REPO = Path(__file__).resolve().parents[1]
STREAMED_SCAN = 8_000_000  # scans larger than this are written by triangle chunks (streamed_scan)


def streamed_scan(path, tris, spacing, noise, holes, hole_radius, seed, chunk=100_000):
    """Write a seeded scan of `tris` (T x 3 x 3 [m]) to the binary PLY `path` triangle chunk by triangle chunk,
    so that memory holds one chunk's points whatever the size: sample_scan's model (area-uniform points, one per
    spacing^2 on average, Gaussian noise of sd `noise` [m], `holes` missing patches of `hole_radius` [m]) with the
    patches' centres drawn from a coarse seeded sample of the surface. Returns the point count."""
    from scipy.spatial import cKDTree

    from unexmin.worlds.meshes import sample_surface

    coarse, _ = sample_surface(tris, 1.0, seed)
    centres = coarse[np.random.default_rng(seed + 1).choice(len(coarse), holes, replace=False)]
    far = cKDTree(centres)
    body = path.with_suffix(".body")
    count = 0
    with open(body, "wb") as f:
        for k, i in enumerate(range(0, len(tris), chunk)):
            points, _ = sample_surface(tris[i : i + chunk], spacing, seed + 2 + k)
            points += np.random.default_rng(seed + 1_000_003 + k).normal(0.0, noise, points.shape)
            gone = far.query(points, distance_upper_bound=hole_radius)[0]
            points = np.ascontiguousarray(points[~np.isfinite(gone)], dtype="<f8")
            points.tofile(f)
            count += len(points)
    header = (
        f"ply\nformat binary_little_endian 1.0\nelement vertex {count}\n"
        "property double x\nproperty double y\nproperty double z\nend_header\n"
    )
    with open(path, "wb") as out, open(body, "rb") as f:
        out.write(header.encode("ascii"))
        shutil.copyfileobj(f, out, 64 << 20)
    body.unlink()
    return count


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--points", type=int, nargs="+", default=[1_000_000, 4_000_000])
    ap.add_argument(
        "--resolution",
        type=float,
        help="[m] passed to the tool (default: 1.25 x the scan's "
        "mean point spacing, sqrt(area / points): 0.40 m for 1M points, 0.20 m for 4M)",
    )
    ap.add_argument("--mesh", default=str(REPO / "worlds" / "meshes" / "mine" / "mine_collision.ply"))
    ap.add_argument("--out", default="/tmp/wfs_bench")
    ap.add_argument("--memory-gb", type=float, default=4.0, help="[GB] passed to the tool (default 4)")
    ap.add_argument("--workers", type=int, nargs="+", default=[2], help="local Dask workers, one run each (default 2)")
    args = ap.parse_args()
    import open3d as o3d

    v, t = read_mesh(args.mesh)
    tris = v[t]
    area = 0.5 * float(np.linalg.norm(np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]), axis=1).sum())
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    import trimesh

    true_volume = -trimesh.Trimesh(v, t, process=False).volume  # faces into the void: negative
    for n in args.points:
        resolution = args.resolution or round(1.25 * math.sqrt(area / n), 2)
        scan = out / f"mine_{n}.ply"
        if not scan.exists() and n > STREAMED_SCAN:
            streamed_scan(scan, tris, math.sqrt(area / n), 0.02, 40, 0.5, n)
        elif not scan.exists():
            points = sample_scan(tris, math.sqrt(area / n), 0.02, holes=40, hole_radius=0.5, seed=n)
            o3d.io.write_point_cloud(str(scan), o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points)))
            del points
        walls = {}
        for workers in args.workers:
            world = out / f"world_{n}_w{workers}"
            load = os.getloadavg()
            t0 = time.monotonic()
            child = subprocess.Popen(
                [
                    sys.executable,
                    "-m",
                    "unexmin.worlds.from_scan",
                    str(scan),
                    "--out",
                    str(world),
                    "--resolution",
                    str(resolution),
                    "--water-level",
                    "0",
                    "--memory-gb",
                    str(args.memory_gb),
                    "--workers",
                    str(workers),
                    "--quiet",
                ]
            )
            _, status, usage = os.wait4(child.pid, 0)
            wall = time.monotonic() - t0
            if status != 0:
                print(f"{n} points, {workers} workers: the tool failed (status {status})")
                continue
            walls[workers] = wall
            rep = json.loads((world / f"mine_{n}.json").read_text())
            print(
                f"{rep['points_read']:,} points ({rep['points_used']:,} at {resolution} m), {workers} workers, "
                f"--memory-gb {args.memory_gb}: {wall:.1f} s wall, {rep['points_read'] / wall:,.0f} points/s, "
                f"cpu {usage.ru_utime + usage.ru_stime:.1f} s, largest process {usage.ru_maxrss / 1024:,.0f} MB, "
                f"bound on all at once {rep['peak_rss_bound_mb']:,.0f} MB"
            )
            tiles = rep["tiles"]
            print(
                f"  tiles {tiles['count']} along {tiles['axis']} (budget {tiles['budget_points']:,} points each), "
                f"seam loops zipped {tiles['zipped_loops']}, open {tiles['open_loops']}, "
                f"failed {len(rep['failed_tiles'])}"
            )
            for b in tiles["built"]:
                print(f"    tile {b['index']}: {b['points_used']:,} points, worker peak {b['peak_rss_mb']:,.0f} MB")
            print(f"  stages [s]: {rep['seconds']}")
            cpu = [b["cpu_seconds"] for b in tiles["built"] if "cpu_seconds" in b]
            if cpu:
                # the tiles in the order Dask hands them to two free workers: the best two can do on these tiles
                ends = [0.0, 0.0]
                for c in cpu:
                    ends[ends.index(min(ends))] += c
                print(
                    f"  tiles' CPU {sum(cpu):.1f} s (largest tile {max(cpu):.1f} s); two workers on them at best "
                    f"{sum(cpu) / max(ends):.2f}x one; the rest of the run's CPU "
                    f"{usage.ru_utime + usage.ru_stime - sum(cpu):.1f} s"
                )
            vol = rep["volume"]
            err = f"{100 * (vol - true_volume) / true_volume:+.2f} %" if vol is not None else "n/a"
            print(
                f"  collision {rep['collision']['triangles']:,} triangles (Poisson {rep['poisson_triangles']:,}), "
                f"visual {rep['visual']['triangles']:,}, closed {rep['closed']}, holes closed {rep['holes_closed']}, "
                f"scan to mesh mean {rep['scan_to_mesh']['mean'] * 100:.1f} cm "
                f"p95 {rep['scan_to_mesh']['p95'] * 100:.1f} cm; void volume {vol} m^3 against the generator's "
                f"{true_volume:,.1f} ({err})"
            )
            after = os.getloadavg()
            print(f"  load average before {load[0]:.2f}, after {after[0]:.2f}", flush=True)
        if len(walls) == 2:
            (w1, t1), (w2, t2) = sorted(walls.items())
            print(f"  {w2} workers against {w1}: {t1 / t2:.2f}x faster (wall)")


if __name__ == "__main__":
    main()

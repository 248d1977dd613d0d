"""Throughput of python -m unexmin.world_from_scan on scans of the Kaatiala-size mine (docs/benchmarks.md).

    python bench/world_from_scan_bench.py --points 1000000 4000000 --out /tmp/wfs_bench

For each size: a seeded scan of the generated mine's collision mesh (worlds/meshes/mine, made by
scripts/setup.sh) with noise sd 2 cm and 40 missing patches of 0.5 m, written as binary PLY; then the
tool runs in a child process. Prints points per second through the whole pipeline (read to report),
the child's wall time and peak resident memory (wait4), and the tool's own stage times.
"""

import argparse
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from unexmin.world_from_scan import sample_scan
from unexmin.worlds.meshes import read_mesh

REPO = Path(__file__).resolve().parents[1]


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
    args = ap.parse_args()
    import open3d as o3d

    v, t = read_mesh(args.mesh)
    tris = v[t]
    area = 0.5 * float(np.linalg.norm(np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]), axis=1).sum())
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    for n in args.points:
        resolution = args.resolution or round(1.25 * math.sqrt(area / n), 2)
        points = sample_scan(tris, math.sqrt(area / n), 0.02, holes=40, hole_radius=0.5, seed=n)
        scan = out / f"mine_{n}.ply"
        o3d.io.write_point_cloud(str(scan), o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points)))
        del points
        t0 = time.monotonic()
        child = subprocess.Popen(
            [
                sys.executable,
                "-m",
                "unexmin.world_from_scan",
                str(scan),
                "--out",
                str(out / f"world_{n}"),
                "--resolution",
                str(resolution),
                "--water-level",
                "0",
                "--quiet",
            ]
        )
        _, status, usage = os.wait4(child.pid, 0)
        wall = time.monotonic() - t0
        if status != 0:
            print(f"{n} points: the tool failed (status {status})")
            continue
        rep = json.loads((out / f"world_{n}" / f"mine_{n}.json").read_text())
        print(
            f"{rep['points_read']:,} points ({rep['points_used']:,} at {resolution} m, Poisson depth "
            f"{rep['poisson_depth']}): {wall:.1f} s wall, {rep['points_read'] / wall:,.0f} points/s, "
            f"peak RSS {usage.ru_maxrss / 1024:,.0f} MB, cpu {usage.ru_utime + usage.ru_stime:.1f} s"
        )
        print(f"  stages [s]: {rep['seconds']}")
        print(
            f"  collision {rep['collision']['triangles']:,} triangles (Poisson {rep['poisson_triangles']:,}), "
            f"visual {rep['visual']['triangles']:,}, closed {rep['closed']}, holes closed {rep['holes_closed']}, "
            f"scan to mesh mean {rep['scan_to_mesh']['mean'] * 100:.1f} cm "
            f"p95 {rep['scan_to_mesh']['p95'] * 100:.1f} cm, "
            f"flooded volume {rep['flooded_volume']} m^3"
        )
        print(f"  load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}", flush=True)


if __name__ == "__main__":
    main()

"""Map quality against the world's ground truth (docs/mapping.md, "Map quality").

    python -m unexmin.map_quality MAP.bt --world mine|tank|<world file> [--trajectory bag-or-csv]
                                  [--tau M] [--range M] --out DIR

The occupied voxels of an OctoMap .bt (read with OctoMap's own `bt2vrml`, octomap-tools) against the
collision meshes of a world, Tanks-and-Temples style at a distance tau (default: one voxel):
- precision: fraction of occupied voxel centres (pruned leaves split into voxels of the finest size) within tau of the surface;
- recall (coverage): fraction of the surface, area-sampled, within tau of an occupied voxel centre,
  over the surface the robot could have seen: within --range (default 10 m, the mapper's max range)
  of its path (--trajectory: a bag with nav_msgs/Odometry topics, or a CSV with x, y, z columns); the
  whole surface without a trajectory;
- F-score 2PR/(P+R); mean and 95th-percentile distance of the voxel centres to the surface.
Distances are to a dense area sample of the surface near the voxels (spacing tau/4, seeded), so they
overestimate the true point-to-triangle distance by at most about that spacing; recall samples the seen
surface at tau/2 (coarser when that would exceed 4 million samples). Writes DIR/map_quality.json and
DIR/map_quality.png (voxel centres coloured by their distance to the surface, top and side views).
"""

import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

import numpy as np

from unexmin.mesh_marker import load_world, read_mesh, rpy_matrix

WORLDS = ("mine", "tank")
_TRANSLATION = re.compile(r"translation\s+(\S+)\s+(\S+)\s+(\S+)\s+children \[ Shape \{ geometry Box \{ size (\S+)")


def world_path(world):
    """A world file for `mine`, `tank` (the package's worlds/) or a path."""
    if world in WORLDS:
        return os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "worlds", f"{world}.world")
    if not os.path.exists(world):
        raise FileNotFoundError(f"--world {world}: neither {' nor '.join(WORLDS)} nor an existing world file")
    return world


def read_bt(path):
    """(centres N x 3, sizes N) [m] of the occupied leaves of an OctoMap .bt, as OctoMap's bt2vrml writes them."""
    if shutil.which("bt2vrml") is None:
        raise RuntimeError("bt2vrml not found: install octomap-tools (scripts/setup.sh does)")
    if not os.path.exists(path):
        raise FileNotFoundError(path)
    with tempfile.TemporaryDirectory() as tmp:
        copy = os.path.join(tmp, "map.bt")
        shutil.copyfile(path, copy)
        out = subprocess.run(["bt2vrml", copy], capture_output=True, text=True, timeout=600)
        if out.returncode != 0 or not os.path.exists(copy + ".wrl"):
            raise RuntimeError(f"bt2vrml {path} failed: {out.stdout[-500:]} {out.stderr[-500:]}")
        with open(copy + ".wrl") as f:
            text = f.read().replace("\n", " ")
    rows = np.array([[float(v) for v in m] for m in _TRANSLATION.findall(text)]).reshape(-1, 4)
    reported = re.search(r"Finished writing (\d+) voxels", out.stdout)
    if reported and int(reported.group(1)) != len(rows):
        raise RuntimeError(f"bt2vrml reported {reported.group(1)} voxels, {len(rows)} parsed")
    return rows[:, :3], rows[:, 3]


def expand(centres, sizes):
    """Centres of the finest voxels (edge: the smallest size) that the (possibly pruned, larger) leaves hold."""
    if not len(sizes):
        return centres, sizes
    res = float(sizes.min())
    out = []
    for n in np.unique(np.rint(sizes / res).astype(int)):
        sel = np.rint(sizes / res).astype(int) == n
        offsets = (np.arange(n) - (n - 1) / 2.0) * res
        grid = np.stack(np.meshgrid(offsets, offsets, offsets, indexing="ij"), -1).reshape(-1, 3)
        out.append((centres[sel][:, None, :] + grid[None, :, :]).reshape(-1, 3))
    centres = np.concatenate(out)
    return centres, np.full(len(centres), res)


def world_triangles(path):
    """T x 3 x 3 [m, world frame] of the world's collision meshes."""
    tris = []
    for entry in load_world(path)["meshes"]:
        if not entry["collision"]:
            continue
        v, t = read_mesh(entry["file"])
        v = (v * np.array(entry["scale"])) @ rpy_matrix(entry["rpy"]).T + np.array(entry["xyz"])
        tris.append(v[t])
    if not tris:
        raise ValueError(f"{path}: no collision mesh")
    return np.concatenate(tris)


def read_trajectory(path):
    """N x 3 positions [m]: every nav_msgs/Odometry of a bag, or the x, y, z columns of a CSV."""
    if path.endswith(".csv"):
        import csv

        with open(path) as f:
            rows = list(csv.DictReader(f))
        return np.array([[float(r["x"]), float(r["y"]), float(r["z"])] for r in rows])
    from pathlib import Path

    from rosbags.highlevel import AnyReader
    from rosbags.typesys import Stores, get_typestore

    points = []
    with AnyReader([Path(path)], default_typestore=get_typestore(Stores.ROS1_NOETIC)) as reader:
        conns = [c for c in reader.connections if c.msgtype == "nav_msgs/msg/Odometry"]
        for conn, _, raw in reader.messages(connections=conns):
            p = reader.deserialize(raw, conn.msgtype).pose.pose.position
            points.append((p.x, p.y, p.z))
    if not points:
        raise ValueError(f"{path}: no nav_msgs/Odometry messages")
    return np.array(points)


def sample_surface(tris, spacing, seed=0):
    """Area-uniform samples of the triangles, one per spacing^2 on average (seeded): N x 3 [m]."""
    rng = np.random.default_rng(seed)
    a, b, c = tris[:, 0], tris[:, 1], tris[:, 2]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    expected = area / spacing ** 2
    counts = np.floor(expected + rng.random(len(tris))).astype(np.int64)
    idx = np.repeat(np.arange(len(tris)), counts)
    u, v = rng.random(len(idx)), rng.random(len(idx))
    flip = u + v > 1.0
    u[flip], v[flip] = 1.0 - u[flip], 1.0 - v[flip]
    return a[idx] + u[:, None] * (b[idx] - a[idx]) + v[:, None] * (c[idx] - a[idx]), float(area.sum())


def near_path(tris, path, reach):
    """Triangles with a vertex or the centroid within reach [m] of a path point."""
    from scipy.spatial import cKDTree

    tree = cKDTree(path)
    pts = np.concatenate([tris, tris.mean(axis=1, keepdims=True)], axis=1).reshape(-1, 3)
    d, _ = tree.query(pts, distance_upper_bound=reach)
    return np.isfinite(d).reshape(len(tris), 4).any(axis=1)


def evaluate(centres, tris, tau, path=None, sensor_range=10.0, seed=0):
    """The quality figures (dict) of occupied voxel centres against the triangles, and the per-voxel distances."""
    from scipy.spatial import cKDTree

    spacing = tau / 4.0
    # Precision: each voxel centre against a dense sample of the triangles near the voxels.
    wide_tris = tris[near_path(tris, centres, 2.0 * tau + 1.0)] if len(centres) else tris[:0]
    wide, _ = sample_surface(wide_tris, spacing, seed)
    # Recall: the surface within sensor range of the path (all of it without a path), sampled at tau/2 or
    # coarser, at most about 4 million samples.
    seen_tris = tris if path is None else tris[near_path(tris, path, sensor_range + 1.0)]
    area = 0.5 * np.linalg.norm(np.cross(seen_tris[:, 1] - seen_tris[:, 0], seen_tris[:, 2] - seen_tris[:, 0]), axis=1).sum()
    seen_spacing = max(tau / 2.0, math.sqrt(area / 4e6)) if area > 0 else tau / 2.0
    seen, seen_area = sample_surface(seen_tris, seen_spacing, seed + 1)
    if path is not None and len(seen):
        d_path, _ = cKDTree(path).query(seen)
        seen_area *= float(np.mean(d_path <= sensor_range))
        seen = seen[d_path <= sensor_range]
    result = {"tau_m": tau, "occupied_voxels": int(len(centres)), "surface_samples": int(len(seen)),
              "surface_area_m2": round(seen_area, 3), "sample_spacing_m": spacing,
              "recall_sample_spacing_m": seen_spacing,
              "sensor_range_m": sensor_range if path is not None else None}
    dist = np.full(len(centres), np.inf)
    if len(centres) and len(wide):
        dist, _ = cKDTree(wide).query(centres)
    precision = float(np.mean(dist <= tau)) if len(centres) else 0.0
    recall = 0.0
    if len(seen) and len(centres):
        d_seen, _ = cKDTree(centres).query(seen)
        recall = float(np.mean(d_seen <= tau))
    finite = dist[np.isfinite(dist)]
    result.update({
        "precision": precision, "recall": recall,
        "f_score": 2 * precision * recall / (precision + recall) if precision + recall > 0 else 0.0,
        "mean_distance_m": float(finite.mean()) if len(finite) else None,
        "p95_distance_m": float(np.percentile(finite, 95)) if len(finite) else None,
    })
    return result, dist


def plot(centres, dist, tau, path, out_png, title):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    d = np.minimum(dist, 3 * tau)
    order = np.argsort(d)
    for ax, (i, j, name) in zip(axes, [(0, 1, "top view (x, y)"), (0, 2, "side view (x, z)")]):
        sc = ax.scatter(centres[order, i], centres[order, j], c=d[order], s=2, cmap="viridis_r", vmin=0, vmax=3 * tau)
        if path is not None:
            ax.plot(path[:, i], path[:, j], "r-", lw=1, label="path")
            ax.legend(loc="best")
        ax.set(xlabel="xyz"[i] + " [m]", ylabel="xyz"[j] + " [m]", title=name, aspect="equal")
    fig.colorbar(sc, ax=axes, label=f"distance to the surface [m] (clipped at 3 tau = {3 * tau:g})")
    fig.suptitle(title)
    fig.savefig(out_png, dpi=110)
    plt.close(fig)


def run(map_path, world, out, trajectory=None, tau=None, sensor_range=10.0, seed=0):
    leaves, leaf_sizes = read_bt(map_path)
    centres, sizes = expand(leaves, leaf_sizes)
    if tau is None:
        tau = float(sizes.min()) if len(sizes) else 0.1
    tris = world_triangles(world_path(world))
    path = read_trajectory(trajectory) if trajectory else None
    result, dist = evaluate(centres, tris, tau, path, sensor_range, seed)
    result.update({"occupied_leaves": int(len(leaves)), "map": os.path.abspath(map_path), "world": world, "trajectory": trajectory,
                   "map_bytes": os.path.getsize(map_path)})
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "map_quality.json"), "w") as f:
        json.dump(result, f, indent=2)
    if len(centres):
        plot(centres, dist, tau, path, os.path.join(out, "map_quality.png"),
             f"{os.path.basename(map_path)} vs {world}: precision {result['precision']:.3f}, "
             f"recall {result['recall']:.3f}, F {result['f_score']:.3f} at tau {tau:g} m")
    return result


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("map", help="OctoMap .bt file")
    parser.add_argument("--world", required=True, help="mine, tank or a world file")
    parser.add_argument("--trajectory", help="bag (nav_msgs/Odometry) or CSV (x, y, z) of the robot's path")
    parser.add_argument("--tau", type=float, help="distance threshold [m] (default: the voxel size)")
    parser.add_argument("--range", type=float, default=10.0, dest="sensor_range",
                        help="surface within this distance [m] of the path counts for recall (default 10)")
    parser.add_argument("--out", required=True, help="output folder (created)")
    args = parser.parse_args(argv)
    r = run(args.map, args.world, args.out, args.trajectory, args.tau, args.sensor_range)
    print(f"{r['occupied_voxels']} occupied voxels: precision {r['precision']:.3f}, recall {r['recall']:.3f}, "
          f"F-score {r['f_score']:.3f} at tau {r['tau_m']:g} m; distance mean {r['mean_distance_m']:.3f} m, "
          f"95th percentile {r['p95_distance_m']:.3f} m -> {os.path.join(args.out, 'map_quality.json')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

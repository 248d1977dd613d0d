"""Map quality against the world's ground truth (docs/mapping.md, "Map quality").

    python -m unexmin.map_quality MAP.bt --world mine|tank|<world file> [--trajectory bag-or-csv]
                                  [--tau M] [--range M] --out DIR

The occupied voxels of an OctoMap .bt (read with OctoMap's own `bt2vrml`, octomap-tools) against the
collision meshes of a world, Tanks-and-Temples style at a distance tau (default: one voxel):
- precision: fraction of occupied voxel centres (pruned leaves split into voxels of the finest size) within tau of
  the surface;
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
import os
import sys

from unexmin.map_quality.io import read_bt, read_trajectory
from unexmin.map_quality.metrics import evaluate, expand
from unexmin.map_quality.plots import plot_distances
from unexmin.worlds.files import world_path, world_triangles


def run(map_path, world, out, trajectory=None, tau=None, sensor_range=10.0, seed=0):
    """The quality figures (dict) of the map at map_path against `world` (mine, tank or a world file); writes
    out/map_quality.json and out/map_quality.png."""
    leaves, leaf_sizes = read_bt(map_path)
    centres, sizes = expand(leaves, leaf_sizes)
    if tau is None:
        tau = float(sizes.min()) if len(sizes) else 0.1
    tris = world_triangles(world_path(world))
    path = read_trajectory(trajectory)[:, 1:4] if trajectory else None
    result, dist = evaluate(centres, tris, tau, path, sensor_range, seed)
    result.update(
        {
            "occupied_leaves": int(len(leaves)),
            "map": os.path.abspath(map_path),
            "world": world,
            "trajectory": trajectory,
            "map_bytes": os.path.getsize(map_path),
        }
    )
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "map_quality.json"), "w") as f:
        json.dump(result, f, indent=2)
    if len(centres):
        plot_distances(
            centres,
            dist,
            tau,
            path,
            os.path.join(out, "map_quality.png"),
            f"{os.path.basename(map_path)} vs {world}: precision {result['precision']:.3f}, "
            f"recall {result['recall']:.3f}, F {result['f_score']:.3f} at tau {tau:g} m",
        )
    return result


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m unexmin.map_quality", description=__doc__.splitlines()[0])
    parser.add_argument("map", help="OctoMap .bt file")
    parser.add_argument("--world", required=True, help="mine, tank or a world file")
    parser.add_argument("--trajectory", help="bag (nav_msgs/Odometry) or CSV (x, y, z) of the robot's path")
    parser.add_argument("--tau", type=float, help="distance threshold [m] (default: the voxel size)")
    parser.add_argument(
        "--range",
        type=float,
        default=10.0,
        dest="sensor_range",
        help="surface within this distance [m] of the path counts for recall (default 10)",
    )
    parser.add_argument("--out", required=True, help="output folder (created)")
    args = parser.parse_args(argv)
    r = run(args.map, args.world, args.out, args.trajectory, args.tau, args.sensor_range)
    print(
        f"{r['occupied_voxels']} occupied voxels: precision {r['precision']:.3f}, recall {r['recall']:.3f}, "
        f"F-score {r['f_score']:.3f} at tau {r['tau_m']:g} m; distance mean {r['mean_distance_m']:.3f} m, "
        f"95th percentile {r['p95_distance_m']:.3f} m -> {os.path.join(args.out, 'map_quality.json')}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())

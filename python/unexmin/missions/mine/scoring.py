"""The mine mission's scoring: the flight's map and its snapshots against the mine's collision mesh
(unexmin.map_quality), the plots (mission_map.png, coverage.png) and summary.json."""

import os
import time

import numpy as np

from unexmin.missions.common import write_summary
from unexmin.missions.mine.runner import M3_MAX_RANGE, ROBOT


def plot_map(map_path, traj, out_png):
    """Top and side views of the map's occupied voxels coloured by height, with the path."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from unexmin.map_quality import read_bt

    centres, _ = read_bt(map_path)
    fig, axes = plt.subplots(2, 1, figsize=(12, 9))
    for ax, (i, j, name) in zip(axes, [(0, 1, "top view"), (0, 2, "side view")]):
        if len(centres):
            ax.scatter(centres[:, i], centres[:, j], c=centres[:, 2], s=1, cmap="turbo")
        ax.plot(traj[:, i], traj[:, j], "k-", lw=1.2, label="UX_1 path")
        ax.set(
            xlabel="xyz"[i] + " [m]",
            ylabel="xyz"[j] + " [m]",
            title=f"mine map ({name}, colour: height)",
            aspect="equal",
        )
        ax.legend(loc="best")
    fig.tight_layout()
    fig.savefig(out_png, dpi=110)
    plt.close(fig)


def plot_coverage(coverage, surface_area, out_png):
    """Recall (the map's share of the surface within range of the whole path) against sim time."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = [c["t"] for c in coverage]
    fig, ax = plt.subplots(figsize=(8, 4.5), layout="constrained")
    ax.plot(t, [c["recall"] for c in coverage], "o-", label="recall")
    ax.plot(t, [c["precision"] for c in coverage], "s--", label="precision")
    ax.set(
        xlabel="sim time [s]",
        ylabel="fraction",
        ylim=(0, 1.02),
        title=f"survey coverage of the {surface_area:.0f} m² within the sensors' range of the path",
    )
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right")
    fig.savefig(out_png, dpi=110)
    plt.close(fig)


def score_snapshots(snapshots, world_file, traj, tau, sensor_range=10.0):
    """[{t, recall, precision, occupied_voxels}] of each saved map against the surface within range of the
    whole path (the final figure's denominator, so the curve ends at the final recall)."""
    from scipy.spatial import cKDTree

    from unexmin.map_quality import expand, read_bt, recall_of, seen_surface
    from unexmin.map_quality.metrics import near_path
    from unexmin.worlds.files import world_triangles
    from unexmin.worlds.meshes import sample_surface

    tris = world_triangles(world_file)
    seen, _, _ = seen_surface(tris, tau, traj, sensor_range, 0)
    maps = [(t, expand(*read_bt(path))[0]) for t, path in snapshots]
    # One surface sample for every snapshot: a voxel's nearest surface within tau lies in the triangles near the
    # union of the snapshots' voxels as surely as in those near its own snapshot's.
    union = np.unique(np.concatenate([c for _, c in maps] + [np.empty((0, 3))]), axis=0)
    wide = np.empty((0, 3))
    if len(union):
        wide, _ = sample_surface(tris[near_path(tris, union, 2.0 * tau + 1.0)], tau / 4.0, 0)
    tree = cKDTree(wide) if len(wide) else None
    rows = []
    for t, centres in maps:
        precision = 0.0
        if len(centres) and tree is not None:
            d, _ = tree.query(centres, distance_upper_bound=tau * (1.0 + 1e-9))
            precision = float(np.mean(d <= tau))
        rows.append(
            {"t": t, "recall": recall_of(centres, seen, tau), "precision": precision, "occupied_voxels": len(centres)}
        )
    return rows


def score(plan, flight):
    """Scores a Flight (runner.py) of a MinePlan (plan.py), writes trajectory.csv, map_quality.json/.png,
    coverage.png, mission_map.png and summary.json into the flight's folder; returns the summary."""
    from unexmin.map_quality import read_trajectory, write_trajectory
    from unexmin.map_quality import run as quality

    files = flight.files
    traj = read_trajectory(files.bag)
    write_trajectory(os.path.join(files.out, "trajectory.csv"), traj)
    q = quality(files.map_path, plan.world_file, files.out, trajectory=os.path.join(files.out, "trajectory.csv"))
    coverage = score_snapshots(flight.snapshots, plan.world_file, traj[:, 1:4], q["tau_m"])
    coverage.append(
        {
            "t": flight.sim_time,
            "recall": q["recall"],
            "precision": q["precision"],
            "occupied_voxels": q["occupied_voxels"],
        }
    )
    plot_coverage(coverage, q["surface_area_m2"], os.path.join(files.out, "coverage.png"))
    plot_map(files.map_path, traj[:, 1:4], os.path.join(files.out, "mission_map.png"))
    wall = time.monotonic() - flight.started
    return write_summary(files.out, summary(plan, flight, traj, q, coverage, wall))


def summary(plan, flight, traj, q, coverage, wall):
    """summary.json's record: the run, the flight, the mapper's figures, the map's quality, the coverage curve."""
    f, final, options = flight, flight.final, plan.options
    return {
        "world": os.path.splitext(os.path.basename(plan.world_file))[0],
        "world_file": plan.world_file,
        "robot": ROBOT,
        "seed": f.seed,
        "visibility": plan.visibility or f"world file ({plan.level})",
        "standoff_m": {"shaft": round(options.standoff, 3), "gallery": round(options.gallery_standoff, 3)},
        "m3_max_range_m": M3_MAX_RANGE,
        "resolution_m": f.resolution,
        "sim_time_s": f.sim_time,
        "plan_s": round(plan.reference.duration, 1),
        "held_s": round(f.held, 1),
        "wall_time_s": round(wall, 2),
        "mission_wall_s": round(f.mission_wall, 2),
        "stepping_wall_s": round(f.stepping_wall, 2),
        "rtf_while_stepping": round(f.sim_time / f.stepping_wall, 2),
        "load_average_1min": round(os.getloadavg()[0], 2),
        "path_length_m": float(np.linalg.norm(np.diff(traj[:, 1:4], axis=0), axis=1).sum()),
        "start": dict(zip("xyz", traj[0, 1:4].round(3).tolist())),
        "end": dict(zip("xyz", traj[-1, 1:4].round(3).tolist())),
        "plan_completed": bool(f.progress >= plan.reference.duration),
        "clouds_expected": f.clouds_expected,
        "clouds_received": int(final.clouds_received),
        "clouds_inserted": int(final.clouds_inserted),
        "clouds_dropped": int(final.clouds_dropped),
        "points_inserted": int(final.points_inserted),
        "insert_wall_s": round(final.insert_seconds, 3),
        "map_memory_bytes": int(final.memory_bytes),
        "map_file_bytes": os.path.getsize(flight.files.map_path),
        "occupied_leaves": q["occupied_leaves"],
        "quality": {
            k: q[k]
            for k in ("precision", "recall", "f_score", "mean_distance_m", "p95_distance_m", "tau_m", "surface_area_m2")
        },
        "recall_definition": (
            "share of the collision surface within sensor_range_m (the mapper's max range) of the recorded path "
            "that lies within tau_m of an occupied voxel centre (unexmin.map_quality)"
        ),
        "sensor_range_m": q["sensor_range_m"],
        "coverage": coverage,
        "legs": f.legs,
    }

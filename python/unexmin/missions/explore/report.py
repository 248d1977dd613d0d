"""The explorer's outputs (docs/explore.md): summary.json, trajectory.csv, map_quality.json/.png, explore_map.png
(the map from above and from the side with the paths) and explore_timeline.png (explored share, drift, distance
and energy against sim time)."""

import json
import os

import numpy as np


def write(explorer):
    """Score the run's map against the world (unexmin.map_quality), write every output; returns the summary."""
    from unexmin.map_quality import run as quality
    from unexmin.map_quality import write_trajectory

    e = explorer
    out = e.out
    rows = [(r["t"], *r["true"], 0.0) for a in e.agents for r in a.rows]
    traj_csv = os.path.join(out, "trajectory.csv")
    write_trajectory(traj_csv, np.array(rows).reshape(-1, 5))
    q = quality(e.map_path, e.world_file, out, trajectory=traj_csv)
    coverage = []
    if e.snapshots:
        from unexmin.missions.mine.scoring import score_snapshots

        coverage = score_snapshots(e.snapshots, e.world_file, np.array(rows)[:, 1:4], q["tau_m"])
        coverage.append({"t": e.sim_time, "recall": q["recall"], "precision": q["precision"]})
        for c in coverage:
            p, r = c["precision"], c["recall"]
            c["f_score"] = 2 * p * r / (p + r) if p + r > 0 else 0.0
    final = e.timeline[-1]
    robots = {}
    for a in e.agents:
        last = a.rows[-1] if a.rows else {}
        robots[a.name] = {
            "mode": a.mode,
            "why": a.why,
            "start": a.home.round(3).tolist(),
            "end_true": last.get("true"),
            "end_estimate": a.nav.p.round(3).tolist(),
            "home_error_m": round(float(np.linalg.norm(np.asarray(last.get("true", a.home)) - a.home)), 3),
            "flown_m": round(a.flown, 2),
            "energy_j": round(a.energy, 1),
            "drift_m": last.get("drift_m"),
            "max_drift_m": max((r["drift_m"] for r in a.rows), default=None),
            "min_clearance_m": round(float(a.min_clearance), 3),
            "dvl_lock_lost_s": round(a.nav.lock_lost_s, 1),
        }
    kinds = [ev["kind"] for ev in e.events]
    summary = {
        "world_file": e.world_file,
        "robots": len(e.agents),
        "seed": e.seed,
        "visibility": e.visibility or "world file",
        "bounds": [e.lo.round(3).tolist(), e.hi.round(3).tolist()],
        "budget": {"time_s": e.budget.time_s, "energy_j": e.budget.energy_j, "reserve": e.budget.reserve},
        "sim_time_s": round(e.sim_time, 2),
        "mission_wall_s": round(e.mission_wall, 1),
        "stepping_wall_s": round(e.stepping_wall, 1),
        "rtf_while_stepping": round(e.sim_time / e.stepping_wall, 2) if e.stepping_wall > 0 else None,
        "load_average_1min": round(os.getloadavg()[0], 2),
        "reachable_m3": round(e.reachable_m3, 2),
        "explored_m3": final["explored_m3"],
        "explored_reachable_m3": final["explored_reachable_m3"],
        "coverage": final["coverage"],
        "coverage_definition": (
            "share of the grid cells (cell_m) where the hull's centre can be (at least hull_radius from the rock, "
            "connected to the start, under the surface less surface_margin) that the map knows (free or occupied)"
        ),
        "cell_m": e.grid.cell,
        "all_home": all(a.mode == "home" for a in e.agents),
        "contacts": kinds.count("contact"),
        "stuck": kinds.count("stuck"),
        "sonar_stops": kinds.count("sonar_stop"),
        "quality": {k: q[k] for k in ("precision", "recall", "f_score", "tau_m", "surface_area_m2", "occupied_voxels")},
        "robot": robots,
        "timeline": e.timeline,
        "f_score_over_time": coverage,
        "events": e.events,
        "tracks": {a.name: a.rows for a in e.agents},
    }
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    plot_map(e, os.path.join(out, "explore_map.png"))
    plot_timeline(e, os.path.join(out, "explore_timeline.png"))
    return summary


def plot_map(e, out_png):
    """Top view over side view of the map's occupied voxels (colour: height) with each robot's true path (solid)
    and estimated path (dashed)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from unexmin.map_quality import read_bt

    centres, _ = read_bt(e.map_path)
    lo, hi = e.lo, e.hi
    span = np.maximum(hi - lo, 1.0)
    fig, axes = plt.subplots(
        2,
        1,
        figsize=(10, min(12, 10 * 0.85 * (span[1] + span[2]) / span[0] + 1.5)),
        sharex=True,
        gridspec_kw={"height_ratios": [span[1], span[2]]},
        layout="constrained",
    )
    colours = ["k", "tab:red", "tab:blue"]
    for ax, (i, j, name) in zip(axes, [(0, 1, "top view (x, y)"), (0, 2, "side view (x, z)")]):
        if len(centres):
            ax.scatter(centres[:, i], centres[:, j], c=centres[:, 2], s=1, cmap="turbo", rasterized=True)
        for a, c in zip(e.agents, colours):
            tr = np.array([r["true"] for r in a.rows]).reshape(-1, 3)
            es = np.array([r["estimate"] for r in a.rows]).reshape(-1, 3)
            ax.plot(tr[:, i], tr[:, j], "-", color=c, lw=1.2, label=f"{a.name} path")
            ax.plot(es[:, i], es[:, j], "--", color=c, lw=0.8, label=f"{a.name} estimate")
            ax.plot(a.home[i], a.home[j], "o", color=c, ms=5)
        ax.set(ylabel="xyz"[j] + " [m]", title=name, aspect="equal", xlim=(lo[0], hi[0]), ylim=(lo[j], hi[j]))
    axes[0].legend(loc="upper right", fontsize=7, ncol=len(e.agents))
    axes[1].set_xlabel("x [m]")
    fig.suptitle(f"explorer: {len(e.agents)} robot(s), map coloured by height")
    fig.savefig(out_png, dpi=90)
    plt.close(fig)


def plot_timeline(e, out_png):
    """Explored share of the reachable volume, drift, distance flown and energy against sim time."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(4, 1, figsize=(8, 9), sharex=True, layout="constrained")
    t = [r["t"] for r in e.timeline]
    axes[0].plot(t, [r["coverage"] for r in e.timeline], "o-", ms=3)
    axes[0].set(ylabel="explored share\nof reachable", ylim=(0, 1.02))
    for a in e.agents:
        ta = [r["t"] for r in a.rows]
        axes[1].plot(ta, [r["drift_m"] for r in a.rows], label=a.name)
        axes[2].plot(ta, [r["flown_m"] for r in a.rows], label=a.name)
        axes[3].plot(ta, [r["energy_j"] for r in a.rows], label=a.name)
    axes[1].set(ylabel="drift [m]")
    axes[2].set(ylabel="distance flown [m]")
    axes[3].set(ylabel="energy [J]", xlabel="sim time [s]")
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[1].legend(loc="upper left", fontsize=8)
    fig.savefig(out_png, dpi=90)
    plt.close(fig)

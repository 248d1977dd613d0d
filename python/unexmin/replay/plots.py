"""The replay's files: PNG plots (thesis figures 6.16-6.19) and trajectory.csv."""

from pathlib import Path

import numpy as np

from unexmin.replay.metrics import TRAJ_COLUMNS


def write_plots(out_dir, sim, nav=None, title=""):
    """PNG plots in out_dir: xy.png, xz.png, yz.png, yaw.png and, with a navigation, error.png.
    sim / nav: rows of TRAJ_COLUMNS (already in the compared frame). Returns the file names."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out_dir = Path(out_dir)
    files = []
    for name, (i, j) in (("xy", (1, 2)), ("xz", (1, 3)), ("yz", (2, 3))):
        fig, ax = plt.subplots(figsize=(6, 5))
        if nav is not None:
            ax.plot(nav[:, i], nav[:, j], "-", color="tab:red", label="real (bag)")
            ax.plot(nav[0, i], nav[0, j], "o", color="tab:red")
        ax.plot(sim[:, i], sim[:, j], "-", color="tab:blue", label="simulated")
        ax.plot(sim[0, i], sim[0, j], "o", color="tab:blue")
        ax.set_xlabel(f"{TRAJ_COLUMNS[i]} [m]")
        ax.set_ylabel(f"{TRAJ_COLUMNS[j]} [m]")
        ax.set_title(f"{title} trajectory {name.upper()}".strip())
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(True, alpha=0.3)
        ax.legend()
        fig.tight_layout()
        fig.savefig(out_dir / f"{name}.png", dpi=100)
        plt.close(fig)
        files.append(f"{name}.png")
    fig, ax = plt.subplots(figsize=(7, 4))
    if nav is not None:
        ax.plot(nav[:, 0], np.degrees(nav[:, 6]), color="tab:red", label="real (bag)")
    ax.plot(sim[:, 0], np.degrees(np.unwrap(sim[:, 6])), color="tab:blue", label="simulated")
    ax.set_xlabel("mission time [s]")
    ax.set_ylabel("yaw [deg]")
    ax.set_title(f"{title} yaw".strip())
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(out_dir / "yaw.png", dpi=100)
    plt.close(fig)
    files.append("yaw.png")
    if nav is not None:
        fig, ax = plt.subplots(figsize=(7, 4))
        ax.plot(sim[:, 0], np.linalg.norm(sim[:, 1:4] - nav[:, 1:4], axis=1), color="k")
        ax.set_xlabel("mission time [s]")
        ax.set_ylabel("position error [m]")
        ax.set_title(f"{title} position error, simulated - real".strip())
        ax.grid(True, alpha=0.3)
        fig.tight_layout()
        fig.savefig(out_dir / "error.png", dpi=100)
        plt.close(fig)
        files.append("error.png")
    return files


def write_csv(path, sim, nav=None):
    """trajectory.csv: t, sim_x .. sim_yaw[, bag_x .. bag_yaw] ([s], [m], [rad]), one row per sample."""
    cols = [f"sim_{c}" for c in TRAJ_COLUMNS[1:]]
    data = [sim]
    if nav is not None:
        cols += [f"bag_{c}" for c in TRAJ_COLUMNS[1:]]
        data.append(nav[:, 1:])
    np.savetxt(path, np.hstack(data), delimiter=",", header=",".join(["t"] + cols), comments="", fmt="%.6f")

"""The map quality picture: voxel centres coloured by their distance to the surface, top and side views."""

import numpy as np


def plot_distances(centres, dist, tau, path, out_png, title):
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

"""The map quality picture: voxel centres coloured by their distance to the surface, top and side views."""

import numpy as np


def plot_distances(centres, dist, tau, path, out_png, title):
    """Top view (x, y) over side view (x, z), equal scales, x shared: the panels' heights follow the map's
    extents so the views fill the page."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    pts = centres if path is None else np.concatenate([centres, path])
    lo, hi = pts.min(axis=0) - 0.5, pts.max(axis=0) + 0.5
    span = np.maximum(hi - lo, 1.0)
    width = 12.0
    heights = [span[1], span[2]]
    panel_h = width * 0.82 / span[0]  # inches per metre, the colour bar beside
    fig_h = min(max(panel_h * sum(heights) + 1.6, 4.0), 16.0)
    fig, axes = plt.subplots(
        2, 1, figsize=(width, fig_h), sharex=True, gridspec_kw={"height_ratios": heights}, layout="constrained"
    )
    d = np.minimum(dist, 3 * tau)
    order = np.argsort(d)
    for ax, (i, j, name) in zip(axes, [(0, 1, "top view (x, y)"), (0, 2, "side view (x, z)")]):
        sc = ax.scatter(centres[order, i], centres[order, j], c=d[order], s=2, cmap="viridis_r", vmin=0, vmax=3 * tau)
        if path is not None:
            ax.plot(path[:, i], path[:, j], "r-", lw=0.8, label="path")
            ax.legend(loc="upper right")
        ax.set(ylabel="xyz"[j] + " [m]", title=name, aspect="equal", xlim=(lo[0], hi[0]), ylim=(lo[j], hi[j]))
    axes[1].set_xlabel("x [m]")
    fig.colorbar(sc, ax=axes, label=f"distance to the surface [m] (clipped at 3 tau = {3 * tau:g})", shrink=0.9)
    fig.suptitle(title)
    fig.savefig(out_png, dpi=110)
    plt.close(fig)

"""docs/images/world_from_scan.png: a scan of the shipped mine's entry shaft and first level (noise 2 cm,
missing patches), the world python -m unexmin.worlds.from_scan makes of it, and UX_1 in that world in rviz.

    python worlds/tools/make_scan_figure.py [--out docs/images/world_from_scan.png] [--work /tmp/scan_figure]

Needs the generated mine (scripts/setup.sh), Xvfb, ImageMagick's import and rviz. rviz runs with a copy of
launch/unexmin.rviz whose orbit view is centred on UX_1's spawn point.
"""

import argparse
import re
import subprocess
import time
from pathlib import Path

import numpy as np

from unexmin.scripting.launcher import WorldProcess, wait_for
from unexmin.worlds.from_scan import build_world, sample_scan
from unexmin.worlds.meshes import read_mesh

REPO = Path(__file__).resolve().parents[2]


def rviz_shot(world_file, spawn, work):
    """Screenshot (PNG path) of rviz showing the world's meshes and UX_1, under a private Xvfb."""
    config = (REPO / "launch" / "unexmin.rviz").read_text()
    focal = "      Focal Point:\n        X: {:.2f}\n        Y: {:.2f}\n        Z: {:.2f}\n".format(*spawn)
    config = re.sub(r"      Focal Point:\n        X: \S+\n        Y: \S+\n        Z: \S+\n", focal, config, count=1)
    config = re.sub(r"      Distance: \S+\n", "      Distance: 14\n", config, count=1)
    (work / "view.rviz").write_text(config)
    launch = work / "figure.launch"
    launch.write_text(
        '<launch><include file="$(find unexmin)/launch/world.launch">'
        f'<arg name="world_file" value="{world_file}"/><arg name="robots" value="1"/>'
        '<arg name="sensors" value="none"/></include>'
        f'<node name="rviz" pkg="rviz" type="rviz" args="-d {work / "view.rviz"}"/></launch>\n'
    )
    xvfb = subprocess.Popen(
        ["Xvfb", "-displayfd", "1", "-screen", "0", "1024x768x24", "-nolisten", "tcp"],
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
        start_new_session=True,
    )
    display = ":" + xvfb.stdout.readline().strip()
    import os

    os.environ["DISPLAY"] = display
    world = WorldProcess(launch_file=launch, log_dir=str(work / "log"))
    try:
        import rosgraph

        master = rosgraph.Master("/scan_figure", master_uri=world.uri)

        def rviz_listens():
            try:
                _, subs, _ = master.getSystemState()
            except OSError:
                return False
            return any(t == "/world_meshes" and "/rviz" in n for t, n in subs)

        wait_for(rviz_listens, 180, "rviz to subscribe to /world_meshes")
        time.sleep(20.0)  # rviz's first frames with the meshes and the robot (a figure, not a test)
        shot = work / "rviz.png"
        subprocess.run(["import", "-display", display, "-window", "root", str(shot)], check=True, timeout=60)
        return shot
    finally:
        world.close()
        xvfb.terminate()
        xvfb.wait(10)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=str(REPO / "docs" / "images" / "world_from_scan.png"))
    ap.add_argument("--work", default="/tmp/scan_figure")
    args = ap.parse_args()
    work = Path(args.work)
    work.mkdir(parents=True, exist_ok=True)
    v, t = read_mesh(str(REPO / "worlds" / "meshes" / "mine" / "mine_collision.ply"))
    tris = v[t]
    c = tris.mean(axis=1)
    section = tris[(c[:, 0] < 30.0) & (c[:, 2] > -32.0)]
    points = sample_scan(section, 0.08, 0.02, holes=15, hole_radius=0.5, seed=11)
    scan = work / "shaft_scan.xyz"
    np.savetxt(scan, points, fmt="%.4f")
    rep = build_world(scan, work / "world", name="shaft_scan", water_level=0.0, quiet=True)
    spawn = rep["spawns"][0]["xyz"]
    shot = rviz_shot(work / "world" / rep["world"], spawn, work)

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.image import imread
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    vv, vt = read_mesh(str(work / "world" / "shaft_scan_visual.ply"))
    fig = plt.figure(figsize=(15, 5.2))
    rng = np.random.default_rng(0)
    sub = points[rng.choice(len(points), min(60000, len(points)), replace=False)]
    for k, title in enumerate(
        (
            f"scan: {len(points):,} points (noise 2 cm, 15 missing patches)",
            f"mesh: {rep['collision']['triangles']:,} triangles, closed, {rep['holes_closed']} holes closed",
        )
    ):
        ax = fig.add_subplot(1, 3, k + 1, projection="3d")
        if k == 0:
            ax.scatter(sub[:, 0], sub[:, 1], sub[:, 2], s=0.2, c=sub[:, 2], cmap="viridis")
        else:
            n = np.cross(vv[vt[:, 1]] - vv[vt[:, 0]], vv[vt[:, 2]] - vv[vt[:, 0]])
            n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-12)
            light = np.abs(n @ (np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])))
            shade = plt.cm.Greys(0.25 + 0.6 * light)
            ax.add_collection3d(Poly3DCollection(vv[vt], facecolors=shade, linewidths=0))
            ax.scatter(*np.array([s["xyz"] for s in rep["spawns"]]).T, s=30, c="gold", depthshade=False)
        lo, hi = points.min(axis=0), points.max(axis=0)
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
        ax.set_zlim(lo[2], hi[2])
        ax.set_box_aspect(hi - lo)
        ax.view_init(elev=18, azim=-60)
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_zlabel("z [m]")
    ax = fig.add_subplot(1, 3, 3)
    ax.imshow(imread(str(shot)))
    ax.set_axis_off()
    ax.set_title(f"rviz: UX_1 at {spawn} (world.launch world_file:=...)", fontsize=9)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}; report: {work / 'world' / 'shaft_scan.json'}")


if __name__ == "__main__":
    main()

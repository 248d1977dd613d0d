"""The simulator with a collision mesh of a real scan's size (docs/benchmarks.md, docs/world_from_scan.md).

    python bench/world_size_load.py --triangles 10000000 --out /tmp/big_world

Makes a world like worlds/mine.world whose collision mesh is the generated mine's (worlds/meshes/mine,
made by scripts/setup.sh) subdivided (every triangle into 4, then as many again as reach --triangles:
the same surface, more triangles), then for it (twice: its Bullet BVH built and written to its cache file,
then read from it) and for worlds/mine.world: launches world.launch (1 robot, --sensors, paused,
lockstep), and prints the wall time from the launch to the first odometry, the simulator's resident memory
then, and the real-time factor of --sim-seconds with nothing subscribed. The stages of a load, with their
CPU times: bench/world_load.cpp.
"""

import argparse
import os
import subprocess
import time
from pathlib import Path

import numpy as np

from unexmin import Simulation
from unexmin.worlds.meshes import read_mesh, write_ply

REPO = Path(__file__).resolve().parents[1]


def big_world(out, triangles):
    """A copy of worlds/mine.world in `out` whose collision mesh is subdivided to about `triangles`."""
    import trimesh

    v, t = read_mesh(str(REPO / "worlds" / "meshes" / "mine" / "mine_collision.ply"))
    while len(t) * 4 <= triangles:
        v, t = trimesh.remesh.subdivide(v, t)
    extra = int(max(0, triangles - len(t)) / 3)  # each subdivided triangle adds three
    if extra:
        v, t = trimesh.remesh.subdivide(v, t, face_index=np.arange(min(extra, len(t))))
    out.mkdir(parents=True, exist_ok=True)
    write_ply(out / "mine_collision.ply", v, t, f"mine subdivided to {len(t)} triangles", inward=False)
    (out / "mine_visual.ply").write_bytes((REPO / "worlds" / "meshes" / "mine" / "mine_visual.ply").read_bytes())
    text = (REPO / "worlds" / "mine.world").read_text()
    text = text.replace("meshes/mine/mine_collision.ply", "mine_collision.ply")
    text = text.replace("meshes/mine/mine_visual.ply", "mine_visual.ply")
    world = out / "mine_big.world"
    world.write_text(text)
    return world, len(t)


def simulator_rss_mb():
    pids = subprocess.run(["pgrep", "-f", "devel/lib/unexmin/simulator_node"], capture_output=True, text=True)
    total = 0.0
    for pid in pids.stdout.split():
        status = Path(f"/proc/{pid}/status")
        if status.exists() and "VmRSS:" in status.read_text():
            total = max(total, int(status.read_text().split("VmRSS:")[1].split()[0]) / 1024)
    return total


def measure(world, sensors, sim_seconds, out):
    launch = out / "world_size.launch"
    launch.write_text(
        '<launch><include file="$(find unexmin)/launch/world.launch">'
        f'<arg name="world_file" value="{world}"/><arg name="robots" value="1"/>'
        f'<arg name="realtime" value="false"/><arg name="paused" value="true"/><arg name="sensors" value="{sensors}"/>'
        "</include></launch>\n"
    )
    t0 = time.monotonic()
    with Simulation.launch(launch_file=launch, log_dir=str(out / "log"), timeout=900.0) as sim:
        ux = sim.robot("UX_1", streams="none")
        sim.step(1)
        ux.odom()
        loaded = time.monotonic() - t0
        rss = simulator_rss_mb()
        w0 = time.monotonic()
        sim.run_for(sim_seconds)
        wall = time.monotonic() - w0
    return loaded, rss, sim_seconds / wall


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--triangles", type=int, default=10_000_000)
    ap.add_argument("--sensors", default="all", help="the sensors:= launch argument (default all)")
    ap.add_argument("--sim-seconds", type=float, default=5.0)
    ap.add_argument("--out", default="/tmp/big_world")
    args = ap.parse_args()
    out = Path(args.out)
    world, count = big_world(out, args.triangles)
    cache = out / "mine_collision.ply.bvh"  # Bullet's BVH cache (docs/worlds.md, "Large meshes")
    if cache.exists():
        cache.unlink()
    for label, path in (
        (f"{count:,} collision triangles, BVH built and cached", world),
        (f"{count:,} collision triangles, BVH from the cache", world),
        ("worlds/mine.world", REPO / "worlds" / "mine.world"),
    ):
        load = os.getloadavg()[0]
        loaded, rss, rtf = measure(path, args.sensors, args.sim_seconds, out)
        print(
            f"{label}: launch to first odometry {loaded:.1f} s, simulator RSS {rss:,.0f} MB, "
            f"RTF {rtf:.1f} over {args.sim_seconds} s of sim (sensors {args.sensors}, nothing subscribed); "
            f"load average {load:.1f} before, {os.getloadavg()[0]:.1f} after",
            flush=True,
        )


if __name__ == "__main__":
    main()

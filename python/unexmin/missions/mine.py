"""The main job: a headless, lockstep mapping survey of the flooded mine (docs/mapping.md, "The mission").

    python -m unexmin.missions.mine --out DIR [--seed N] [--gallery M] [--resolution M]
                                    [--visibility none|low|medium|high] [--world-file FILE] [--snapshot S]

Launches the mine world (lockstep, paused) with the mapper on, records a bag (odometry, M3 scans, SLS
clouds, the mapper's stats), and flies UX_1 along the survey plan of unexmin.missions.survey (read from the
mine generator's layout: a helix down the entry shaft, then the first level's gallery out and back, turning)
with a tracking controller on ground-truth odometry (thesis allocation, eq. 5.12). Every --snapshot seconds
of sim time the mapper saves its map (snapshots/); at the end the world gets SIGINT (the mapper saves its map)
and the map and the snapshots are scored against the mine's collision mesh (unexmin.map_quality). Leaves in
DIR: mine_mission.bag, mine_map.bt, trajectory.csv, map_quality.json, map_quality.png, mission_map.png,
coverage.png, summary.json, snapshots/, logs/.
"""

import math
import os
import subprocess
import sys
import time

import numpy as np

from unexmin.control.allocation import ThrusterAllocator
from unexmin.geometry import yaw_of
from unexmin.missions.common import mission_parser, recorder_connected, wait_until_written, write_summary
from unexmin.missions.survey import Reference, mine_layout, options_for, plan, track
from unexmin.scripting.launcher import WorldProcess, stop_process_group, wait_for

ROBOT = "UX_1"
SPEED = 0.4  # [m/s] cruise speed
TOLERANCE = 0.5  # [m] a waypoint is reached within this distance
CONTROL_DT = 0.1  # [s] sim time between controller updates
SLS_UNITS = 4
# [m] the M3's points farther than this are not marked occupied (the mapper's m3_max_range): beyond it the fan's
# 3-degree beam meets the walls at grazing incidence and a share of its echoes land beside them (docs/mapping.md)
M3_MAX_RANGE = 7.0


def waypoints(gallery_length):
    """A straight path [m, world frame] (the batch missions'): the shaft's axis from the spawn depth down to the
    first level's gallery, then that gallery's centreline (from the mine generator's layout, seed 7)."""
    from unexmin.mine_generator.generator import PRESETS, make_layout, point_on

    layout = make_layout(PRESETS["full"], 7)
    sx, sy = layout.shaft_xy
    gallery = next(t for t in layout.tunnels if t.kind == "gallery")
    poly = np.asarray(gallery.points, dtype=float)
    z0 = poly[0, 2]
    path = [(sx, sy, -2.5), (sx, sy, z0 + 0.3)]
    for x in np.arange(sx + 4.0, sx + gallery_length + 1e-9, 4.0):
        p = point_on(poly, x)
        path.append((float(p[0]), float(p[1]), float(p[2]) + 0.3))
    return path


def controller(pose, twist, target, yaw_target=0.0):
    """Body wrench [X Y Z K M N] (allocation units) towards target: a velocity command along the error
    (SPEED at most), feed-forward for the quadratic drag, proportional on the velocity error; yaw held."""
    p = np.array([pose.position.x, pose.position.y, pose.position.z])
    yaw = yaw_of(pose.orientation)
    c, s = math.cos(yaw), math.sin(yaw)
    err = np.array(target) - p
    dist = float(np.linalg.norm(err))
    v_des = err / dist * min(SPEED, 0.5 * dist) if dist > 1e-6 else np.zeros(3)
    # to the body frame (yaw only; the UX-1 is kept level by its pendulum)
    v_des_b = np.array([c * v_des[0] + s * v_des[1], -s * v_des[0] + c * v_des[1], v_des[2]])
    v_b = np.array([twist.linear.x, twist.linear.y, twist.linear.z])  # odometry twist: child (body) frame
    ff = 10.0 * (v_des_b / 0.4) * np.abs(v_des_b / 0.4)
    force = np.clip(ff + 25.0 * (v_des_b - v_b), -15.0, 15.0)
    yaw_err = math.remainder(yaw_target - yaw, 2 * math.pi)
    n = float(np.clip(3.0 * yaw_err - 4.0 * twist.angular.z, -3.0, 3.0))
    return (float(force[0]), float(force[1]), float(force[2]), 0.0, 0.0, n), dist


def topics():
    return [f"/{ROBOT}/odom", f"/{ROBOT}/m3/scan", "/mapper/stats"] + [
        f"/{ROBOT}/sls_{i}/points" for i in range(SLS_UNITS)
    ]


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


def run(
    out,
    seed=0,
    gallery=40.0,
    resolution=0.1,
    time_limit=None,
    visibility=None,
    world_file=None,
    snapshot_every=90.0,
):
    from unexmin.scripting.simulation import Simulation
    from unexmin.worlds.files import world_path
    from unexmin.worlds.schema import read_world

    out = os.path.abspath(out)
    world_file = os.path.abspath(world_file) if world_file else world_path("mine")
    log_dir = os.path.join(out, "logs")
    snap_dir = os.path.join(out, "snapshots")
    os.makedirs(log_dir, exist_ok=True)
    os.makedirs(snap_dir, exist_ok=True)
    bag = os.path.join(out, "mine_mission.bag")
    map_path = os.path.join(out, "mine_map.bt")
    for stale in [bag, map_path] + [os.path.join(snap_dir, f) for f in os.listdir(snap_dir)]:
        if os.path.exists(stale):
            os.remove(stale)
    layout, preset = mine_layout(world_file)
    spawn = layout.spawns[0]
    level = visibility or (read_world(world_file).get("visibility") or {}).get("level", "none")
    options = options_for(level, sum(amplitude for _, amplitude in preset.octaves), gallery)
    frames, durations = plan(layout, preset, (spawn[0], spawn[1], spawn[2], 0.0), options)
    reference = Reference(frames, durations)
    # [s, sim] the plan and half again for the robot to catch up
    time_limit = time_limit if time_limit is not None else 1.5 * reference.duration + 60.0
    extra = [
        "mapping:=true",
        f"map_file:={map_path}",
        f"map_resolution:={resolution}",
        f"map_m3_max_range:={M3_MAX_RANGE}",
        f"world_file:={world_file}",
    ]
    if visibility:
        extra.append(f"visibility:={visibility}")
    wall0 = time.monotonic()
    world = WorldProcess(
        world="mine", robots=1, seed=seed, realtime=False, paused=True, log_dir=log_dir, extra_args=extra
    )
    recorder = log = sim = stats_sub = None
    stats = {}
    legs = []
    snapshots = []
    try:
        sim = Simulation(timeout=120.0, world=world, node_name="unexmin_mine_mission")
        import rosgraph
        import rospy

        from unexmin.msg import MapperStats
        from unexmin.srv import SaveMap

        stats_sub = rospy.Subscriber("/mapper/stats", MapperStats, lambda m: stats.update(last=m), queue_size=10)
        wait_for(lambda: "last" in stats, 120.0, "the mapper's /mapper/stats")
        rospy.wait_for_service("/mapper/save_map", 60.0)
        save_map = rospy.ServiceProxy("/mapper/save_map", SaveMap)
        ux = sim.robot(ROBOT)
        log = open(os.path.join(log_dir, "rosbag_record.log"), "w")
        recorder = subprocess.Popen(
            ["rosbag", "record", "--tcpnodelay", "-O", bag, *topics()],
            stdout=log,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
        master = rosgraph.Master(rospy.get_name())
        wait_for(
            lambda: recorder_connected(master, ("/simulator",), [f"/{ROBOT}/odom", f"/{ROBOT}/m3/scan"]),
            30.0,
            "rosbag record to connect",
        )
        allocator = ThrusterAllocator()
        sim.step(1)
        steps = max(1, round(CONTROL_DT * sim.physics_rate))

        def mapper_caught_up(timeout):
            expected = int(round(sim.time * 40.0)) + int(round(sim.time * 10.0)) * SLS_UNITS
            wait_for(
                lambda: stats["last"].clouds_inserted + stats["last"].clouds_dropped >= stats["last"].clouds_received
                and stats["last"].pending == 0
                and stats["last"].clouds_received >= expected - 5 * (1 + SLS_UNITS),
                timeout,
                "the mapper to insert every cloud",
            )
            return expected

        def snapshot():
            try:
                mapper_caught_up(60.0)
            except TimeoutError as e:
                print(f"warning: {e}")
            path = os.path.join(snap_dir, f"map_{sim.time:07.1f}.bt")
            if save_map(path=path, robot="").success:
                snapshots.append((sim.time, path))

        sim_wall0 = time.monotonic()
        print(f"{'leg':<10}{'t [s]':>8}{'x [m]':>9}{'y [m]':>9}{'z [m]':>9}{'clouds':>9}{'occupied':>10}{'lag [s]':>9}")
        progress, next_frame, next_snapshot, held, pendulum = 0.0, 1, snapshot_every, 0.0, 0.0
        while progress < reference.duration and sim.time <= time_limit:
            odom = ux.odom()
            ref, rate = reference(progress)
            wrench, dist, yaw_err = track(odom.pose.pose, odom.twist.twist, ref, rate)
            ux.thrusts(allocator.allocate(wrench)[0])
            if ref[4] != pendulum:
                pendulum = float(ref[4])
                ux.pendulum(pendulum)
            sim.step(steps)
            # the reference waits for the robot when it lags (a pull, not a chase)
            if dist < 0.6 and abs(yaw_err) < 0.6:
                progress += steps / sim.physics_rate
            else:
                held += steps / sim.physics_rate
            if next_frame < len(reference.t) and progress >= reference.t[next_frame]:
                next_frame = int(np.searchsorted(reference.t, progress, side="right"))
                if next_frame % 40 == 0 or next_frame >= len(reference.t):
                    p, m = ux.odom().pose.pose.position, stats["last"]
                    legs.append({"frame": next_frame - 1, "t": sim.time, "held_s": round(held, 1)})
                    print(
                        f"{next_frame - 1:<10}{sim.time:8.1f}{p.x:9.2f}{p.y:9.2f}{p.z:9.2f}{m.clouds_inserted:9d}"
                        f"{m.occupied_leaves:10d}{held:9.1f}",
                        flush=True,
                    )
            if sim.time >= next_snapshot:
                snapshot()
                next_snapshot += snapshot_every
        if sim.time > time_limit:
            print(f"time limit {time_limit:.0f} s of sim time reached")
        ux.thrusts([0.0] * 8)
        ux.pendulum(0.0)
        sim.run_for(1.0)  # the clouds of the last step find their tf
        sim_time, sim_wall = sim.time, time.monotonic() - sim_wall0
        # Every cloud the simulator published reached the map: M3 at 40 Hz, each SLS unit at 10 Hz.
        try:
            expected = mapper_caught_up(60.0)
        except TimeoutError as e:
            expected = int(round(sim_time * 40.0)) + int(round(sim_time * 10.0)) * SLS_UNITS
            print(f"warning: {e}")
        final = stats["last"]
        wait_until_written(bag + ".active")
    finally:
        if recorder is not None:
            stop_process_group(recorder, 20.0)
            log.close()
        if stats_sub is not None:
            stats_sub.unregister()
        # This script's topics go first, while the master is up (no "unable to communicate" at exit), then the
        # world gets SIGINT: the mapper saves mine_map.bt.
        if sim is not None:
            sim.close(30.0)
        else:
            world.close(30.0)
    stepping_done = time.monotonic() - wall0
    if not os.path.exists(map_path):
        raise RuntimeError(f"the mapper did not save {map_path}: see {log_dir}")

    from unexmin.map_quality import read_trajectory, write_trajectory
    from unexmin.map_quality import run as quality

    traj = read_trajectory(bag)
    write_trajectory(os.path.join(out, "trajectory.csv"), traj)

    q = quality(map_path, world_file, out, trajectory=os.path.join(out, "trajectory.csv"))
    coverage = score_snapshots(snapshots, world_file, traj[:, 1:4], q["tau_m"])
    coverage.append(
        {"t": sim_time, "recall": q["recall"], "precision": q["precision"], "occupied_voxels": q["occupied_voxels"]}
    )
    plot_coverage(coverage, q["surface_area_m2"], os.path.join(out, "coverage.png"))
    plot_map(map_path, traj[:, 1:4], os.path.join(out, "mission_map.png"))
    wall = time.monotonic() - wall0
    summary = {
        "world": os.path.splitext(os.path.basename(world_file))[0],
        "world_file": world_file,
        "robot": ROBOT,
        "seed": seed,
        "visibility": visibility or f"world file ({level})",
        "standoff_m": {"shaft": round(options.standoff, 3), "gallery": round(options.gallery_standoff, 3)},
        "m3_max_range_m": M3_MAX_RANGE,
        "resolution_m": resolution,
        "sim_time_s": sim_time,
        "plan_s": round(reference.duration, 1),
        "held_s": round(held, 1),
        "wall_time_s": round(wall, 2),
        "mission_wall_s": round(stepping_done, 2),
        "stepping_wall_s": round(sim_wall, 2),
        "rtf_while_stepping": round(sim_time / sim_wall, 2),
        "load_average_1min": round(os.getloadavg()[0], 2),
        "path_length_m": float(np.linalg.norm(np.diff(traj[:, 1:4], axis=0), axis=1).sum()),
        "start": dict(zip("xyz", traj[0, 1:4].round(3).tolist())),
        "end": dict(zip("xyz", traj[-1, 1:4].round(3).tolist())),
        "plan_completed": bool(progress >= reference.duration),
        "clouds_expected": expected,
        "clouds_received": int(final.clouds_received),
        "clouds_inserted": int(final.clouds_inserted),
        "clouds_dropped": int(final.clouds_dropped),
        "points_inserted": int(final.points_inserted),
        "insert_wall_s": round(final.insert_seconds, 3),
        "map_memory_bytes": int(final.memory_bytes),
        "map_file_bytes": os.path.getsize(map_path),
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
        "legs": legs,
    }
    return write_summary(out, summary)


def main(argv=None):
    parser = mission_parser("python -m unexmin.missions.mine", __doc__.splitlines()[0])
    parser.add_argument("--gallery", type=float, default=40.0, help="metres flown along the gallery (default 40)")
    parser.add_argument("--resolution", type=float, default=0.1, help="map voxel edge [m] (default 0.1)")
    parser.add_argument(
        "--visibility", choices=("none", "low", "medium", "high"), help="water visibility (default: the world file's)"
    )
    parser.add_argument("--world-file", help="a generated mine's world file (default: the shipped mine)")
    parser.add_argument(
        "--snapshot", type=float, default=90.0, help="sim seconds between saved maps for the coverage curve"
    )
    args = parser.parse_args(argv)
    if not args.snapshot > 0:
        parser.error(f"--snapshot {args.snapshot}: expected > 0 s")
    s = run(
        args.out,
        args.seed,
        args.gallery,
        args.resolution,
        visibility=args.visibility,
        world_file=args.world_file,
        snapshot_every=args.snapshot,
    )
    q = s["quality"]
    print(
        f"\nUX_1 surveyed {s['path_length_m']:.0f} m of the mine (shaft helix and gallery; plan "
        f"{'completed' if s['plan_completed'] else 'NOT completed'}, waited {s['held_s']:.0f} s for the robot) in "
        f"{s['sim_time_s']:.0f} s of sim time, {s['wall_time_s']:.0f} s of wall time (RTF "
        f"{s['rtf_while_stepping']:.1f} while stepping)."
    )
    print(
        f"map: {s['clouds_inserted']}/{s['clouds_received']} clouds inserted ({s['clouds_dropped']} dropped, "
        f"{s['clouds_expected']} published), {s['occupied_leaves']} occupied leaves, "
        f"{s['map_memory_bytes'] / 1e6:.1f} MB in memory, {s['map_file_bytes'] / 1e6:.2f} MB .bt"
    )
    print(
        f"quality at tau {q['tau_m']:g} m: precision {q['precision']:.3f}, recall {q['recall']:.3f} "
        f"(over {q['surface_area_m2']:.0f} m2 within range of the path), F-score {q['f_score']:.3f}, "
        f"distance mean {q['mean_distance_m']:.3f} m, 95th percentile {q['p95_distance_m']:.3f} m"
    )
    print(
        f"outputs: {os.path.abspath(args.out)} (mine_mission.bag, mine_map.bt, map_quality.json, "
        f"map_quality.png, mission_map.png, coverage.png, trajectory.csv, summary.json, snapshots/)"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())

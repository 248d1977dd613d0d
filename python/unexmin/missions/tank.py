"""The main job: a headless, lockstep tank mission with a scripted thrust sequence.

    python -m unexmin.missions.tank --out DIR [--seed N]

Launches the tank world (lockstep, paused), records a bag of odometry and thrusts with
``rosbag record``, drives UX_1 through the legs below with the thesis allocation (eq. 5.12) via
``/sim/step`` (deterministic), then reads the bag back with rosbags and reports where the robot
went. Leaves in DIR: mission.bag, trajectory.csv, trajectory.png, summary.json, logs/.
"""

import math
import os
import subprocess
import sys
import time

import numpy as np

from unexmin.control.allocation import ThrusterAllocator
from unexmin.geometry import yaw_of
from unexmin.map_quality.io import read_trajectory, write_trajectory
from unexmin.missions.common import mission_parser, recorder_connected, wait_until_written, write_summary
from unexmin.scripting.launcher import stop_process_group, wait_for

ROBOT = "UX_1"
# (name, body wrench [X Y Z K M N] in allocation units, duration [s])
# The tank is 6 m x 4 m x 3 m: a slow survey around the anchor (about 0.4 m/s, 1.5 km/h).
LEGS = (
    ("surge forward", (10.0, 0, 0, 0, 0, 0), 4.0),
    ("coast", (0, 0, 0, 0, 0, 0), 4.0),
    ("yaw left", (0, 0, 0, 0, 0, 2.0), 2.0),
    ("coast", (0, 0, 0, 0, 0, 0), 3.0),
    ("heave down", (0, 0, -6.0, 0, 0, 0), 3.0),
    ("coast", (0, 0, 0, 0, 0, 0), 4.0),
    ("sway left", (0, 10.0, 0, 0, 0, 0), 3.0),
    ("coast", (0, 0, 0, 0, 0, 0), 4.0),
)
TOPICS = [f"/{ROBOT}/odom"] + [f"/{ROBOT}/thrusters/{i}/{k}" for i in range(8) for k in ("input", "thrust")]


def start_recorder(bag_path, log_dir):
    log = open(os.path.join(log_dir, "rosbag_record.log"), "w")
    proc = subprocess.Popen(
        ["rosbag", "record", "--tcpnodelay", "-O", bag_path, *TOPICS],
        stdout=log,
        stderr=subprocess.STDOUT,
        start_new_session=True,
    )
    return proc, log


def thrust_means(bag_path):
    """The mean |thrust| [N] per thruster over the bag's thrust messages, and their count per thruster."""
    from unexmin.bag import read_messages

    thrust_sum, thrust_n = np.zeros(8), np.zeros(8)
    for topic, _, _, msg in read_messages(bag_path, [t for t in TOPICS if t.endswith("/thrust")]):
        i = int(topic.split("/")[-2])
        thrust_sum[i] += abs(msg.data)
        thrust_n[i] += 1
    return thrust_sum / np.maximum(thrust_n, 1), thrust_n


def plot(traj, legs, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_xy, ax_z) = plt.subplots(1, 2, figsize=(10, 4.5))
    ax_xy.plot(traj[:, 1], traj[:, 2], "b-")
    ax_xy.plot(traj[0, 1], traj[0, 2], "go", label="start")
    ax_xy.plot(traj[-1, 1], traj[-1, 2], "rs", label="end")
    ax_xy.set(xlabel="x [m]", ylabel="y [m]", title="UX_1 in the tank (top view)", aspect="equal")
    ax_xy.legend()
    ax_z.plot(traj[:, 0], traj[:, 3], "b-")
    for t in legs:
        ax_z.axvline(t, color="0.8", lw=0.8)
    ax_z.set(xlabel="sim time [s]", ylabel="z [m]", title="depth (legs marked)")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def run(out, seed):
    from unexmin.scripting.simulation import Simulation

    out = os.path.abspath(out)
    log_dir = os.path.join(out, "logs")
    os.makedirs(log_dir, exist_ok=True)
    bag = os.path.join(out, "mission.bag")
    wall0 = time.monotonic()
    sim = Simulation.launch("tank", robots=1, seed=seed, log_dir=log_dir, node_name="unexmin_mission")
    recorder = log = None
    try:
        import rosgraph
        import rospy

        ux = sim.robot(ROBOT, streams="none")  # rosbag record subscribes what the report needs
        recorder, log = start_recorder(bag, log_dir)
        master = rosgraph.Master(rospy.get_name())
        publishers = ("/simulator", rospy.get_name())  # odometry and thrusts; thruster inputs
        wait_for(lambda: recorder_connected(master, publishers, TOPICS), 30.0, "rosbag record to connect")
        allocator = ThrusterAllocator()
        sim.step(1)
        boundaries = []
        print(f"{'leg':<15}{'t [s]':>8}{'x [m]':>9}{'y [m]':>9}{'z [m]':>9}{'yaw [deg]':>11}")
        for name, wrench, seconds in LEGS:
            thrusts, _ = allocator.allocate(wrench)
            ux.thrusts(thrusts)
            sim.run_for(seconds)
            boundaries.append(sim.time)
            p = ux.odom().pose.pose
            print(
                f"{name:<15}{sim.time:8.2f}{p.position.x:9.3f}{p.position.y:9.3f}{p.position.z:9.3f}"
                f"{math.degrees(yaw_of(p.orientation)):11.1f}"
            )
        sim_time = sim.time
        wait_until_written(bag + ".active")
    finally:
        if recorder is not None:
            stop_process_group(recorder, 20.0)  # rosbag closes the bag on SIGINT
            log.close()
        sim.close()
    wall = time.monotonic() - wall0

    traj = read_trajectory(bag)
    mean_thrust, counts = thrust_means(bag)
    if len(traj) < 2:
        raise RuntimeError(f"{bag}: the bag holds {len(traj)} odometry messages, expected many")
    write_trajectory(os.path.join(out, "trajectory.csv"), traj)
    plot(traj, boundaries, os.path.join(out, "trajectory.png"))
    steps = np.linalg.norm(np.diff(traj[:, 1:4], axis=0), axis=1)
    summary = {
        "world": "tank",
        "robot": ROBOT,
        "seed": seed,
        "sim_time_s": sim_time,
        "wall_time_s": round(wall, 2),
        "start": dict(zip("xyz", traj[0, 1:4].round(4).tolist())),
        "end": dict(zip("xyz", traj[-1, 1:4].round(4).tolist())),
        "net_displacement_m": float(np.linalg.norm(traj[-1, 1:4] - traj[0, 1:4])),
        "path_length_m": float(steps.sum()),
        "max_speed_m_s": float((steps / np.maximum(np.diff(traj[:, 0]), 1e-9)).max()),
        "yaw_change_deg": float(math.degrees(math.remainder(traj[-1, 4] - traj[0, 4], 2 * math.pi))),
        "odometry_messages": int(len(traj)),
        "thrust_messages": [int(c) for c in counts],
        "mean_abs_thrust_N": [round(float(v), 3) for v in mean_thrust],
        "legs": [{"name": n, "wrench": list(w), "seconds": s} for n, w, s in LEGS],
    }
    return write_summary(out, summary)


def main(argv=None):
    parser = mission_parser("python -m unexmin.missions.tank", __doc__.splitlines()[0])
    args = parser.parse_args(argv)
    s = run(args.out, args.seed)
    print(
        f"\nUX_1 went from ({s['start']['x']:.2f}, {s['start']['y']:.2f}, {s['start']['z']:.2f}) "
        f"to ({s['end']['x']:.2f}, {s['end']['y']:.2f}, {s['end']['z']:.2f}) m: "
        f"{s['net_displacement_m']:.2f} m net, {s['path_length_m']:.2f} m of path, "
        f"yaw {s['yaw_change_deg']:+.1f} deg, top speed {s['max_speed_m_s']:.2f} m/s, "
        f"{s['sim_time_s']:.0f} s of sim time in {s['wall_time_s']:.1f} s of wall time."
    )
    print(f"outputs: {os.path.abspath(args.out)} (mission.bag, trajectory.csv, trajectory.png, summary.json)")
    return 0


if __name__ == "__main__":
    sys.exit(main())

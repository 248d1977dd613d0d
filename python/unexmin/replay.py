"""Rosbag mission replay (thesis 6.5): a real robot's motor commands, played into the simulator.

    rosrun unexmin replay_mission worlds/bags/ux1_tank_perturbed.bag --out /tmp/replay
    python -m unexmin.replay BAG --out DIR [--world tank] [--seed 0] [--nav-topic /UX_1/odom] ...

1. The bag is read completely first (rosbags, no roscore; message types are registered from the
   definitions stored in the bag): /ux1/command/motors (ux1_msgs/MotorCommand), the robot's
   pendulum and VBS commands (std_msgs/Float64) if present, and its navigation if present
   (nav_msgs/Odometry, geometry_msgs/PoseStamped or PoseWithCovarianceStamped). A truncated or
   corrupt bag stops here with one error and exit status 2, before any simulator is started.
2. A headless lockstep world is launched (Simulation.launch, its own master). The motor commands
   go through the simulated ESC driver (unexmin.esc_driver_node, run in this process) on
   /ux1/command/motors, exactly as a live robot's would; pendulum and VBS commands go to the robot's
   topics. Every command is applied at its bag time (mission time 0 = the first command) rounded to
   a physics step, and the simulator is advanced with /sim/step between commands, so the replay is
   deterministic and runs as fast as the machine allows (or paced with --pace).
3. The simulated ground-truth pose is sampled every --sample-period seconds and compared with the
   bag's navigation: position error over time, final and RMS error, yaw error. By default both
   trajectories are first expressed in their own start frame (origin at the start position, x along
   the start heading), since the simulated robot starts at the world's spawn pose and the real one
   wherever it was. Plots (XY, XZ, YZ, yaw and error over time, PNG), trajectory.csv and report.json
   are written to --out.

Parameters and report fields: docs/replay.md. Sample bag: worlds/bags/ (worlds/tools/make_sample_bag.py).
"""

import argparse
import json
import math
import os
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from unexmin.bag import BagError, read_messages, topic_types
from unexmin.geometry import quaternion_to_rpy, wrap_angle
from unexmin.topics import ESC_COMMAND_TOPIC

MOTORS_TOPIC = ESC_COMMAND_TOPIC
MOTOR_TYPE = "ux1_msgs/msg/MotorCommand"
FLOAT64_TYPE = "std_msgs/msg/Float64"
NAV_TYPES = ("nav_msgs/msg/Odometry", "geometry_msgs/msg/PoseWithCovarianceStamped", "geometry_msgs/msg/PoseStamped")
TRAJ_COLUMNS = ("t", "x", "y", "z", "roll", "pitch", "yaw")   # [s], [m] world frame, [rad] ZYX Euler


class ReplayError(Exception):
    """A bag or an argument the replay cannot use; the message says which and why."""


def pose_row(t, pose):
    """A TRAJ_COLUMNS row from a geometry_msgs/Pose (rospy or rosbags object)."""
    p, q = pose.position, pose.orientation
    return (t, p.x, p.y, p.z, *quaternion_to_rpy(q.x, q.y, q.z, q.w))


@dataclass
class Mission:
    """What the replay needs from a bag. Times are mission times [s]: bag time minus t0."""

    path: str
    t0: float                                   # bag time [s] of the first command
    motors: list                                # (t, mode, values[8])
    pendulum: list = field(default_factory=list)  # (t, angle [rad])
    vbs: list = field(default_factory=list)       # (t, mass [kg])
    nav: np.ndarray = None                      # rows of TRAJ_COLUMNS, or None
    topics: dict = field(default_factory=dict)  # role -> topic used

    def events(self):
        """Every command in time order: (t, kind, payload), kind 'motors' | 'pendulum' | 'vbs'."""
        ev = [(t, "motors", (mode, values)) for t, mode, values in self.motors]
        ev += [(t, "pendulum", v) for t, v in self.pendulum]
        ev += [(t, "vbs", v) for t, v in self.vbs]
        order = {"motors": 0, "pendulum": 1, "vbs": 2}
        return sorted(ev, key=lambda e: (e[0], order[e[1]]))

    @property
    def duration(self):
        """[s] up to the last command or navigation sample."""
        ends = [self.events()[-1][0]]
        if self.nav is not None and len(self.nav):
            ends.append(float(self.nav[-1, 0]))
        return max(ends)


def pick_topic(types, wanted, accepted, role, required):
    """Topic of the bag for `role`: `wanted` if given (it must exist with one of the `accepted` types),
    else the bag's only topic of those types; None when absent and not `required`.
    types: {topic: message type} of the bag. Raises ReplayError naming the role and the bag's topics."""
    listing = ", ".join(f"{t} [{m}]" for t, m in sorted(types.items())) or "none"
    if wanted:
        if wanted not in types:
            if required:
                raise ReplayError(f"no topic {wanted} in the bag (topics: {listing})")
            return None
        if types[wanted] not in accepted:
            raise ReplayError(f"topic {wanted} is {types[wanted]}, expected {' or '.join(accepted)} for the {role}")
        return wanted
    candidates = sorted(t for t, m in types.items() if m in accepted)
    if len(candidates) == 1:
        return candidates[0]
    if len(candidates) > 1:
        raise ReplayError(f"several {role} topics in the bag ({', '.join(candidates)}): choose one with "
                          f"--{role.split()[0]}-topic")
    if required:
        raise ReplayError(f"no {role} ({' or '.join(accepted)}) in the bag (topics: {listing})")
    return None


def read_bag(path, robot="UX_1", motors_topic=MOTORS_TOPIC, pendulum_topic=None, vbs_topic=None, nav_topic=None):
    """Read a robot bag into a Mission. Raises ReplayError (one message) for a missing, truncated or
    corrupt bag or one without motor commands.

    Topic defaults: motors_topic (else the bag's only MotorCommand topic); /<robot>/pendulum and
    /<robot>/vbs; navigation /<robot>/odom, else the bag's only Odometry/Pose topic.
    """
    try:
        types = topic_types(path)
        chosen = {
            # The default topic falls back to the bag's only MotorCommand topic; an explicit one must exist.
            "motors": pick_topic(types, None if motors_topic == MOTORS_TOPIC and motors_topic not in types
                                 else motors_topic, (MOTOR_TYPE,), "motors command", True),
            "pendulum": pick_topic(types, pendulum_topic or f"/{robot}/pendulum", (FLOAT64_TYPE,),
                                   "pendulum command", bool(pendulum_topic)),
            "vbs": pick_topic(types, vbs_topic or f"/{robot}/vbs", (FLOAT64_TYPE,), "vbs command", bool(vbs_topic)),
            "nav": pick_topic(types, nav_topic or (f"/{robot}/odom" if f"/{robot}/odom" in types else None),
                              NAV_TYPES, "nav topic", bool(nav_topic)),
        }
        role_of = {t: r for r, t in chosen.items() if t}
        messages = read_messages(path, set(role_of))
    except BagError as e:
        raise ReplayError(str(e)) from None
    rows = {"motors": [], "pendulum": [], "vbs": [], "nav": []}
    for topic, msgtype, t, msg in messages:
        role = role_of[topic]
        if role == "motors":
            rows["motors"].append((t, int(msg.mode), tuple(float(v) for v in msg.values)))
        elif role in ("pendulum", "vbs"):
            rows[role].append((t, float(msg.data)))
        else:
            pose = msg.pose if msgtype == "geometry_msgs/msg/PoseStamped" else msg.pose.pose
            rows["nav"].append(pose_row(t, pose))
    if not rows["motors"]:
        raise ReplayError(f"{path}: no messages on {chosen['motors']}")
    commands = rows["motors"] + [(t, 0, ()) for t, _ in rows["pendulum"] + rows["vbs"]]
    t0 = min(t for t, _, _ in commands)
    nav = None
    if rows["nav"]:
        nav = np.array(rows["nav"], dtype=float)
        nav = nav[np.argsort(nav[:, 0], kind="stable")]
        nav[:, 0] -= t0
        nav = nav[nav[:, 0] >= -1e-9]
        if len(nav) < 2:
            nav = None
    return Mission(
        path=str(path), t0=t0,
        motors=[(t - t0, m, v) for t, m, v in rows["motors"]],
        pendulum=[(t - t0, v) for t, v in rows["pendulum"]],
        vbs=[(t - t0, v) for t, v in rows["vbs"]],
        nav=nav, topics={k: v for k, v in chosen.items() if v})


class LockstepRunner:
    """Plays timed commands into a paused simulator with /sim/step and samples the robot's pose.

    Motor commands are published on motors_topic and converted by an ESC driver running in this
    process (the same class as nodes/esc_driver). The runner waits until the driver has published
    the thrusts and tells the Simulation how many command messages went out, so the next /sim/step
    waits for them: every command applies from the physics step after its time, deterministically.
    Mission time 0 is LEAD seconds after the (re)start, so the first sample is the start pose.
    """

    LEAD = 0.02  # [s] between the reset and mission time 0

    def __init__(self, sim, robot="UX_1", motors_topic=MOTORS_TOPIC, sample_period=0.1, timeout=30.0):
        from ux1_msgs.msg import MotorCommand

        from unexmin.esc_driver_node import EscDriverNode
        from unexmin.launcher import wait_for
        from unexmin.topics import sync_publisher

        self.sim, self.timeout, self.MotorCommand = sim, timeout, MotorCommand
        self.rate = sim.physics_rate
        self.lead_steps = max(1, round(self.LEAD * self.rate))
        self.sample_steps = round(sample_period * self.rate)
        if self.sample_steps < 1 or abs(self.sample_steps - sample_period * self.rate) > 1e-6:
            raise ReplayError(f"--sample-period {sample_period} s must be a whole number of physics steps "
                              f"({1.0 / self.rate} s)")
        self.ux = sim.robot(robot)
        self.driver = EscDriverNode(robot=robot, motor_topic=motors_topic, announce=False)
        self.pub = sync_publisher(motors_topic, MotorCommand)
        wait_for(lambda: self.pub.get_num_connections() > 0
                 and all(p.get_num_connections() > 0 for p in self.driver.thruster_pubs),
                 timeout, f"the ESC driver and the simulator to connect on {motors_topic} and /{robot}/thrusters")
        self.sent = 0

    def _apply(self, kind, payload, t_sim):
        import rospy

        if kind == "motors":
            mode, values = payload
            msg = self.MotorCommand()
            msg.header.stamp = rospy.Time.from_sec(t_sim)
            msg.mode = mode
            msg.values = list(values)
            published = self.driver.published
            self.pub.publish(msg)
            self.sent += 1
            if not self.driver.wait_processed(self.sent, self.timeout):
                raise RuntimeError(f"the ESC driver did not handle motor command {self.sent} within {self.timeout} s")
            # The driver publishes from this node: the next /sim/step waits until these have arrived.
            self.sim.note_published(self.driver.published - published)
        elif kind == "pendulum":
            self.ux.pendulum(payload)
        else:
            self.ux.vbs(payload)

    def run(self, events, duration, seed=0, progress=None, pace=0.0, on_sample=None):
        """Reset the world (seed), play `events` [(t, kind, payload)] and sample until `duration` [s].

        progress: callable(dt [s]) told how much mission time each chunk advanced (tqdm.update).
        pace: 0 = as fast as possible; f > 0 keeps sim time <= f x wall time.
        on_sample: callable(t [s], nav_msgs/Odometry) called for every sample (e.g. to record a bag).
        Returns the simulated trajectory, rows of TRAJ_COLUMNS at mission times k * sample_period.
        """
        self.sim.pause()
        self.sim.reset(seed=seed)
        lead = self.lead_steps
        samples = list(range(lead, lead + int(math.floor(duration * self.rate / self.sample_steps + 1e-9))
                             * self.sample_steps + 1, self.sample_steps))
        timed = [(lead + round(t * self.rate), 1, kind, payload) for t, kind, payload in events
                 if t <= duration + 1e-9]
        timed += [(s, 0, "sample", None) for s in samples]
        timed.sort(key=lambda e: (e[0], e[1]))       # at one step: sample the state, then apply commands
        traj, step, wall0 = [], 0, time.monotonic()
        for target, _, kind, payload in timed:
            if target > step:
                self.sim.step(target - step)
                if progress and target - max(step, lead) > 0:
                    progress((target - max(step, lead)) / self.rate)
                step = target
                if pace > 0:
                    ahead = (step / self.rate) / pace - (time.monotonic() - wall0)
                    if ahead > 0:
                        time.sleep(ahead)
            if kind == "sample":
                odom = self.ux.odom()  # the state at the last step call's time
                traj.append(pose_row((step - lead) / self.rate, odom.pose.pose))
                if on_sample:
                    on_sample(traj[-1][0], odom)
            else:
                self._apply(kind, payload, step / self.rate)
        return np.array(traj, dtype=float).reshape(-1, len(TRAJ_COLUMNS))


def to_start_frame(traj, t_ref):
    """Trajectory in its own start frame: origin at the position at t_ref [s], x along the heading at
    t_ref, z unchanged in direction; yaw relative to the yaw at t_ref (unwrapped)."""
    out = traj.copy()
    t = traj[:, 0]
    yaw = np.unwrap(traj[:, 6])
    p_ref = [np.interp(t_ref, t, traj[:, i]) for i in (1, 2, 3)]
    yaw_ref = np.interp(t_ref, t, yaw)
    c, s = math.cos(yaw_ref), math.sin(yaw_ref)
    dx, dy = traj[:, 1] - p_ref[0], traj[:, 2] - p_ref[1]
    out[:, 1], out[:, 2] = c * dx + s * dy, -s * dx + c * dy
    out[:, 3] = traj[:, 3] - p_ref[2]
    out[:, 6] = yaw - yaw_ref
    return out


def path_length(traj):
    return float(np.sum(np.linalg.norm(np.diff(traj[:, 1:4], axis=0), axis=1))) if len(traj) > 1 else 0.0


def compare(sim_traj, nav, align=True):
    """Errors of the simulated trajectory against the bag's navigation.

    Both are rows of TRAJ_COLUMNS at mission times. The comparison uses the simulated samples inside
    the navigation's time span, with the navigation interpolated linearly (yaw unwrapped). With
    align, both are first put in their own start frame at the first common time.
    Returns (metrics dict, sim rows used, navigation rows at the same times).
    """
    t_lo, t_hi = max(nav[0, 0], sim_traj[0, 0]), min(nav[-1, 0], sim_traj[-1, 0])
    keep = (sim_traj[:, 0] >= t_lo - 1e-9) & (sim_traj[:, 0] <= t_hi + 1e-9)
    if keep.sum() < 2:
        raise ReplayError(f"the navigation ({nav[0, 0]:.2f}..{nav[-1, 0]:.2f} s) and the simulated trajectory "
                          f"({sim_traj[0, 0]:.2f}..{sim_traj[-1, 0]:.2f} s) share fewer than 2 samples")
    s = sim_traj[keep]
    n = np.empty_like(s)
    n[:, 0] = s[:, 0]
    yaw_nav = np.unwrap(nav[:, 6])
    for i in range(1, 7):
        n[:, i] = np.interp(s[:, 0], nav[:, 0], yaw_nav if i == 6 else nav[:, i])
    if align:
        s, n = to_start_frame(s, s[0, 0]), to_start_frame(n, n[0, 0])
    else:
        s = s.copy()
        s[:, 6] = np.unwrap(s[:, 6])
    err = np.linalg.norm(s[:, 1:4] - n[:, 1:4], axis=1)
    yaw_err = np.degrees(wrap_angle(s[:, 6] - n[:, 6]))
    metrics = {
        "aligned_to_start_frame": bool(align),
        "samples": int(len(s)),
        "t_start_s": float(s[0, 0]),
        "t_end_s": float(s[-1, 0]),
        "position_error_m": {"final": float(err[-1]), "max": float(err.max()), "mean": float(err.mean()),
                             "rms": float(np.sqrt(np.mean(err ** 2)))},
        "final_error_xyz_m": [float(v) for v in (s[-1, 1:4] - n[-1, 1:4])],
        "yaw_error_deg": {"final": float(yaw_err[-1]), "max_abs": float(np.abs(yaw_err).max()),
                          "rms": float(np.sqrt(np.mean(yaw_err ** 2)))},
        "bag_path_length_m": path_length(n),
        "sim_path_length_m": path_length(s),
        "bag_displacement_m": float(np.linalg.norm(n[-1, 1:4] - n[0, 1:4])),
        "sim_displacement_m": float(np.linalg.norm(s[-1, 1:4] - s[0, 1:4])),
    }
    return metrics, s, n


def write_plots(out_dir, sim, nav=None, title=""):
    """PNG plots (thesis figures 6.16-6.19): xy.png, xz.png, yz.png, yaw.png and, with a navigation,
    error.png. sim / nav: rows of TRAJ_COLUMNS (already in the compared frame). Returns file names."""
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
    cols = [f"sim_{c}" for c in TRAJ_COLUMNS[1:]]
    data = [sim]
    if nav is not None:
        cols += [f"bag_{c}" for c in TRAJ_COLUMNS[1:]]
        data.append(nav[:, 1:])
    np.savetxt(path, np.hstack(data), delimiter=",", header=",".join(["t"] + cols), comments="", fmt="%.6f")


def replay(mission, out_dir, world="tank", seed=0, robot="UX_1", sample_period=0.1, duration=None, align=True,
           pace=0.0, progress=True, connect=False, timeout=60.0):
    """Run the replay of `mission` (from read_bag) and write the report; returns the report dict."""
    from unexmin.simulation import Simulation

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    duration = mission.duration if duration is None else float(duration)
    if not (math.isfinite(duration) and duration > 0):
        raise ReplayError(f"--duration {duration}: expected a positive number of seconds")
    wall0 = time.monotonic()
    sim = Simulation(timeout=timeout) if connect else Simulation.launch(
        world, robots=1, seed=seed, log_dir=str(out_dir / "ros_log"), timeout=timeout)
    bar = None
    try:
        runner = LockstepRunner(sim, robot, mission.topics["motors"], sample_period, timeout=timeout)
        if progress:
            from tqdm import tqdm

            bar = tqdm(total=round(duration, 3), unit="sim s", desc="replay", leave=False,
                       bar_format="{desc}: {percentage:3.0f}%|{bar}| {n:.1f}/{total:.1f} sim s [{elapsed}<{remaining}]")
        sim_start = time.monotonic()
        traj = runner.run(mission.events(), duration, seed=seed, progress=bar.update if bar else None, pace=pace)
        sim_wall = time.monotonic() - sim_start
    finally:
        if bar is not None:
            bar.close()
        sim.close()
    report = {
        "bag": str(Path(mission.path).resolve()),
        "topics": mission.topics,
        "messages": {"motors": len(mission.motors), "pendulum": len(mission.pendulum), "vbs": len(mission.vbs),
                     "navigation": 0 if mission.nav is None else int(len(mission.nav))},
        "world": "(running simulator)" if connect else world, "robot": robot, "seed": seed,
        "physics_rate_hz": sim.physics_rate, "sample_period_s": sample_period,
        "mission_duration_s": duration,
        "replay_wall_time_s": round(sim_wall, 3), "total_wall_time_s": round(time.monotonic() - wall0, 3),
        "speed_vs_real_time": round(duration / sim_wall, 2) if sim_wall > 0 else None,
        "errors": None,
    }
    nav_c = None
    sim_c = traj.copy()
    if mission.nav is not None:
        report["errors"], sim_c, nav_c = compare(traj, mission.nav, align)
    elif align:
        sim_c = to_start_frame(traj, traj[0, 0])
    name = Path(mission.path).stem
    report["plots"] = write_plots(out_dir, sim_c, nav_c, title=name)
    write_csv(out_dir / "trajectory.csv", sim_c, nav_c)
    report["trajectory_csv"] = "trajectory.csv"
    with open(out_dir / "report.json", "w") as f:
        json.dump(report, f, indent=2)
    return report


def summary(report):
    """Human-readable lines of a report."""
    lines = [f"replayed {report['mission_duration_s']:.1f} s of {report['bag']} "
             f"in {report['replay_wall_time_s']:.1f} s "
             f"({report['speed_vs_real_time']}x real time), {report['messages']['motors']} motor commands"]
    e = report["errors"]
    if e:
        p, y = e["position_error_m"], e["yaw_error_deg"]
        lines.append(f"position error: final {p['final']:.3f} m, rms {p['rms']:.3f} m, max {p['max']:.3f} m "
                     f"(bag path {e['bag_path_length_m']:.2f} m)")
        lines.append(f"yaw error: final {y['final']:+.1f} deg, rms {y['rms']:.1f} deg, max {y['max_abs']:.1f} deg")
    else:
        lines.append("no navigation in the bag: simulated trajectory only")
    return lines


def _ensure_rosbags(argv):
    """rosbags lives in the project's venv; catkin's wrapper of nodes/replay_mission runs /usr/bin/python3.
    Re-run this command with the venv's interpreter ($UNEXMIN_VENV, set by scripts/env.sh) if needed."""
    try:
        import rosbags  # noqa: F401
        return
    except ImportError:
        pass
    venv_python = Path(os.environ.get("UNEXMIN_VENV", "/nonexistent")) / "bin" / "python3"
    if venv_python.exists() and os.environ.get("UNEXMIN_REPLAY_REEXEC") != "1":
        os.environ["UNEXMIN_REPLAY_REEXEC"] = "1"
        os.execv(str(venv_python), [str(venv_python), "-m", "unexmin.replay", *argv])
    raise ReplayError(f"the Python package rosbags is not importable by {sys.executable}: source scripts/env.sh "
                      "(it sets UNEXMIN_VENV) or run `<venv>/bin/python -m unexmin.replay`")


def main(argv=None):
    """Command line of nodes/replay_mission and `python -m unexmin.replay`. Exit 0, 2 (bad bag or
    argument), 1 (simulator failure)."""
    argv = sys.argv[1:] if argv is None else list(argv)
    ap = argparse.ArgumentParser(prog="replay_mission", description=__doc__.split("\n\n")[0])
    ap.add_argument("bag", help="ROS 1 bag of the real robot")
    ap.add_argument("--out", default="replay_out", help="output folder for report.json, plots, trajectory.csv")
    ap.add_argument("--world", default="tank", help="world to launch: <world>_world.launch (default tank)")
    ap.add_argument("--connect", action="store_true", help="use the running simulator (ROS_MASTER_URI) instead "
                    "of launching one; it is reset, and must be paused")
    ap.add_argument("--robot", default="UX_1", help="simulated robot that replays the bag (default UX_1)")
    ap.add_argument("--seed", type=int, default=0, help="simulator seed (default 0)")
    ap.add_argument("--motors-topic", default=MOTORS_TOPIC, help=f"MotorCommand topic (default {MOTORS_TOPIC})")
    ap.add_argument("--pendulum-topic", help="Float64 pendulum command topic (default /<robot>/pendulum if present)")
    ap.add_argument("--vbs-topic", help="Float64 VBS command topic (default /<robot>/vbs if present)")
    ap.add_argument("--nav-topic", help="navigation topic (default /<robot>/odom, else the only Odometry/Pose one)")
    ap.add_argument("--sample-period", type=float, default=0.1, help="[s] trajectory sampling (default 0.1)")
    ap.add_argument("--duration", type=float, help="[s] mission time to replay (default: the whole bag)")
    ap.add_argument("--no-align", action="store_true", help="compare world coordinates, not start frames")
    ap.add_argument("--pace", type=float, default=0.0, help="0 = as fast as possible (default); 1 = real time")
    ap.add_argument("--quiet", action="store_true", help="no progress bar")
    args = ap.parse_args(argv)
    try:
        _ensure_rosbags(argv)
        if args.pace < 0 or not math.isfinite(args.pace):
            raise ReplayError(f"--pace {args.pace}: expected >= 0")
        if not (args.sample_period > 0 and math.isfinite(args.sample_period)):
            raise ReplayError(f"--sample-period {args.sample_period}: expected a positive number of seconds")
        mission = read_bag(args.bag, args.robot, args.motors_topic, args.pendulum_topic, args.vbs_topic,
                           args.nav_topic)
        report = replay(mission, args.out, args.world, args.seed, args.robot, args.sample_period, args.duration,
                        not args.no_align, args.pace, not args.quiet, args.connect)
    except ReplayError as e:
        print(f"replay_mission: error: {e}", file=sys.stderr)
        return 2
    except (RuntimeError, TimeoutError) as e:
        print(f"replay_mission: simulator failure: {e}", file=sys.stderr)
        return 1
    for line in summary(report):
        print(line)
    print(f"report: {Path(args.out).resolve() / 'report.json'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""The replay as a command and a function: replay() runs it and writes the report; main() is the
command line of nodes/replay_mission and `python -m unexmin.replay` (docs/replay.md)."""

import argparse
import json
import math
import os
import sys
import time
from pathlib import Path

from unexmin.replay.bag_io import MOTORS_TOPIC, read_bag
from unexmin.replay.errors import ReplayError, print_summary
from unexmin.replay.metrics import compare, to_start_frame
from unexmin.replay.plots import write_csv, write_plots

DESCRIPTION = "Rosbag mission replay (thesis 6.5): a real robot's motor commands, played into the simulator."


def replay(
    mission,
    out_dir,
    world="tank",
    seed=0,
    robot="UX_1",
    sample_period=0.1,
    duration=None,
    align=True,
    pace=0.0,
    progress=True,
    connect=False,
    timeout=60.0,
    overrides=None,
    backend=None,
):
    """Run the replay of `mission` (from read_bag) and write the report, plots and CSV into out_dir;
    returns the report dict (fields: docs/replay.md). duration [s]: mission time to replay (default the
    bag's); sample_period [s]; pace [x real time], 0 = as fast as possible; timeout [s] of wall time;
    overrides: xacro overrides file of the replaying robot (e.g. from unexmin.identify); that robot is
    then spawned at the bag's first roll and pitch (the real robot's trim), not level. backend: "core" (the
    engine in-process, no ROS; the default without `connect`) or "ros" (a launched world; `connect` needs it)."""
    from unexmin.replay.runner import CoreRunner, LockstepRunner
    from unexmin.scripting.simulation import Simulation

    backend = backend or ("ros" if connect else "core")
    if backend not in ("ros", "core"):
        raise ReplayError(f"--backend {backend}: expected ros or core")
    if connect and backend == "core":
        raise ReplayError("--connect joins a running ROS simulator: not with --backend core")

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    duration = mission.duration if duration is None else float(duration)
    if not (math.isfinite(duration) and duration > 0):
        raise ReplayError(f"--duration {duration}: expected a positive number of seconds")
    wall0 = time.monotonic()
    launch_file = None
    if overrides:
        if connect:
            raise ReplayError("--overrides needs a simulator of its own: not with --connect")
        if not Path(overrides).is_file():
            raise ReplayError(f"--overrides {overrides}: no such file")
        from unexmin.worlds.spawn import world_launch_file

        roll_pitch = None if mission.nav is None else (float(mission.nav[0, 4]), float(mission.nav[0, 5]))
        try:
            launch_file = world_launch_file(out_dir, world, robot, roll_pitch, overrides=overrides, seed=seed)
        except (FileNotFoundError, ValueError) as e:
            raise ReplayError(str(e)) from None
    if connect:
        sim = Simulation(timeout=timeout)
    elif backend == "core":
        world_file = world if launch_file is None else str(out_dir / f"{world}_spawn.world")
        overrides_map = {robot: str(Path(overrides).resolve())} if overrides else None
        sim = Simulation.launch(world_file, robots=1, seed=seed, backend="core", overrides=overrides_map)
    else:
        sim = Simulation.launch(
            world, robots=1, seed=seed, log_dir=str(out_dir / "ros_log"), timeout=timeout, launch_file=launch_file
        )
    bar = None
    with sim:
        if robot not in sim.robots:
            raise ReplayError(f"--robot {robot}: the simulator has no such robot (robots: {', '.join(sim.robots)})")
        runner = (CoreRunner if backend == "core" else LockstepRunner)(
            sim, robot, mission.topics["motors"], sample_period, timeout=timeout
        )
        if progress:
            from tqdm import tqdm

            bar = tqdm(
                total=round(duration, 3),
                unit="sim s",
                desc="replay",
                leave=False,
                bar_format="{desc}: {percentage:3.0f}%|{bar}| {n:.1f}/{total:.1f} sim s [{elapsed}<{remaining}]",
            )
        try:
            sim_start = time.monotonic()
            traj = runner.run(mission.events(), duration, seed=seed, progress=bar.update if bar else None, pace=pace)
            sim_wall = time.monotonic() - sim_start
        finally:
            if bar is not None:
                bar.close()
            runner.close()
    report = {
        "bag": str(Path(mission.path).resolve()),
        "topics": mission.topics,
        "messages": {
            "motors": len(mission.motors),
            "pendulum": len(mission.pendulum),
            "vbs": len(mission.vbs),
            "navigation": 0 if mission.nav is None else int(len(mission.nav)),
        },
        "world": "(running simulator)" if connect else world,
        "robot": robot,
        "seed": seed,
        "backend": backend,
        "overrides": str(Path(overrides).resolve()) if overrides else None,
        "physics_rate_hz": sim.physics_rate,
        "sample_period_s": sample_period,
        "mission_duration_s": duration,
        "replay_wall_time_s": round(sim_wall, 3),
        "total_wall_time_s": round(time.monotonic() - wall0, 3),
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
    lines = [
        f"replayed {report['mission_duration_s']:.1f} s of {report['bag']} "
        f"in {report['replay_wall_time_s']:.1f} s "
        f"({report['speed_vs_real_time']}x real time), {report['messages']['motors']} motor commands"
    ]
    e = report["errors"]
    before = report.get("errors_before")
    if before:
        p, y = before["position_error_m"], before["yaw_error_deg"]
        lines.append(
            f"before (nominal robot): position error final {p['final']:.3f} m, rms {p['rms']:.3f} m; "
            f"yaw rms {y['rms']:.2f} deg"
        )
        lines.append(f"after (--overrides {report['overrides']}):")
    if e:
        p, y = e["position_error_m"], e["yaw_error_deg"]
        lines.append(
            f"position error: final {p['final']:.3f} m, rms {p['rms']:.3f} m, max {p['max']:.3f} m "
            f"(bag path {e['bag_path_length_m']:.2f} m)"
        )
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
    raise ReplayError(
        f"the Python package rosbags is not importable by {sys.executable}: source scripts/env.sh "
        "(it sets UNEXMIN_VENV) or run `<venv>/bin/python -m unexmin.replay`"
    )


def main(argv=None):
    """Command line of nodes/replay_mission and `python -m unexmin.replay`. Exit 0, 2 (bad bag or
    argument), 1 (simulator failure)."""
    argv = sys.argv[1:] if argv is None else list(argv)
    ap = argparse.ArgumentParser(prog="replay_mission", description=DESCRIPTION)
    ap.add_argument("bag", help="ROS 1 bag of the real robot")
    ap.add_argument("--out", default="replay_out", help="output folder for report.json, plots, trajectory.csv")
    ap.add_argument("--world", default="tank", help="world to launch: <world>_world.launch (default tank)")
    ap.add_argument(
        "--connect",
        action="store_true",
        help="use the running simulator (ROS_MASTER_URI) instead of launching one; it is reset, and must be paused",
    )
    ap.add_argument(
        "--backend",
        choices=("core", "ros"),
        help="core: the engine in-process, no ROS (default); ros: a launched ROS world (default with --connect)",
    )
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
    ap.add_argument(
        "--overrides",
        help="xacro overrides of the replaying robot (python -m unexmin.identify writes "
        "one): the bag is replayed with the nominal robot, then with this one, and both errors reported",
    )
    args = ap.parse_args(argv)
    try:
        _ensure_rosbags(argv)
        if args.pace < 0 or not math.isfinite(args.pace):
            raise ReplayError(f"--pace {args.pace}: expected >= 0")
        if not (args.sample_period > 0 and math.isfinite(args.sample_period)):
            raise ReplayError(f"--sample-period {args.sample_period}: expected a positive number of seconds")
        mission = read_bag(args.bag, args.robot, args.motors_topic, args.pendulum_topic, args.vbs_topic, args.nav_topic)
        options = {
            "world": args.world,
            "seed": args.seed,
            "robot": args.robot,
            "sample_period": args.sample_period,
            "duration": args.duration,
            "align": not args.no_align,
            "pace": args.pace,
            "progress": not args.quiet,
            "connect": args.connect,
            "backend": args.backend,
        }
        before = replay(mission, Path(args.out) / "nominal", **options) if args.overrides else None
        report = replay(mission, args.out, overrides=args.overrides, **options)
        if before is not None:
            report["errors_before"] = before["errors"]
            with open(Path(args.out) / "report.json", "w") as f:
                json.dump(report, f, indent=2)
    except ReplayError as e:
        print(f"replay_mission: error: {e}", file=sys.stderr)
        return 2
    except (RuntimeError, TimeoutError) as e:
        print(f"replay_mission: simulator failure: {e}", file=sys.stderr)
        return 1
    return print_summary(summary(report), f"report: {Path(args.out).resolve() / 'report.json'}")

#!/usr/bin/env python3
"""Mine world benchmark: real-time factor with 1, 2 and 3 robots, memory of the simulator, and the
time from launch to the first odometry message (docs/benchmarks.md, "Mine world").

    source scripts/env.sh && python bench/mine_rtf.py [--sim-seconds 120] [--seed 0] [--repeat 3] [--world mine|tank]
                                                      [--sensors all|none|imu,dvl,...]
    python bench/mine_rtf.py --vehicles ux1,bluerov2_heavy,remus100 [--repeat 3] [--sim-seconds 60]   # a mixed team

For each robot count, --repeat times (the summary gives medians), in a fresh process with its own
ROS master:
  * launches `mine_world.launch robots:=N realtime:=false` (lockstep, running), every robot's
    odometry subscribed from the start; first message: wall time from starting roslaunch to the
    first /UX_k/odom of every robot, split into master up, simulator ready (/sim/step offered: world
    and meshes loaded) and first odom; then unsubscribes (a benchmark client would load the cores);
  * pauses it and steps it as fast as it goes through /sim/step, in 10 s chunks (`hold`: commands
    do not time out) before each of which every robot's thrust pattern is re-sent (UX_1 surges into
    the shaft wall, UX_2 sinks down the shaft, UX_3 turns): contacts with the 1.13M-triangle mesh are
    part of the load;
  * RTF: --sim-seconds of sim time divided by the wall time it took;
  * the simulator's CPU use over that span and its resident memory (VmRSS now, VmHWM peak);
  * the topics the simulator publishes under /UX_1 (which sensors existed when the figure was taken).
With --vehicles, one team instead of the 1, 2, 3 UX-1s (mine_world.launch vehicles:=; each vehicle holds a thrust
pattern of its own: the ROV surges, the AUV runs its propeller at 1000 rpm), and the RTF in the simulator's CPU time
(sim seconds over the simulator's CPU seconds) beside the wall-time one.
With --translations, a C++ sink (bench/topic_counter.cpp, built with g++) subscribes to every robot's
m3/points and dvl_water_track from the start, so the simulator builds its M3 and DVL translations and sends
them; the sink's CPU is reported apart, and the share of the translated messages stamped inside the stepped
span that reached it ("delivered", 1.00 = all).
With --subscribe TOPIC@HZ[,TOPIC@HZ...] (e.g. /ROV_1/imaging_sonar/polar@10), the same sink subscribes to those
topics too (alone, without --translations): a sensor whose messages are built only while someone subscribes (the
sonars' images, the cameras' frames) then does its work.
"""

import argparse
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from xmlrpc.client import ServerProxy

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sensors_rtf import run_child  # noqa: E402

from unexmin.vehicles import team_names  # noqa: E402

PATTERNS = {  # thrust per thruster [N], thesis allocation columns (eq. 5.12) scaled
    "UX_1": [10.0, 0.0, -10.0, 0.0, 10.0, 0.0, -10.0, 0.0],  # surge
    "UX_2": [0.0, 10.0, 0.0, 10.0, 0.0, -10.0, 0.0, 10.0],  # heave down (-Z column)
    "UX_3": [-5.0, 0.0, 5.0, 0.0, 5.0, 0.0, -5.0, 0.0],  # yaw
    "ROV_1": [200.0] * 4 + [0.0] * 4,  # surge: T200 pulse offsets [us] on the horizontal thrusters
    "AUV_1": [1000.0],  # propeller [rpm]
}


def proc_status(pid):
    out = {}
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            key, _, value = line.partition(":")
            if key in ("VmRSS", "VmHWM"):
                out[key] = int(value.split()[0]) / 1024.0
    return out


def cpu_seconds(pid):
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


TRANSLATIONS = {"m3/points": 40.0, "dvl_water_track": 8.0}  # [Hz of sim time]: the C++ translations


def parse_subscriptions(text):
    """{topic: rate [Hz]} from "TOPIC@HZ,TOPIC@HZ" (--subscribe); {} for ""."""
    out = {}
    for item in filter(None, text.split(",")):
        topic, sep, hz = item.rpartition("@")
        if not sep or not topic.startswith("/"):
            raise SystemExit(f"--subscribe {item!r}: expected /absolute/topic@rate_hz")
        out[topic] = float(hz)
    return out


def measure(
    robots, sim_seconds, seed, timeout, world_name="mine", sensors="all", translations=False, vehicles="", subscribe=""
):
    t_launch = time.monotonic()
    from unexmin.scripting.launcher import WorldProcess, wait_for

    # Lockstep (realtime:=false), running: the first message comes with the first physics step, as in
    # real time, and the lockstep wall-rate caps on /clock and joint_states apply while stepping.
    team = (f"vehicles:={vehicles}",) if vehicles else ()
    world = WorldProcess(
        world=world_name,
        robots=robots,
        seed=seed,
        realtime=False,
        paused=False,
        extra_args=(f"sensors:={sensors}", *team),
    )
    workdir = tempfile.TemporaryDirectory(prefix="mine_rtf_")
    sink = None
    try:
        import rosgraph
        import rospy
        from nav_msgs.msg import Odometry
        from std_msgs.msg import Float64
        from std_srvs.srv import Empty

        from unexmin.srv import Step
        from unexmin.topics import sync_publisher

        rospy.init_node("mine_bench", anonymous=True, disable_signals=True)
        t_master = time.monotonic()
        names = team_names(vehicles) if vehicles else [f"UX_{i + 1}" for i in range(robots)]
        window = Path(workdir.name) / "window"
        rates = {f"/{n}/{t}": hz for n in names for t, hz in TRANSLATIONS.items()} if translations else {}
        rates.update(parse_subscriptions(subscribe))
        sink_topics = sorted(rates)
        if sink_topics:
            sys.path.insert(0, str(Path(__file__).resolve().parent))
            from sensors_rtf import build_counter, wait_for_sink

            sink = subprocess.Popen(
                [str(build_counter(workdir.name)), str(window), "100000"] + sink_topics,
                stdout=subprocess.PIPE,
                text=True,
            )
        first = {}
        subs = [
            rospy.Subscriber(
                f"/{n}/odom",
                Odometry,
                lambda m, n=n: first.setdefault(n, time.monotonic()),
                queue_size=1,
                tcp_nodelay=True,
            )
            for n in names
        ]
        rospy.wait_for_service("/sim/step", timeout)
        t_ready = time.monotonic()
        wait_for(lambda: len(first) == len(names), timeout, "the first odometry of every robot")
        t_odom = max(first.values())
        for sub in subs:  # the benchmark is no odometry client: it would load the two cores
            sub.unregister()
        rospy.ServiceProxy("/sim/pause", Empty)()
        pubs = {
            n: [sync_publisher(f"/{n}/thrusters/{i}/input", Float64) for i in range(len(PATTERNS[n]))] for n in names
        }
        wait_for(
            lambda: all(p.get_num_connections() > 0 for ps in pubs.values() for p in ps),
            timeout,
            "the simulator to subscribe to the thrusters",
        )
        master = rosgraph.Master(rospy.get_name())
        pid = ServerProxy(master.lookupNode("/simulator")).getPid(rospy.get_name())[2]
        if sink:
            wait_for_sink(
                master,
                sink_topics,
                lambda n: n.startswith("/topic_counter"),
                timeout,
                "the sink to subscribe to every translation",
            )
        step = rospy.ServiceProxy("/sim/step", Step, persistent=True)
        chunk = 10.0  # [s] of sim time per call; `hold` keeps the commands past the 1 s watchdog
        sim0 = step(duration=0.0, steps=1, client="", commands=0, hold=True).time
        wall0, cpu0 = time.monotonic(), cpu_seconds(pid)
        sink_cpu0 = cpu_seconds(sink.pid) if sink else 0.0
        sim1 = sim0
        while sim1 - sim0 < sim_seconds - 1e-9:
            for n, ps in pubs.items():
                for p, v in zip(ps, PATTERNS[n]):
                    p.publish(Float64(v))
            sim1 = step(duration=chunk, steps=0, client="", commands=0, hold=True).time
        wall1, cpu1 = time.monotonic(), cpu_seconds(pid)
        mem = proc_status(pid)
        publishers = master.getSystemState()[0]
        topics = sorted(t for t, nodes in publishers if t.startswith(f"/{names[0]}/") and "/simulator" in nodes)
        result = {
            "robots": robots,
            "master_s": t_master - t_launch,
            "ready_s": t_ready - t_launch,
            "first_odom_s": t_odom - t_launch,
            "rtf": (sim1 - sim0) / (wall1 - wall0),
            "cpu_percent": 100.0 * (cpu1 - cpu0) / (wall1 - wall0),
            "cpu_rtf": (sim1 - sim0) / (cpu1 - cpu0),
            "rss_mb": mem["VmRSS"],
            "peak_rss_mb": mem["VmHWM"],
            "sim_seconds": sim1 - sim0,
            "topics": topics,
        }
        if sink:
            result["sink_cpu_percent"] = 100.0 * (cpu_seconds(sink.pid) - sink_cpu0) / (wall1 - wall0)
            window.write_text(f"{sim0} {sim1}")
            sink.send_signal(signal.SIGINT)  # it counts what it got stamped inside the window, then exits
            counts = dict(line.split() for line in sink.communicate(timeout=timeout)[0].splitlines())
            result["delivered"] = min(int(counts.get(t, 0)) / round((sim1 - sim0) * rates[t]) for t in sink_topics)
        return result
    finally:
        if sink and sink.poll() is None:
            sink.kill()
            sink.wait()
        world.close()
        workdir.cleanup()


def machine():
    """The machine a benchmark runs on: cores, CPU model and the load average now."""
    cpu = subprocess.run("lscpu | grep 'Model name'", shell=True, capture_output=True, text=True).stdout
    return f"nproc {os.cpu_count()}, {' '.join(cpu.split()[2:])}; load average before: {os.getloadavg()[0]:.2f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sim-seconds", type=float, default=120.0, help="sim seconds per RTF measurement")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--repeat", type=int, default=3, help="runs per robot count (the summary takes medians)")
    ap.add_argument("--timeout", type=float, default=120.0, help="wall seconds allowed for each wait")
    ap.add_argument("--robots", type=int, choices=(1, 2, 3), help="measure this count only (JSON out)")
    ap.add_argument("--world", choices=("mine", "tank"), default="mine", help="tank: the same, for comparison")
    ap.add_argument("--sensors", default="all", help="sensor families that run (the sensors:= launch argument)")
    ap.add_argument(
        "--vehicles", default="", help="a mixed team instead of 1, 2, 3 UX-1s, e.g. ux1,bluerov2_heavy,remus100"
    )
    ap.add_argument(
        "--translations",
        action="store_true",
        help="a C++ sink subscribes to every robot's m3/points and dvl_water_track (the C++ translations)",
    )
    ap.add_argument(
        "--subscribe",
        default="",
        help="the sink subscribes to these topics too, e.g. /ROV_1/imaging_sonar/polar@10 (TOPIC@HZ, comma-separated)",
    )
    args = ap.parse_args()
    parse_subscriptions(args.subscribe)
    if args.robots:
        print(
            json.dumps(
                measure(
                    args.robots,
                    args.sim_seconds,
                    args.seed,
                    args.timeout,
                    args.world,
                    args.sensors,
                    args.translations,
                    args.vehicles,
                    args.subscribe,
                )
            )
        )
        return 0
    print(
        f"{args.world} world{', team ' + args.vehicles if args.vehicles else ''}, sensors {args.sensors}, "
        f"{'subscribed ' + args.subscribe + ', ' if args.subscribe else ''}"
        "physics 500 Hz, stepped as fast as it goes, "
        f"{args.sim_seconds:.0f} s of sim time per run, {args.repeat} runs per count; {machine()}"
    )
    header = (
        f"{'robots':>6} {'RTF':>7} {'CPU %':>6} {'RSS MB':>7} {'peak MB':>8} {'master s':>9} "
        f"{'ready s':>8} {'1st odom s':>11}"
    )
    print(header)
    topics, summary = None, []
    for robots in (1,) if args.vehicles else (1, 2, 3):
        runs = []
        for _ in range(args.repeat):
            r = run_child(
                [
                    __file__,
                    "--robots",
                    str(robots),
                    "--seed",
                    str(args.seed),
                    "--world",
                    args.world,
                    "--sim-seconds",
                    str(args.sim_seconds),
                    "--sensors",
                    args.sensors,
                    *(["--translations"] if args.translations else []),
                    *(["--vehicles", args.vehicles] if args.vehicles else []),
                    *(["--subscribe", args.subscribe] if args.subscribe else []),
                    "--timeout",
                    str(args.timeout),
                ],
                args.vehicles or f"{robots} robots",
            )
            if r is None:
                return 1
            runs.append(r)
            print(row(robots, runs[-1]), flush=True)
        topics = topics or runs[0]["topics"]
        summary.append(row(robots, {k: float(np.median([r[k] for r in runs])) for k in runs[0] if k != "topics"}))
    print(f"median of {args.repeat} runs (load average after: {os.getloadavg()[0]:.2f})\n{header}")
    print("\n".join(summary))
    print("simulator topics under the first robot: " + " ".join(t.split("/", 2)[2] for t in topics))
    return 0


def row(robots, r):
    return (
        f"{robots:>6} {r['rtf']:>7.1f} {r['cpu_percent']:>6.0f} {r['rss_mb']:>7.0f} {r['peak_rss_mb']:>8.0f} "
        f"{r['master_s']:>9.2f} {r['ready_s']:>8.2f} {r['first_odom_s']:>11.2f}"
        + (f"  delivered {r['delivered']:.2f}, sink CPU {r['sink_cpu_percent']:.0f} %" if "delivered" in r else "")
        + f"  RTF in the simulator's CPU time {r['cpu_rtf']:.1f}"
    )


if __name__ == "__main__":
    sys.exit(main())

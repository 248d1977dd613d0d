#!/usr/bin/env python3
"""Real-time factor with the sonars (MSIS + M3) running, 1 and 3 robots (targets >= 50 and >= 15).

    source scripts/env.sh && python bench/sonar_rtf.py [--robots 1 3] [--window 10] [--sink counter|none]

Tank world (tank_world.launch: every robot's full sensor set: IMU 500 Hz, pressure, DVL 8 Hz, MSIS 25 pings/s
of 350 rays, M3 40 Hz of 1024 rays, the DVL and M3 translators, the allocator), lockstep as fast as possible
(realtime:=false), physics 500 Hz. Every run has its own ROS master and runs --window s of wall time after
/sim/unpause. Sink "counter" (default): bench/topic_counter.cpp (built with g++) subscribes to every robot's
tritech_micron/scan, m3/scan and m3/points, so the simulator builds and sends every sonar message and the
translator works; "none": only the M3 translator subscribes (the sonar models still run every ping).
Reported: RTF = sim time advanced / wall time, the delivered fraction of the sonar messages stamped inside
the window (1.00 = the sink got all), CPU of the simulator and the M3 translators (share of one core).
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from sensors_rtf import (  # noqa: E402
    build_counter,
    counter_counts,
    node_pids,
    run_child,
    stop_bench,
    timed_window,
    wait_for_sink,
)

ROBOTS = ["UX_1", "UX_2", "UX_3"]
RATES = {"tritech_micron/scan": 25.0, "m3/scan": 40.0, "m3/points": 40.0}


def measure(robots, window, sink, workdir):
    import rosgraph
    import rospy

    from unexmin import Simulation
    from unexmin.scripting.launcher import free_port, wait_for

    port = free_port()
    os.environ["ROS_MASTER_URI"] = f"http://127.0.0.1:{port}"
    names = ROBOTS[:robots]
    topics = [f"/{r}/{t}" for r in names for t in RATES]
    log = open(Path(workdir) / "launch.log", "w")
    proc = subprocess.Popen(
        [
            "roslaunch",
            "--port",
            str(port),
            "unexmin",
            "tank_world.launch",
            f"robots:={robots}",
            "realtime:=false",
            "paused:=true",
            "seed:=0",
        ],
        stdout=log,
        stderr=subprocess.STDOUT,
        start_new_session=True,
    )
    counter = None
    window_file = Path(workdir) / "window"
    try:
        sim = Simulation(node_name="sonar_bench", timeout=60.0)
        for r in names:
            wait_for(
                lambda r=r: any(t == f"/{r}/m3/points" for t, _ in rospy.get_published_topics()),
                30.0,
                f"/{r}/m3/points",
            )
        nodes = ["/simulator"] + [f"/{r}/m3_translator" for r in names]
        if sink == "counter":
            counter = subprocess.Popen(
                [str(build_counter(workdir)), str(window_file), "100000"] + topics, stdout=subprocess.PIPE, text=True
            )
            wait_for_sink(rosgraph.Master("/sonar_bench"), topics, lambda n: n.startswith("/topic_counter"), 30.0)
            time.sleep(1.0)  # connections are made after the master registration (benchmark set-up only)
        pids = node_pids("/sonar_bench", nodes)
        t_sim0, t_sim1, wall, cpu = timed_window(sim, pids, window)
        result = {"robots": robots, "rtf": (t_sim1 - t_sim0) / wall, "cpu": cpu, "delivered": None}
        if counter:
            time.sleep(3.0)  # let the translators and the sink drain (benchmark only)
            counts = counter_counts(counter, window_file, t_sim0, t_sim1)
            result["delivered"] = min(
                counts.get(t, 0) / max(1, round(RATES[t.split("/", 2)[2]] * (t_sim1 - t_sim0))) for t in topics
            )
        return result
    finally:
        stop_bench(counter, proc, log)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", type=int, nargs="+", default=[1, 3], choices=[1, 2, 3])
    parser.add_argument("--window", type=float, default=10.0, help="wall seconds per run")
    parser.add_argument("--sink", choices=["counter", "none"], default="counter")
    parser.add_argument("--one", type=int, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.one:
        with tempfile.TemporaryDirectory() as tmp:
            os.environ.setdefault("ROS_LOG_DIR", tmp)
            print(json.dumps(measure(args.one, args.window, args.sink, tmp)))
        return
    print(f"tank, lockstep, physics 500 Hz, MSIS + M3 on every robot, sink {args.sink}, {args.window:.0f} s per run")
    print(f"{'robots':>6} {'RTF':>6} {'delivered':>9}  CPU (share of one core)")
    for n in args.robots:
        r = run_child([__file__, "--one", str(n), "--window", str(args.window), "--sink", args.sink], f"{n} robots")
        if r is None:
            continue
        d = "-" if r["delivered"] is None else f"{r['delivered']:.2f}"
        cpu = ", ".join(f"{k} {100 * c:.0f} %" for k, c in r["cpu"].items())
        print(f"{n:>6} {r['rtf']:6.1f} {d:>9}  {cpu}", flush=True)


if __name__ == "__main__":
    main()

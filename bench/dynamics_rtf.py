#!/usr/bin/env python3
"""Real-time factor of the lockstep simulator, dynamics only, with 1, 2 and 3 robots in the tank.

    source scripts/env.sh && python bench/dynamics_rtf.py [--seconds 200] [--world tank]

For each robot count: launches the world (lockstep, paused), then measures
  * stepped RTF: one /sim/step call of --seconds of sim time, divided by its wall time;
  * free-running RTF: sim time advanced on /clock during --window s of wall time after unpausing;
  * the simulator process's resident memory (VmRSS) at the end.
Every robot holds a thrust command the whole time, so the physics is not idle.
"""

import argparse
import json
import subprocess
import sys
import time
from xmlrpc.client import ServerProxy

import rosgraph

from unexmin import Simulation


def simulator_rss_mb(caller):
    master = rosgraph.Master(caller)
    pid = ServerProxy(master.lookupNode("/simulator")).getPid(caller)[2]
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def measure(world, robots, seconds, window):
    sim = Simulation.launch(world, robots=robots, seed=0)
    try:
        handles = [sim.robot(f"UX_{i + 1}", streams="none") for i in range(robots)]  # dynamics only
        for h in handles:
            h.thrusts([5.0, 0, -5.0, 0, 5.0, 0, -5.0, 0])
        sim.step(1)
        t0 = time.perf_counter()
        sim_t0 = sim.time
        sim.run_for(seconds)
        stepped = (sim.time - sim_t0) / (time.perf_counter() - t0)
        # Free-running lockstep (as with realtime:=false and nobody stepping).
        sim_start = sim.time
        sim.unpause()
        t0 = time.perf_counter()
        time.sleep(window)  # a benchmark window, not a test wait
        sim.pause()
        free = (sim.time - sim_start) / (time.perf_counter() - t0)
        rss = simulator_rss_mb("/bench")
        return stepped, free, rss
    finally:
        sim.close()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=200.0, help="sim seconds per stepped run")
    parser.add_argument("--window", type=float, default=5.0, help="wall seconds of free running")
    parser.add_argument("--world", default="tank")
    parser.add_argument("--robots", type=int, help="measure only this count (one ROS master per process)")
    args = parser.parse_args()
    if args.robots:
        print(json.dumps(measure(args.world, args.robots, args.seconds, args.window)))
        return
    print(f"world {args.world}, physics 500 Hz, lockstep, {args.seconds:.0f} s stepped, {args.window:.0f} s free")
    print(f"{'robots':>6} {'stepped RTF':>12} {'free RTF':>10} {'RSS [MB]':>9}")
    for robots in (1, 2, 3):
        out = subprocess.run(
            [
                sys.executable,
                __file__,
                "--robots",
                str(robots),
                "--world",
                args.world,
                "--seconds",
                str(args.seconds),
                "--window",
                str(args.window),
            ],
            capture_output=True,
            text=True,
            check=True,
        ).stdout
        stepped, free, rss = json.loads(out.strip().splitlines()[-1])
        print(f"{robots:>6} {stepped:>12.0f} {free:>10.0f} {rss:>9.1f}", flush=True)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Hardware in the loop across two hosts (docs/real_robot.md): the latency from the robot's command to the
simulator's thrust, the clock offset between the hosts, and what a dropped link does; printed as a table.

    sudo -E env PATH="$PATH" python bench/hil_latency.py [--steps 10] [--drop 5]     # root: network namespaces

Two network namespaces joined by a veth pair stand for the robot and the simulator's host (unexmin.hil.rig): the
robot's host runs the master and the stand-in (its ESC commands step between two levels every second, stamped on its
wall clock), the simulator's host the tank world in real time and the ESC driver on the robot's master.
Latencies are from each command step's stamp (robot clock, moved to the simulator host's clock by the measured
offset) to its arrival on the simulator's host, to the ESC driver's thruster input, and to the simulator's thrust
responding (2 % of the step); `round trip` is from the stamp to that thrust response arriving back on the robot.
"""

import argparse
import json
import os
import sys
import tempfile


def row(name, figures, scale=1e3, unit="ms"):
    if figures["count"] == 0:
        return f"| {name} | - | - | 0 |"
    median, worst = figures["median"] * scale, figures["max"] * scale
    return f"| {name} | {median:.1f} {unit} | {worst:.1f} {unit} | {figures['count']} |"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--steps", type=int, default=10, help="command steps measured (default %(default)s)")
    ap.add_argument("--drop", type=float, default=5.0, help="link drop [s] (0: none; default %(default)s)")
    ap.add_argument("--keep", action="store_true", help="keep the records and logs (their folder is printed)")
    args = ap.parse_args(argv)
    if os.geteuid() != 0:
        ap.error("network namespaces need root: run it with sudo -E")
    if args.steps < 1 or args.drop < 0:
        ap.error(f"--steps {args.steps} --drop {args.drop}: expected at least 1 step and a drop >= 0 s")

    from unexmin.hil.probe import link_drop, load, step_latencies
    from unexmin.hil.rig import HilRig

    folder = tempfile.mkdtemp(prefix="hil_latency_")
    with HilRig(folder) as rig:
        clock = rig.clock_offset()
        start = rig.wait_steps(0)
        rig.wait_steps(args.steps)
        sim, robot = load(rig.record), load(rig.robot_record)
        for events in (sim, robot):  # the steps measured: those after the start-up
            events["cmd"] = [c for c in events["cmd"] if c["stamp"] - clock["offset"] > start]
        one_way = step_latencies(sim, clock["offset"])
        round_trip = step_latencies(robot, 0.0)
        drop = None
        if args.drop > 0:
            down, up, _ = rig.drop_link(args.drop)
            rig.wait_recovered(down, up, clock["offset"])
            drop = link_drop(load(rig.record), down, up, clock["offset"])
    print(
        f"clock offset (robot - simulator host): {clock['offset'] * 1e6:+.1f} us, "
        f"round trip of the exchange {clock['delay'] * 1e6:.1f} us (best of {len(clock['samples'])})"
    )
    print("| from the command's stamp to | median | max | steps |\n| --- | --- | --- | --- |")
    print(row("its arrival on the simulator's host (every command)", one_way["link"]))
    print(row("the ESC driver's thruster input", one_way["input"]))
    print(row("the simulator's thrust responding", one_way["thrust"]))
    print(row("that thrust back on the robot (round trip)", round_trip["thrust"]))
    if drop:
        print(
            f"link down {args.drop:g} s: thrust held {drop['held_until']:.2f} s after the last command's input, "
            f"within 1 % of 0 after {drop['zero_at']:.2f} s; simulator advanced {drop['sim_advance']:.2f} s of "
            f"sim time (longest /clock gap {drop['clock_gap'] * 1e3:.0f} ms); first fresh command "
            f"{drop['recovered_after']:.2f} s after the link came up, {drop['late_commands']} commands of the drop "
            f"delivered late, thrust on the fresh level {drop['thrust_follows_after']:.2f} s after it"
        )
    if args.keep:
        print(f"records: {folder}")
    else:
        import shutil

        shutil.rmtree(folder, ignore_errors=True)
    json.dump(
        {
            "clock": {k: clock[k] for k in ("offset", "delay")},
            "one_way": one_way,
            "round_trip": round_trip,
            "drop": drop,
        },
        sys.stderr,
    )
    sys.stderr.write("\n")


if __name__ == "__main__":
    main()

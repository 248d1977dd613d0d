#!/usr/bin/env python3
"""Coast-down of a yaw turn: the main job's yaw leg (python -m unexmin.missions.tank: N = 2 for 2 s from rest,
thesis allocation), then no thrust; prints the peak yaw rate and the time it takes to halve, measured
in the simulator and from the closed form of quadratic damping.

    source scripts/env.sh
    python bench/yaw_coast.py                          # the shipped robot
    python bench/yaw_coast.py --overrides FILE         # another (e.g. quadratic_damping_rotational 0.54)

Closed form (yaw only, D_l ~ 0): (I_z + I_A) dw/dt = -D_q w^2 gives w(t) = w0 / (1 + D_q w0 t / I), so the
rate halves in t_half = I / (D_q w0) after the thrust ends (the thrusters' 0.1 s lag aside).
"""

import argparse
import math
import os
import sys
import tempfile

import numpy as np


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--overrides", help="xacro overrides of UX_1 (default: the shipped robot)")
    ap.add_argument("--coast", type=float, default=60.0, help="[s] of coasting after the command (default 60)")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)

    from unexmin import description
    from unexmin.control.allocation import ThrusterAllocator
    from unexmin.geometry import yaw_of
    from unexmin.scripting.simulation import Simulation
    from unexmin.worlds.spawn import world_launch_file

    physics = description.load(description.ROBOT_FILE, overrides=args.overrides)
    inertia = physics.hydro.inertia[2] + physics.hydro.added_mass[5, 5]
    d_q = physics.hydro.quadratic_damping[5]
    tmp = tempfile.mkdtemp(prefix="yaw_coast_")
    launch = world_launch_file(tmp, "tank", "UX_1", overrides=args.overrides) if args.overrides else None
    rows = []
    with Simulation.launch(
        "tank", robots=1, seed=args.seed, log_dir=os.path.join(tmp, "log"), launch_file=launch
    ) as sim:
        ux = sim.robot("UX_1", streams="none")
        alloc = ThrusterAllocator()
        thrusts, _ = alloc.allocate((0, 0, 0, 0, 0, 2.0))
        ux.thrusts(thrusts)
        t_cmd = sim.time
        for _ in range(20):  # 2 s of the yaw command, sampled every 0.1 s
            sim.run_for(0.1)
            o = ux.odom()
            rows.append((sim.time - t_cmd, yaw_of(o.pose.pose.orientation), o.twist.twist.angular.z))
        ux.thrusts([0.0] * len(thrusts))
        for _ in range(int(round(args.coast / 0.1))):
            sim.run_for(0.1)
            o = ux.odom()
            rows.append((sim.time - t_cmd, yaw_of(o.pose.pose.orientation), o.twist.twist.angular.z))
    a = np.array(rows)
    rate = np.degrees(a[:, 2])
    k0 = int(np.argmax(np.abs(rate)))
    w0 = abs(rate[k0])
    half = np.flatnonzero((np.arange(len(rate)) > k0) & (np.abs(rate) <= w0 / 2))
    t_half = a[half[0], 0] - a[k0, 0] if len(half) else float("nan")
    turned = math.degrees(np.unwrap(a[:, 1])[-1] - a[0, 1])
    at = {s: rate[np.argmin(np.abs(a[:, 0] - s))] for s in (5.0, 10.0, 19.0, 30.0)}
    print(f"yaw damping D_q {d_q:.3f} N m s^2/rad^2, inertia I_z + I_A {inertia:.3f} kg m^2")
    print(
        f"peak yaw rate {w0:.2f} deg/s at t = {a[k0, 0]:.1f} s (command from 0 to 2 s); "
        + ", ".join(f"{v:.2f} deg/s at {s:.0f} s" for s, v in at.items())
    )
    print(f"measured: rate halves {t_half:.1f} s after the peak; turned {turned:.0f} deg in {a[-1, 0]:.0f} s")
    print(f"closed form I / (D_q w0): {inertia / (d_q * math.radians(w0)):.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""How the identification degrades with sensor-grade navigation (docs/identification.md).

    source scripts/env.sh
    python bench/identify_noise.py [--bag worlds/bags/ux1_tank_perturbed.bag] [--seeds 3] [--levels 5:0.1:5,...]

The sample bag's navigation is its robot's ground truth. White Gaussian noise (seeded) is added to
the position [m] and to roll, pitch and yaw [rad] of every 10 Hz sample, as a stand-in for
odometry from a navigation filter, and the bag is identified again (in process, no simulator).
Prints, per noise level, the largest error over the seeds of each parameter against the truth
(urdf/ux1_perturbed.xacro) and how many parameters the fit reported as not identified.
"""

import argparse
import math
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
LEVELS = ((0.0, 0.0, 0.7), (0.0, 0.0, 5.0), (0.002, 0.05, 5.0), (0.005, 0.1, 5.0), (0.01, 0.2, 5.0), (0.02, 0.5, 5.0))
# (position sigma [m], angle sigma [deg], Savitzky-Golay window [s])


def main(argv=None):
    from unexmin import description
    from unexmin.identify import identify_bag, model
    from unexmin.identify.model import DOF, INDEX
    from unexmin.replay import read_bag

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bag", default=str(REPO / "worlds" / "bags" / "ux1_tank_perturbed.bag"))
    ap.add_argument("--truth", default=str(REPO / "urdf" / "ux1_perturbed.xacro"), help="overrides of the bag's robot")
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--levels", help="noise levels 'pos_mm:angle_deg:window_s,...' (default: the table LEVELS)")
    args = ap.parse_args(argv)
    levels = (
        LEVELS
        if not args.levels
        else [
            tuple(float(v) * f for v, f in zip(level.split(":"), (1e-3, 1.0, 1.0))) for level in args.levels.split(",")
        ]
    )
    truth = model.nominal_vector(description.load(description.ROBOT_FILE, overrides=args.truth))
    rows = []
    for sp, sa, window in levels:
        worst = {}
        flat = []
        t0 = time.monotonic()
        for seed in range(args.seeds if sp > 0 else 1):
            mission = read_bag(args.bag)
            rng = np.random.default_rng(seed)
            mission.nav[:, 1:4] += rng.normal(0.0, sp, (len(mission.nav), 3))
            mission.nav[:, 4:7] += rng.normal(0.0, math.radians(sa), (len(mission.nav), 3))
            with tempfile.TemporaryDirectory() as out:
                data = identify_bag(args.bag, out, window_s=window, progress=False, mission=mission)
            flat.append(len(data["unidentifiable"]))
            got = {
                "buoyancy [g]": (data["buoyancy_kg"]["value"] - truth[INDEX["buoyancy_kg"]]) * 1000.0,
                "cog [mm]": 1000.0
                * max(abs(v - truth[INDEX[f"cog_{a}"]]) for v, a in zip(data["cog_m"]["value"], "xyz")),
                "gain h [%]": 100.0 * (data["thrust_gain"]["value"]["horizontal"] - 1.0),
                "gain v [%]": 100.0 * (data["thrust_gain"]["value"]["vertical"] - 1.0),
            }
            for i, d in enumerate(DOF):
                if d in ("roll", "pitch"):
                    continue
                name = f"damping_quadratic_{d}"
                v = data["damping_quadratic"]["value"][i]
                got[f"Dq {d} [%]"] = (
                    100.0 * (v / truth[INDEX[name]] - 1.0) if name not in data["unidentifiable"] else float("nan")
                )
            for k, v in got.items():
                if k not in worst or not (abs(worst[k]) >= abs(v)):
                    worst[k] = v
        rows.append((sp, sa, window, worst, max(flat), time.monotonic() - t0))
    keys = list(rows[0][3])
    print("pos[mm] ang[deg] win[s] " + " ".join(f"{k:>14s}" for k in keys) + "  flat  wall[s]")
    for sp, sa, window, worst, flat, wall in rows:
        print(
            f"{sp * 1000:7.0f} {sa:8.2f} {window:6.1f} "
            + " ".join(f"{worst[k]:14.2f}" for k in keys)
            + f"  {flat:4d}  {wall:7.1f}"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Robots of known parameters: record each one's bag and identify it, timed (docs/identification.md).

    source scripts/env.sh
    python bench/identify_robots.py [--robots heavy_stiff,light_soft] [--out DIR]

The robots are those of test/pytest/test_identify.py (ROBOTS: the corners of the identified parameters' ranges),
recorded the same way (worlds/tools/make_sample_bag.py --overrides ... --vbs-trim ... --level, in a
subprocess with its own world). Prints per robot the wall time of the recording and of the
identification, the largest error of each parameter group against the truth as a fraction of the
test's bound (<= 1 passes: 10 % of the truth, or 0.02 kg / 2 mm / 10 % of the damping at the mission's
RMS speed near zero), and the parameters reported as not identified.
"""

import argparse
import importlib.util
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


def main(argv=None):
    spec = importlib.util.spec_from_file_location("test_identify", REPO / "test" / "pytest" / "test_identify.py")
    t = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(t)
    from unexmin import description
    from unexmin.identify import model
    from unexmin.identify.model import DOF, INDEX, PARAMS

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--robots", help="comma-separated names (default: all of test_identify.ROBOTS)")
    ap.add_argument("--out", help="folder for the bags (default: a temporary one)")
    args = ap.parse_args(argv)
    names = args.robots.split(",") if args.robots else list(t.ROBOTS)
    unknown = [n for n in names if n not in t.ROBOTS]
    if unknown:
        ap.error(f"--robots {','.join(unknown)}: unknown (known: {', '.join(t.ROBOTS)})")
    out = Path(args.out or tempfile.mkdtemp(prefix="identify_robots_"))
    out.mkdir(parents=True, exist_ok=True)
    groups = {
        "buoyancy": ["buoyancy_kg"],
        "cog": ["cog_x", "cog_y", "cog_z"],
        "gains": ["thrust_gain_horizontal", "thrust_gain_vertical"],
        "Dq trans": [f"damping_quadratic_{d}" for d in DOF[:3]],
        "Dq rot": [f"damping_quadratic_{d}" for d in DOF[3:]],
        "D lin": [f"damping_linear_{d}" for d in DOF],
        "added I": [f"added_inertia_{d}" for d in DOF[3:]],
    }
    print(
        f"{'robot':<16}{'record[s]':>10}{'identify[s]':>12}" + "".join(f"{g:>10}" for g in groups) + "  not identified"
    )
    for name in names:
        w0 = time.monotonic()
        bag, overrides = t.make_bag(out, name)
        w1 = time.monotonic()
        data = t.identify_bag(bag, out / f"{name}_id", progress=False)
        w2 = time.monotonic()
        truth_physics = description.load(description.ROBOT_FILE, overrides=overrides)
        truth = model.nominal_vector(truth_physics)
        got = t.got_values(data)
        worst = {}
        for g, members in groups.items():
            ratios = [
                abs(got[n] - truth[INDEX[n]]) / t.bound_of(n, truth, truth_physics, data)
                for n in members
                if n not in data["unidentifiable"]
            ]
            worst[g] = f"{max(ratios):.2f}" if ratios else "flat"
        print(
            f"{name:<16}{w1 - w0:>10.1f}{w2 - w1:>12.1f}"
            + "".join(f"{worst[g]:>10}" for g in groups)
            + "  "
            + ", ".join(n.replace("damping_", "") for n in data["unidentifiable"] if n in PARAMS)
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())

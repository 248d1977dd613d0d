"""python -m unexmin.missions.explore: frontier exploration of a mine by one to three robots (docs/explore.md).

python -m unexmin.missions.explore --out DIR [--world-file FILE] [--robots 1|2|3] [--time S] [--energy J]
                          [--bounds X0 Y0 Z0 X1 Y1 Z1] [--visibility none|low|medium|high] [--speed M/S] ...
"""

import argparse
import math
import sys

from unexmin.missions.explore.budget import Budget
from unexmin.missions.explore.plan import PlanOptions
from unexmin.missions.explore.runner import ExploreOptions, Explorer
from unexmin.worlds.schema import visibility_levels


def parser():
    p = argparse.ArgumentParser(prog="python -m unexmin.missions.explore", description=__doc__.splitlines()[0])
    p.add_argument("--out", default="explore_output", help="output folder (created)")
    p.add_argument("--world-file", help="a mine's world file (default: the shipped mine, worlds/mine.world)")
    p.add_argument("--robots", type=int, default=1, help="robots exploring together, 1..3 (default 1)")
    p.add_argument("--seed", type=int, default=0, help="the simulator's seed (default 0)")
    p.add_argument("--time", type=float, default=600.0, help="time budget [s of sim time] (default 600)")
    p.add_argument("--energy", type=float, default=math.inf, help="energy budget per robot [J] (default: none)")
    p.add_argument("--reserve", type=float, default=1.5, help="the way home costed at this factor (default 1.5)")
    p.add_argument(
        "--bounds",
        type=float,
        nargs=6,
        metavar=("X0", "Y0", "Z0", "X1", "Y1", "Z1"),
        help="the box explored [m] (default: 40 m along x and 15 m along y either way of the start, "
        "25 m down, clipped to the world and the water surface)",
    )
    p.add_argument("--visibility", choices=visibility_levels(), help="default: the world file's")
    p.add_argument("--speed", type=float, default=0.3, help="[m/s] along the path (default 0.3)")
    p.add_argument("--yaw-rate", type=float, default=0.2, help="[rad/s] the continuous turn (default 0.2)")
    p.add_argument("--margin", type=float, default=0.3, help="[m] water kept between hull and mapped rock (0.3)")
    p.add_argument("--map-period", type=float, default=5.0, help="[s of sim time] between replans (default 5)")
    p.add_argument("--resolution", type=float, default=0.1, help="[m] map voxel edge (default 0.1)")
    p.add_argument("--cell-voxels", type=int, default=4, help="planning cell edge in voxels: 1, 2, 4, 8 (default 4)")
    p.add_argument("--snapshot", type=float, default=0.0, help="[s of sim time] between scored maps (default: none)")
    return p


def main(argv=None):
    args = parser().parse_args(argv)
    from unexmin.missions.explore.report import write
    from unexmin.worlds.files import world_path

    options = ExploreOptions(
        robots=args.robots,
        speed=args.speed,
        yaw_rate=args.yaw_rate,
        map_period=args.map_period,
        resolution=args.resolution,
        cell_voxels=args.cell_voxels,
        snapshot=args.snapshot,
        bounds=(tuple(args.bounds[:3]), tuple(args.bounds[3:])) if args.bounds else None,
    )
    try:
        options.check()
        budget = Budget(time_s=args.time, energy_j=args.energy, reserve=args.reserve)
        budget.check()
        plan_options = PlanOptions(margin=args.margin)
        plan_options.check()
    except ValueError as e:
        parser().error(str(e))
    world_file = args.world_file or world_path("mine")
    e = Explorer(args.out, world_file, options, budget, plan_options, args.seed, args.visibility).run()
    s = write(e)
    q = s["quality"]
    lines = [
        f"\n{s['robots']} robot(s) explored {s['explored_reachable_m3']:.0f} of {s['reachable_m3']:.0f} m3 reachable "
        f"({100 * s['coverage']:.0f} %) in {s['sim_time_s']:.0f} s of sim time ({s['mission_wall_s']:.0f} s wall, RTF "
        f"{s['rtf_while_stepping']}); all home: {s['all_home']}; contacts {s['contacts']}, stuck {s['stuck']}, "
        f"sonar stops {s['sonar_stops']}"
    ]
    lines += [
        f"  {name}: {r['flown_m']:.0f} m flown, {r['energy_j']:.0f} J, drift {r['drift_m']} m (max "
        f"{r['max_drift_m']}), {r['home_error_m']} m from its start, min clearance {r['min_clearance_m']} m"
        for name, r in s["robot"].items()
    ]
    lines.append(
        f"map: precision {q['precision']:.3f}, recall {q['recall']:.3f}, F-score {q['f_score']:.3f} -> {args.out}"
    )
    print("\n".join(lines))
    return 0 if s["contacts"] == 0 and s["all_home"] else 3


if __name__ == "__main__":
    sys.exit(main())

"""The main job: a headless, lockstep mapping survey of the flooded mine (docs/mapping.md, "The mission").

    python -m unexmin.missions.mine --out DIR [--seed N] [--gallery M] [--resolution M]
                                    [--visibility none|low|medium|high] [--world-file FILE] [--snapshot S]

Leaves in DIR: mine_mission.bag, mine_map.bt, trajectory.csv, map_quality.json, map_quality.png, mission_map.png,
coverage.png, summary.json, snapshots/, logs/.
"""

import os

from unexmin.missions.common import mission_parser
from unexmin.missions.mine.plan import make_plan
from unexmin.missions.mine.runner import MineRunner
from unexmin.missions.mine.scoring import score
from unexmin.worlds.schema import visibility_levels


def run(
    out, seed=0, gallery=40.0, resolution=0.1, time_limit=None, visibility=None, world_file=None, snapshot_every=90.0
):
    """The mission: its plan, flown, scored. Returns the summary (also DIR/summary.json)."""
    plan = make_plan(world_file, gallery, visibility, time_limit)
    flight = MineRunner(plan, out, seed, resolution, snapshot_every).run()
    return score(plan, flight)


def main(argv=None):
    parser = mission_parser("python -m unexmin.missions.mine", __doc__.splitlines()[0])
    parser.add_argument("--gallery", type=float, default=40.0, help="metres flown along the gallery (default 40)")
    parser.add_argument("--resolution", type=float, default=0.1, help="map voxel edge [m] (default 0.1)")
    parser.add_argument(
        "--visibility", choices=visibility_levels(), help="water visibility (default: the world file's)"
    )
    parser.add_argument("--world-file", help="a generated mine's world file (default: the shipped mine)")
    parser.add_argument(
        "--snapshot", type=float, default=90.0, help="sim seconds between saved maps for the coverage curve"
    )
    args = parser.parse_args(argv)
    if not args.snapshot > 0:
        parser.error(f"--snapshot {args.snapshot}: expected > 0 s")
    s = run(
        args.out,
        args.seed,
        args.gallery,
        args.resolution,
        visibility=args.visibility,
        world_file=args.world_file,
        snapshot_every=args.snapshot,
    )
    q = s["quality"]
    print(
        f"\nUX_1 surveyed {s['path_length_m']:.0f} m of the mine (shaft helix and gallery; plan "
        f"{'completed' if s['plan_completed'] else 'NOT completed'}, waited {s['held_s']:.0f} s for the robot) in "
        f"{s['sim_time_s']:.0f} s of sim time, {s['wall_time_s']:.0f} s of wall time (RTF "
        f"{s['rtf_while_stepping']:.1f} while stepping)."
    )
    print(
        f"map: {s['clouds_inserted']}/{s['clouds_received']} clouds inserted ({s['clouds_dropped']} dropped, "
        f"{s['clouds_expected']} published), {s['occupied_leaves']} occupied leaves, "
        f"{s['map_memory_bytes'] / 1e6:.1f} MB in memory, {s['map_file_bytes'] / 1e6:.2f} MB .bt"
    )
    print(
        f"quality at tau {q['tau_m']:g} m: precision {q['precision']:.3f}, recall {q['recall']:.3f} "
        f"(over {q['surface_area_m2']:.0f} m2 within range of the path), F-score {q['f_score']:.3f}, "
        f"distance mean {q['mean_distance_m']:.3f} m, 95th percentile {q['p95_distance_m']:.3f} m"
    )
    print(
        f"outputs: {os.path.abspath(args.out)} (mine_mission.bag, mine_map.bt, map_quality.json, "
        f"map_quality.png, mission_map.png, coverage.png, trajectory.csv, summary.json, snapshots/)"
    )
    return 0

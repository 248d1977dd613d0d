"""Small mines for the explorer's tests and bench, built with the mine generator's own construction (capsules of
superellipse section with rough walls, their union, the same PLY), and a world file for each (no ROS).

    python -m unexmin.missions.explore.course --kind branch|dead_end --out DIR

- `branch`: a level in miniature: a 26 m gallery along +x (4.0 m wide, 3.6 m high) with a 9 m crosscut to +y
  (3.4 m across) at x = 14 m and a dead-end stub of 5 m to -y at x = 6 m; centreline z = -10 m.
- `dead_end`: one straight gallery, 10 m along +x, closed at both ends; centreline z = -10 m.
The robots start 2 m from the gallery's closed west end (x = 2 m), on its axis, 1.5 m apart along +x.
"""

import argparse
import sys
from pathlib import Path

import numpy as np
import yaml

from unexmin.worlds.files import world_path
from unexmin.worlds.generator import generator as mg
from unexmin.worlds.meshes import write_ply

Z = -10.0  # [m] centreline of the course
KINDS = ("branch", "dead_end")


def layout(kind):
    """The tunnels of a course (unexmin.worlds.generator's Tunnel) and the robots' start points [m]."""
    g = dict(a=2.0, b=1.8, c=2.0)
    if kind == "branch":
        tunnels = [
            mg.Tunnel("gallery", [(0.0, 0.0, Z), (13.0, 0.4, Z), (26.0, -0.3, Z)], **g),
            mg.Tunnel("crosscut", [(14.0, 0.4, Z), (14.0, 9.0, Z - 0.3)], a=1.7, b=1.6, c=1.7),
            mg.Tunnel("crosscut", [(6.0, 0.2, Z), (6.0, -5.0, Z)], a=1.7, b=1.6, c=1.7),
        ]
    elif kind == "dead_end":
        tunnels = [mg.Tunnel("gallery", [(0.0, 0.0, Z), (10.0, 0.0, Z)], **g)]
    else:
        raise ValueError(f"course kind {kind!r}: expected one of {', '.join(KINDS)}")
    spawns = [(2.0 + 1.5 * i, 0.0, Z) for i in range(3)]
    return tunnels, spawns


def build(kind, out, seed=1):
    """Write <out>/course_collision.ply, course_visual.ply and course.world; returns the world file's path."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    tunnels, spawns = layout(kind)
    lay = mg.Layout(tunnels=tunnels, spawns=spawns, shaft_xy=(0.0, 0.0))
    octaves = ((6.0, 0.10), (2.0, 0.05), (0.9, 0.025))
    walls = mg.RoughWalls(octaves, seed)
    for key, edge, cut in (("collision", 0.4, 0.0), ("visual", 1.0, 3.0)):
        v, t = mg.canonical_mesh(mg.build_solid(lay, edge, walls, cut))
        v, _ = mg.separate_pinches(v, t)
        write_ply(out / f"course_{key}.ply", v, t, f"unexmin explore course {kind} seed {seed} {key}")
    world = yaml.safe_load(Path(world_path("mine")).read_text())
    world["name"] = f"course_{kind}"
    world["meshes"][0]["file"] = "course_collision.ply"
    world["meshes"][1]["file"] = "course_visual.ply"
    for robot, spawn in zip(world["robots"], spawns):
        robot["xyz"] = [float(v) for v in spawn]
    path = out / "course.world"
    path.write_text(yaml.safe_dump(world, sort_keys=False))
    return path


def bounds(kind):
    """(lo, hi) [m]: a box holding the course's void with a margin."""
    tunnels, _ = layout(kind)
    pts = np.concatenate([t.points for t in tunnels])
    r = max(max(t.a, t.b, t.c) for t in tunnels) + 1.0
    return pts.min(axis=0) - r, pts.max(axis=0) + r


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="python -m unexmin.missions.explore.course", description=__doc__.splitlines()[0]
    )
    parser.add_argument("--kind", choices=KINDS, default="branch")
    parser.add_argument("--out", required=True, help="output folder (created)")
    parser.add_argument("--seed", type=int, default=1, help="wall noise seed")
    args = parser.parse_args(argv)
    print(build(args.kind, args.out, args.seed))
    return 0


if __name__ == "__main__":
    sys.exit(main())

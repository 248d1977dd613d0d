"""Geology and water column of a generated mine (docs/mine_world.md "Geology and water").

    python -m unexmin.worlds.generator.science --seed 7     # prints the `water:` and `geology:` of worlds/mine.world

A mine of seed S gets, from S and its layout (`make_layout`, the same one its meshes are built from):

- a potassic host rock (granite with K-feldspar);
- a sulphide vein (chalcopyrite, pyrite, a malachite stain, quartz) across level 0's gallery;
- a magnetite lens in the rock beside level 0's gallery, its near side about a metre behind the wall;
- a hematite-goethite zone (a gossan) around the pump station by the shaft;
- a uranium-bearing fracture zone (autunite in quartz) across level 0's gallery farther out;
- two thin fluorescent calcite veins crossing the entry shaft between the water surface and level 0;
- a water column: a warm, fresher upper layer over a chemocline with acid, conductive water below it,
  the boundary heaving slowly.

Every position is drawn from the seed within the first ~150 m of level 0 and the shaft, where a dive from the
shaft reaches; every number is assumed (typical of flooded metal mines, Nuttall & Younger 2004, not measured in one).
"""

import argparse
import sys

import numpy as np

from unexmin.worlds.generator.generator import PRESETS, make_layout, point_on


def _r(x, nd=3):
    return round(float(x), nd)


def _gallery(layout, level=0):
    return [t for t in layout.tunnels if t.kind == "gallery"][level]


def _vein_across(rng, gallery, x_lo, x_hi, thickness, extent):
    """A vein crossing the gallery at a drawn x: its mid-plane through the centreline, its normal near the gallery's
    axis (tilted by up to 30 deg in plan and 20 deg in dip)."""
    x = rng.uniform(x_lo, x_hi)
    p = point_on(gallery.points, x)
    strike = rng.uniform(-0.5, 0.5)  # [rad] from across the gallery
    dip = rng.uniform(-0.35, 0.35)
    n = np.array([np.cos(strike) * np.cos(dip), np.sin(strike) * np.cos(dip), np.sin(dip)])
    return {"xyz": [_r(v) for v in p], "normal": [_r(v) for v in n], "thickness": _r(thickness), "extent": _r(extent)}


def geology(seed, preset="full"):
    """The `geology:` map (dict) of the mine of `seed`."""
    if not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"seed must be a non-negative integer, got {seed!r}")
    P = PRESETS[preset] if isinstance(preset, str) else preset
    layout = make_layout(P, int(seed))
    rng = np.random.default_rng([int(seed), 11])
    g0 = _gallery(layout, 0)
    reach = min(150.0, float(g0.points[-1, 0]) - 10.0)
    sx, sy = layout.shaft_xy
    k_feldspar = _r(rng.uniform(0.15, 0.3), 2)
    bodies = []
    vein = _vein_across(rng, g0, 25.0, 0.35 * reach, rng.uniform(0.6, 1.2), rng.uniform(15.0, 25.0))
    bodies.append(
        {
            "name": "sulphide_vein",
            "kind": "vein",
            **vein,
            "minerals": [
                {"mineral": "chalcopyrite", "fraction": 0.25},
                {"mineral": "pyrite", "fraction": 0.2},
                {"mineral": "malachite", "fraction": 0.1},
                {"mineral": "quartz", "fraction": 0.45},
            ],
        }
    )
    # The magnetite lens: an ellipsoid along the gallery, on one side, 1 m of host rock between it and the wall.
    x = rng.uniform(0.4 * reach, 0.6 * reach)
    p = point_on(g0.points, x)
    side = float(rng.choice([-1.0, 1.0]))
    radii = [_r(rng.uniform(5.0, 8.0)), _r(rng.uniform(2.0, 3.0)), _r(rng.uniform(1.5, 2.5))]
    centre = p + np.array([0.0, side * (g0.a + 1.0 + radii[1]), 0.0])
    bodies.append(
        {
            "name": "magnetite_lens",
            "kind": "ellipsoid",
            "xyz": [_r(v) for v in centre],
            "radii": radii,
            "rpy": [0.0, 0.0, _r(rng.uniform(-0.2, 0.2))],
            "minerals": [{"mineral": "magnetite", "fraction": 0.5}, {"mineral": "quartz", "fraction": 0.5}],
        }
    )
    # The gossan: a box around the pump station (the first chamber) and the gallery beside it.
    chamber = [t for t in layout.tunnels if t.kind == "chamber"][0]
    c = chamber.points.mean(axis=0)
    length = float(np.linalg.norm(chamber.points[1] - chamber.points[0])) + 2 * chamber.a + 4.0
    goethite = _r(rng.uniform(0.3, 0.5), 2)
    bodies.append(
        {
            "name": "gossan",
            "kind": "box",
            "xyz": [_r(v) for v in c],
            "size": [_r(length), _r(2 * chamber.a + 6.0), _r(2 * chamber.b + 4.0)],
            "rpy": [0.0, 0.0, 0.0],
            "minerals": [
                {"mineral": "hematite", "fraction": _r(0.6 - goethite, 2)},
                {"mineral": "goethite", "fraction": goethite},
                {"mineral": "quartz", "fraction": 0.4},
            ],
        }
    )
    vein = _vein_across(rng, g0, 0.7 * reach, reach, rng.uniform(1.5, 3.0), rng.uniform(12.0, 20.0))
    autunite = _r(rng.uniform(0.002, 0.006), 4)
    bodies.append(
        {
            "name": "uranium_fractures",
            "kind": "vein",
            **vein,
            "minerals": [
                {"mineral": "autunite", "fraction": autunite},
                {"mineral": "quartz", "fraction": _r(1 - autunite, 4)},
            ],
        }
    )
    # Calcite veins: near-horizontal sheets crossing the entry shaft between 4 m under water and level 0's roof.
    top, bottom = P.surface_z - 4.0, P.first_level_z + 4.0
    for k, z in enumerate(sorted(rng.uniform(bottom, top, 2), reverse=True)):
        tilt, azimuth = rng.uniform(0.1, 0.4), rng.uniform(-np.pi, np.pi)
        n = [np.sin(tilt) * np.cos(azimuth), np.sin(tilt) * np.sin(azimuth), np.cos(tilt)]
        bodies.append(
            {
                "name": f"calcite_vein_{k + 1}",
                "kind": "vein",
                "xyz": [_r(sx), _r(sy), _r(z)],
                "normal": [_r(v) for v in n],
                "thickness": _r(rng.uniform(0.15, 0.35)),
                "extent": 12.0,
                "minerals": [{"mineral": "calcite", "fraction": 0.9}, {"mineral": "quartz", "fraction": 0.1}],
            }
        )
    return {
        "host": [
            {"mineral": "granite", "fraction": _r(1 - k_feldspar, 2)},
            {"mineral": "k_feldspar", "fraction": k_feldspar},
        ],
        "bodies": bodies,
    }


def water(seed, preset="full"):
    """The `water:` map (dict) of the mine of `seed`: surface_z, a linear profile with a chemocline, a boundary."""
    if not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"seed must be a non-negative integer, got {seed!r}")
    P = PRESETS[preset] if isinstance(preset, str) else preset
    rng = np.random.default_rng([int(seed), 12])
    bottom = _r(P.surface_z - (P.first_level_z - (P.levels - 1) * P.level_spacing - 2.0), 1)  # the sump's depth
    level0 = P.surface_z - P.first_level_z
    cline = _r(rng.uniform(level0 + 5.0, level0 + 0.5 * P.level_spacing), 1)  # below level 0, above level 1
    width = _r(rng.uniform(1.0, 2.0), 1)  # the transition's thickness [m]
    upper = {
        "temperature": _r(rng.uniform(12.0, 14.0), 2),
        "conductivity": _r(rng.uniform(350.0, 700.0), 0),
        "ph": _r(rng.uniform(7.0, 7.6), 2),
        "redox": _r(rng.uniform(250.0, 350.0), 0),
        "oxygen": _r(rng.uniform(7.5, 9.5), 2),
        "turbidity": _r(rng.uniform(2.0, 4.0), 2),
    }
    lower = {
        "temperature": _r(rng.uniform(9.0, 10.5), 2),
        "conductivity": _r(rng.uniform(3000.0, 9000.0), 0),
        "ph": _r(rng.uniform(3.5, 4.5), 2),
        "redox": _r(rng.uniform(400.0, 550.0), 0),
        "oxygen": _r(rng.uniform(0.2, 1.5), 2),
        "turbidity": _r(rng.uniform(6.0, 12.0), 2),
    }
    warm_top = dict(upper, temperature=_r(upper["temperature"] + rng.uniform(0.5, 1.5), 2))
    deep = dict(lower, temperature=_r(lower["temperature"] + rng.uniform(0.5, 1.5), 2))
    rows = [
        {"depth": 0.0, **warm_top},
        {"depth": _r(cline - width / 2, 1), **upper},
        {"depth": _r(cline + width / 2, 1), **lower},
        {"depth": bottom, **deep},
    ]
    return {
        "surface_z": float(P.surface_z),
        "interpolation": "linear",
        "profile": rows,
        "boundary": {"depth": cline, "amplitude": _r(rng.uniform(0.2, 0.6), 2), "period": 21600.0, "phase": 0.0},
    }


def _flow(value):
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k}: {_flow(v)}" for k, v in value.items()) + "}"
    if isinstance(value, list):
        return "[" + ", ".join(_flow(v) for v in value) + "]"
    return str(value)


def world_blocks(seed, preset="full"):
    """The `water:` and `geology:` keys as worlds/mine.world writes them (YAML text, one flow map per row/body)."""
    w, g = water(seed, preset), geology(seed, preset)
    lines = ["water:"]
    lines += [f"  {k}: {_flow(v)}" for k, v in w.items() if k != "profile"]
    lines.append("  profile:")
    lines += [f"    - {_flow(row)}" for row in w["profile"]]
    lines += ["geology:", f"  host: {_flow(g['host'])}", "  bodies:"]
    lines += [f"    - {_flow(body)}" for body in g["bodies"]]
    return "\n".join(lines) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(
        prog="python -m unexmin.worlds.generator.science", description=__doc__.split("\n\n")[0]
    )
    ap.add_argument("--seed", type=int, default=7, help="the mine's seed (default 7, the shipped mine.world)")
    ap.add_argument("--preset", choices=sorted(PRESETS), default="full")
    args = ap.parse_args(argv)
    if args.seed < 0:
        ap.error(f"--seed must be >= 0, got {args.seed}")
    sys.stdout.write(world_blocks(args.seed, args.preset))
    return 0


if __name__ == "__main__":
    sys.exit(main())

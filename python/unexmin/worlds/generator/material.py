"""Rock material of a generated mine (docs/worlds.md "material", docs/vision.md "Materials").

    python -m unexmin.worlds.generator.material --seed 7           # prints the `material:` of worlds/mine.world's mesh

The walls of a mine of seed S get the `rock` material drawn from S: its albedo (greyish brown), the
scales of its grains, cracks, strata and stains [m], contrast, relief and a tint that changes with a
region size of about half the level spacing, so that levels and chambers look different. The mine
generator writes its meshes from the same seed (`python -m unexmin.worlds.generator --seed S`). Every
number is assumed (chosen to look like weathered rock at 1-3 m), not measured.
"""

import argparse
import sys

import numpy as np

from unexmin.worlds.generator import PRESETS


def material(seed, preset="full"):
    """The `material:` map (dict, floats rounded to 3 decimals) of the walls of the mine of `seed`."""
    if not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"seed must be a non-negative integer, got {seed!r}")
    rng = np.random.default_rng([int(seed), 5])
    grey = rng.uniform(0.24, 0.36)
    warmth = rng.uniform(0.0, 0.08)  # brown: red above blue
    r3 = lambda x: round(float(x), 3)  # noqa: E731
    return {
        "kind": "rock",
        "albedo": [r3(grey + warmth / 2), r3(grey), r3(grey - warmth / 2)],
        "seed": int(seed),
        "contrast": r3(rng.uniform(0.3, 0.4)),
        "relief": r3(rng.uniform(0.25, 0.45)),
        "grain": r3(rng.uniform(0.015, 0.03)),
        "cracks": r3(rng.uniform(0.2, 0.5)),
        "strata": r3(rng.uniform(0.3, 0.9)),
        "stains": r3(rng.uniform(1.5, 3.5)),
        "region": r3(0.5 * PRESETS[preset].level_spacing),
        "tint": r3(rng.uniform(0.12, 0.2)),
    }


def flow(seed, preset="full"):
    """The material as one YAML flow map, as worlds/mine.world writes it."""
    m = material(seed, preset)
    items = []
    for key, value in m.items():
        items.append(f"{key}: [{', '.join(str(v) for v in value)}]" if isinstance(value, list) else f"{key}: {value}")
    return "{" + ", ".join(items) + "}"


def main(argv=None):
    ap = argparse.ArgumentParser(
        prog="python -m unexmin.worlds.generator.material", description=__doc__.split("\n\n")[0]
    )
    ap.add_argument("--seed", type=int, default=7, help="the mine's seed (default 7, the shipped mine.world)")
    ap.add_argument("--preset", choices=sorted(PRESETS), default="full")
    args = ap.parse_args(argv)
    if args.seed < 0:
        ap.error(f"--seed must be >= 0, got {args.seed}")
    print(flow(args.seed, args.preset))
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""The procedural flooded mine (docs/mine_world.md): `python -m unexmin.worlds.generator --out DIR`.
The layout, the solid, the files and the command line are in generator.py."""

from unexmin.worlds.generator.generator import PRESETS, generate, main, make_layout, point_on

__all__ = ["PRESETS", "generate", "main", "make_layout", "point_on"]

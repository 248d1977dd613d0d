"""Map quality against the world's ground truth (docs/mapping.md, "Map quality"): `python -m unexmin.map_quality`.

metrics.py: the figures (precision, recall, F-score, distances); io.py: the .bt map and the trajectory (bag or
CSV); plots.py: the picture; cli.py: run() and the command line. World files come from unexmin.worlds.
"""

from unexmin.map_quality.cli import main, run
from unexmin.map_quality.io import read_bt, read_trajectory, write_trajectory
from unexmin.map_quality.metrics import evaluate, expand, recall_of, seen_surface

__all__ = [
    "evaluate",
    "expand",
    "main",
    "read_bt",
    "read_trajectory",
    "recall_of",
    "run",
    "seen_surface",
    "write_trajectory",
]

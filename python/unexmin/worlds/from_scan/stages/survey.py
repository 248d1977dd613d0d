"""Stage survey: the first streaming pass over the scan (tiles.survey); a cloud with no usable surface stops here."""

import numpy as np

from unexmin.worlds.from_scan.errors import ScanError
from unexmin.worlds.from_scan.scan import MIN_POINTS
from unexmin.worlds.from_scan.stream import scan_size
from unexmin.worlds.from_scan.tiles import survey


def survey_scan(b):
    """Fills b.size and b.survey (count, bounds, covariance, occupied survey cells). Raises ScanError when too few
    points are left after down-sampling or when they lie along a line."""
    resolution = b.options.resolution
    b.size = scan_size(b.scan)
    with b.progress.stage("survey", "survey", *b.size) as bar:
        s = survey(b.scan, resolution, progress=bar)
    if s["voxels"] < MIN_POINTS:
        raise ScanError(
            f"{b.scan}: no usable surface: {s['voxels']} points after down-sampling to "
            f"{resolution} m (expected at least {MIN_POINTS}: a denser scan or a finer --resolution)"
        )
    spread = np.sqrt(np.maximum(np.linalg.eigvalsh(s["cov"]), 0.0))  # ascending [m]
    if spread[1] < 5 * resolution:
        raise ScanError(
            f"{b.scan}: no usable surface: the points lie along a line (spread {spread[2]:.3g} x "
            f"{spread[1]:.3g} x {spread[0]:.3g} m; expected walls around a void)"
        )
    b.survey = s
    return b

"""The Python scan -> points (unexmin.translators.m3.scan_points) against its C++ twin (mapping::scanPoints,
cpp/unexmin/mapping/scan_points.h, which the M3 cloud and the mapper use) on the same scans: seeded M3-like scans
and edge cases (+-inf, NaN, ranges at and just beyond range_min and range_max, negative increments, no beams).
The fields hold float32 values, as in a received sensor_msgs/LaserScan; the C++ side runs through
test/pytest/clients/scan_points_twin.cpp (built with the workspace). Each point must be the same float32, bit for bit.

Run: python -m pytest test/pytest/test_scan_points_twin.py (workspace built and sourced).
"""

import math
import os
import random
import struct
import subprocess
from pathlib import Path
from types import SimpleNamespace

import pytest

from unexmin.translators.m3 import scan_points

REPO = Path(__file__).resolve().parents[2]


def f32(x):
    """x rounded to float32, as a LaserScan field holds it."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


def twin():
    for ws in (os.environ.get("UNEXMIN_WS"), str(REPO.parent / (REPO.name + "_ws"))):
        if ws and (Path(ws) / "devel/lib/unexmin/scan_points_twin").exists():
            return Path(ws) / "devel/lib/unexmin/scan_points_twin"
    pytest.fail("scan_points_twin is not built: build the workspace (UNEXMIN_WS, scripts/setup.sh)")


def scan(angle_min, increment, range_min, range_max, ranges):
    return SimpleNamespace(
        angle_min=f32(angle_min),
        angle_increment=f32(increment),
        range_min=f32(range_min),
        range_max=f32(range_max),
        ranges=[f32(r) for r in ranges],
    )


def scans():
    rng = random.Random(23)
    out = []
    fov = math.radians(120.0)
    for beams in (256, 512, 1024):  # the M3's fan, in float32 fields
        ranges = [rng.uniform(0.1, 160.0) for _ in range(beams)]
        for k in rng.sample(range(beams), beams // 10):
            ranges[k] = rng.choice([math.inf, -math.inf, math.nan])
        out.append(scan(-fov / 2, fov / (beams - 1), 0.2, 150.0, ranges))
    inf, nan = math.inf, math.nan
    out += [
        scan(0.0, 0.5, 0.5, 10.0, [inf, -inf, nan, 0.4999999, 0.5, 10.0, 10.000001, 2.0]),
        scan(math.pi, -0.01, 0.0, 1e30, [rng.uniform(0.0, 1e3) for _ in range(700)]),
        scan(-3.0, 0.001, 1.0, 2.0, []),
        scan(-3.0, 0.001, 1.0, 2.0, [nan] * 5),
        scan(1.0, 0.0, 0.0, 5.0, [1.0, 2.0, 3.0]),
    ]
    return out


def line(s):
    return " ".join(repr(v) for v in [s.angle_min, s.angle_increment, s.range_min, s.range_max] + s.ranges)


def test_python_and_cpp_give_the_same_float32_points():
    cases = scans()
    out = subprocess.run(
        [str(twin())], input="\n".join(line(s) for s in cases) + "\n", capture_output=True, text=True, timeout=60
    )
    assert out.returncode == 0, out.stderr
    rows = out.stdout.splitlines()
    assert len(rows) == len(cases)
    total = 0
    for i, (s, row) in enumerate(zip(cases, rows)):
        values = row.split()
        cpp = [f32(float(v)) for v in values[1:]]
        assert int(values[0]) * 3 == len(cpp), f"scan {i}: malformed row"
        py = [f32(c) for p in scan_points(s) for c in p]  # the float32 of a PointCloud2 field
        assert len(py) == len(cpp), f"scan {i}: {len(py) // 3} points in Python, {len(cpp) // 3} in C++"
        mismatches = [k for k, (a, b) in enumerate(zip(py, cpp)) if a != b]
        if mismatches:
            k = mismatches[0]
            pytest.fail(f"scan {i}: coordinate {k} of {len(mismatches)} differing: Python {py[k]!r}, C++ {cpp[k]!r}")
        total += len(cpp) // 3
    # The edge cases keep what REP-117 keeps: range_min and range_max themselves, nothing non-finite.
    assert [int(r.split()[0]) for r in rows[3:]] == [3, 700, 0, 0, 3]
    assert total > 1500

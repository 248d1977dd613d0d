"""M3 translator (python/unexmin/translators/m3.py): LaserScan -> PointCloud2 (x y z) and back gives the
same ranges; REP-117 markers and out-of-window ranges are dropped; at most one point per beam (256).
Pure functions: no ROS master needed.

Run: /work/main_ws/venv/bin/python -m pytest test/pytest/test_m3_translator.py (workspace sourced).
"""

import math
import random

import pytest

pytest.importorskip("sensor_msgs.msg", reason="source the workspace (scripts/env.sh) to import the messages")

from sensor_msgs import point_cloud2  # noqa: E402
from sensor_msgs.msg import LaserScan, PointField  # noqa: E402

from unexmin.translators.m3 import cloud_to_ranges, scan_points, scan_to_cloud  # noqa: E402

BEAMS = 256
FOV = math.radians(120.0)


def m3_scan(ranges):
    s = LaserScan()
    s.header.frame_id = "UX_1/m3_link"
    s.header.stamp.secs, s.header.stamp.nsecs = 12, 250000000
    s.angle_min, s.angle_max = -FOV / 2, FOV / 2
    s.angle_increment = FOV / (BEAMS - 1)
    s.scan_time = 1.0 / 40.0
    s.range_min, s.range_max = 0.2, 150.0
    s.ranges = ranges
    return s


def test_round_trip_keeps_every_valid_range_and_drops_the_rest():
    rng = random.Random(4)
    ranges = [round(rng.uniform(0.2, 150.0), 2) for _ in range(BEAMS)]
    invalid = {3: math.inf, 7: -math.inf, 11: math.nan, 20: 0.1, 21: 150.5}
    for k, r in invalid.items():
        ranges[k] = r
    scan = m3_scan(ranges)
    cloud = scan_to_cloud(scan)
    assert cloud.header.frame_id == "UX_1/m3_link" and cloud.header.stamp == scan.header.stamp
    assert [(f.name, f.datatype) for f in cloud.fields] == [(n, PointField.FLOAT32) for n in "xyz"]
    assert cloud.width * cloud.height == BEAMS - len(invalid) <= BEAMS
    back = cloud_to_ranges(cloud, scan.angle_min, scan.angle_increment, BEAMS)
    for k in range(BEAMS):
        if k in invalid:
            assert back[k] == math.inf, k
        else:
            # float32 coordinates: 1e-7 relative.
            assert back[k] == pytest.approx(ranges[k], rel=2e-7, abs=1e-6), k


def test_points_lie_on_their_beams_in_the_scan_plane():
    scan = m3_scan([10.0] * BEAMS)
    pts = list(point_cloud2.read_points(scan_to_cloud(scan), field_names=("x", "y", "z")))
    assert len(pts) == BEAMS
    for k, (x, y, z) in enumerate(pts):
        a = -FOV / 2 + k * FOV / (BEAMS - 1)
        assert (x, y, z) == pytest.approx((10.0 * math.cos(a), 10.0 * math.sin(a), 0.0), abs=1e-5)
    # The edge beams at +-60 deg.
    assert math.degrees(math.atan2(pts[0][1], pts[0][0])) == pytest.approx(-60.0, abs=1e-4)
    assert math.degrees(math.atan2(pts[-1][1], pts[-1][0])) == pytest.approx(60.0, abs=1e-4)


def test_no_echo_gives_an_empty_cloud():
    scan = m3_scan([math.inf] * BEAMS)
    assert scan_points(scan) == []
    assert scan_to_cloud(scan).width == 0

"""M3 translator (the thesis's "M3_topic" node): simulated multibeam LaserScan -> the real robot's cloud.

Subscribes /<robot>/m3/scan (sensor_msgs/LaserScan of first echoes, the simulator's Kongsberg M3 model in
profiling mode) and publishes /<robot>/m3/points (sensor_msgs/PointCloud2, fields x y z FLOAT32: the
PointCloudXYZ form of the real M3 driver) at the ping rate (40 Hz), same header (stamp, frame = the M3
link). Beam k at angle a_k = angle_min + k * angle_increment and range r_k becomes the point
(r_k cos a_k, r_k sin a_k, 0); beams with no echo are left out: +inf (nothing within range_max),
-inf (nearer than range_min) and NaN (REP-117), and any range outside [range_min, range_max]. So the cloud
has at most as many points as the scan has beams (256). The conversion is a pure function with its
inverse (no ROS master needed), so a round trip is testable. Parameters: docs/sonars.md.
"""

import math

from sensor_msgs import point_cloud2
from sensor_msgs.msg import LaserScan, PointCloud2

from unexmin.translators.node import run


def scan_points(scan):
    """[(x, y, z)] of the valid beams of a LaserScan, in beam order."""
    points = []
    for k, r in enumerate(scan.ranges):
        if not math.isfinite(r) or r < scan.range_min or r > scan.range_max:
            continue
        a = scan.angle_min + k * scan.angle_increment
        points.append((r * math.cos(a), r * math.sin(a), 0.0))
    return points


def scan_to_cloud(scan):
    """sensor_msgs/LaserScan -> sensor_msgs/PointCloud2 (x y z FLOAT32), header kept."""
    return point_cloud2.create_cloud_xyz32(scan.header, scan_points(scan))


def cloud_to_ranges(cloud, angle_min, angle_increment, beams):
    """Inverse for tests: per beam the range of the cloud's point at that beam's angle (+inf: none)."""
    ranges = [math.inf] * beams
    for x, y, _ in point_cloud2.read_points(cloud, field_names=("x", "y", "z")):
        k = int(round((math.atan2(y, x) - angle_min) / angle_increment))
        ranges[k] = math.hypot(x, y)
    return ranges


def main():
    run(
        "m3_translator",
        LaserScan,
        PointCloud2,
        scan_to_cloud,
        input_topic="m3/scan",
        output_topic="m3/points",
        queue_size=100,
    )

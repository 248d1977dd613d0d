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

import rospy
from sensor_msgs import point_cloud2
from sensor_msgs.msg import LaserScan, PointCloud2


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


class M3Translator:
    """ROS wrapper: ~input_topic (LaserScan) -> ~output_topic (PointCloud2 x y z)."""

    def __init__(self):
        self.load_params()
        self.translated = 0
        self.pub = rospy.Publisher(self.output_topic, PointCloud2, queue_size=self.queue_size)
        self.sub = rospy.Subscriber(self.input_topic, LaserScan, self.on_scan, queue_size=self.queue_size,
                                    tcp_nodelay=True)
        rospy.loginfo("m3_translator: %s -> %s", self.sub.resolved_name, self.pub.resolved_name)

    def load_params(self):
        """Every parameter, checked in one place (ValueError names the parameter)."""
        self.input_topic = str(rospy.get_param("~input_topic", "m3/scan"))
        self.output_topic = str(rospy.get_param("~output_topic", "m3/points"))
        self.queue_size = rospy.get_param("~queue_size", 100)
        if not isinstance(self.queue_size, int) or self.queue_size < 1:
            raise ValueError(f"parameter ~queue_size = {self.queue_size!r}: expected an integer >= 1")
        for name in ("input_topic", "output_topic"):
            if not getattr(self, name):
                raise ValueError(f"parameter ~{name}: expected a topic name, got ''")

    def on_scan(self, msg):
        self.pub.publish(scan_to_cloud(msg))
        self.translated += 1


def main():
    rospy.init_node("m3_translator")
    M3Translator()
    rospy.spin()

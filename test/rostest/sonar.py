#!/usr/bin/env python3
"""rostest: the sonars and the M3 translator through ROS (test/rostest/sonar.test).

Records are made with the scripting API's collectors (Robot.collect): complete after each step for
the simulator's topics; the translator's m3/points is waited for."""

import math
import unittest

import rospy
import rostest
from sensor_msgs import point_cloud2
from sensor_msgs.msg import LaserScan, PointCloud2
from std_msgs.msg import Float64

from unexmin import Simulation

NS = "/UX_1/"
TOPICS = {"tritech_micron/scan": PointCloud2, "msis/msis_r": Float64, "m3/scan": LaserScan, "m3/points": PointCloud2}
SECONDS = 2.0  # [s] of sim time per record
M3_RATE = 40.0  # [Hz] urdf/properties.xacro m3_rate
MSIS_RATE = 25.0  # [steps/s] msis_step_rate
MSIS_STEP = math.radians(0.9)


class Sonar(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sim = Simulation(node_name="sonar_test", timeout=60.0)
        cls.ux = cls.sim.robot("UX_1", streams=["tritech_micron/scan", "msis/msis_r", "m3/scan"])

    def record(self):
        """Reset to t = 0 (seed 1), step SECONDS of sim time, return every message of the record."""
        self.sim.reset(seed=1)
        collectors = {t: self.ux.collect(t, c) for t, c in TOPICS.items()}
        self.sim.run_for(SECONDS)
        got = {t: c.messages for t, c in collectors.items()}
        got["m3/points"] = collectors["m3/points"].wait_count(round(M3_RATE * SECONDS))  # the translator's
        for c in collectors.values():
            c.stop()
        return got

    def test_type_names(self):
        published = dict(rospy.get_published_topics())
        for topic, cls in TOPICS.items():
            self.assertEqual(published.get(NS + topic), cls._type, topic)

    def test_rates_in_simulation_time_and_the_head_steps(self):
        got = self.record()
        for topic, rate in (("tritech_micron/scan", MSIS_RATE), ("m3/scan", M3_RATE), ("m3/points", M3_RATE)):
            stamps = [m.header.stamp.to_sec() for m in got[topic]]
            self.assertEqual(len(stamps), round(rate * SECONDS), topic)
            for k, t in enumerate(stamps, start=1):  # sample k at the first 2 ms step at or after k / rate
                self.assertGreaterEqual(t, k / rate - 1e-9, topic)
                self.assertLess(t, k / rate + 0.002 - 1e-9, topic)
        angles = [m.data for m in got["msis/msis_r"]]
        self.assertEqual(len(angles), round(MSIS_RATE * SECONDS))
        for k, a in enumerate(angles):  # continuous from sector_left = -pi
            expected = -math.pi + k * MSIS_STEP
            self.assertAlmostEqual(math.remainder(a - expected, 2 * math.pi), 0.0, delta=1e-9)
        scan = got["tritech_micron/scan"][-1]
        self.assertEqual(scan.header.frame_id, "UX_1/msis_head_link")
        self.assertEqual([f.name for f in scan.fields], ["x", "y", "z", "intensity", "rgb"])
        self.assertEqual(scan.width, 400)

    def test_m3_points_are_at_the_scan_ranges(self):
        got = self.record()
        scans = {m.header.stamp.to_nsec(): m for m in got["m3/scan"]}
        for cloud in got["m3/points"]:
            scan = scans[cloud.header.stamp.to_nsec()]
            valid = [r for r in scan.ranges if math.isfinite(r) and scan.range_min <= r <= scan.range_max]
            pts = list(point_cloud2.read_points(cloud, field_names=("x", "y", "z")))
            self.assertEqual(len(pts), len(valid))
            self.assertLessEqual(len(pts), 256)
            for (x, y, _), r in zip(pts, valid):
                self.assertAlmostEqual(math.hypot(x, y), r, delta=1e-5 * max(1.0, r))
        # End to end (REP-103, the M3's order): beam 0 at -fov/2 (to the right), the last at +fov/2.
        scan = got["m3/scan"][-1]
        self.assertLess(scan.angle_min, scan.angle_max)
        self.assertAlmostEqual(scan.angle_min, -math.radians(60), places=5)
        self.assertAlmostEqual(scan.angle_min + 255 * scan.angle_increment, scan.angle_max, places=5)
        # UX_1 in the tank faces the anchor 1.9 m away, the far wall beyond it: the fan sees something.
        self.assertGreater(max(c.width for c in got["m3/points"]), 50)


if __name__ == "__main__":
    rostest.rosrun("unexmin", "sonar", Sonar)

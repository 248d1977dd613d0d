#!/usr/bin/env python3
"""rostest: the 4 structured-light units through ROS (test/rostest/sls.test): type names and frames of
sls_<i>/points and sls_<i>/scan, every sample of a lockstep step arriving at the camera rate in sim time, the
motor joints in joint_states following the triangle wave, and the points lying in front of their camera at
the distances of the raw fan."""

import math
import unittest

import rospy
import rostest
from sensor_msgs import point_cloud2
from sensor_msgs.msg import JointState, LaserScan, PointCloud2

from unexmin import Simulation

NS = "/UX_1/"
UNITS = range(4)
TOPICS = {**{f"sls_{i}/points": PointCloud2 for i in UNITS}, **{f"sls_{i}/scan": LaserScan for i in UNITS}}
RATE = 10.0  # [Hz] urdf/properties.xacro camera_<i>_fps
SECONDS = 3.0  # [s] of sim time per record
MOTOR = (math.radians(-45), math.radians(45), math.radians(10))  # sls_motor_min, _max, _speed; start 0


def motor_angle(t):
    """The triangle wave from 0, moving up, between the limits."""
    lo, hi, speed = MOTOR
    span = hi - lo
    m = math.fmod(0.0 - lo + speed * t, 2 * span)
    return lo + (m if m <= span else 2 * span - m)


class Sls(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sim = Simulation(node_name="sls_test", timeout=60.0)
        cls.ux = cls.sim.robot("UX_1", streams=[*TOPICS, "joint_states"])

    def record(self):
        """Reset to t = 0 (seed 1), step SECONDS of sim time, return every message of each topic (the
        collectors lose none)."""
        self.sim.reset(seed=1)
        collectors = {t: self.ux.collect(t, c) for t, c in TOPICS.items()}
        self.sim.run_for(SECONDS)
        got = {t: c.messages for t, c in collectors.items()}
        for c in collectors.values():
            c.stop()
        return got

    def test_type_names(self):
        published = dict(rospy.get_published_topics())
        for topic, cls in TOPICS.items():
            self.assertEqual(published.get(NS + topic), cls._type, topic)

    def test_every_sample_arrives_at_the_camera_rate_in_its_frame(self):
        got = self.record()
        for i in UNITS:
            for topic, frame in (
                (f"sls_{i}/points", f"UX_1/camera_{i}_optical_frame"),
                (f"sls_{i}/scan", f"UX_1/sls_{i}_scan_link"),
            ):
                msgs = got[topic]
                self.assertEqual(len(msgs), round(RATE * SECONDS), topic)  # none lost, none extra
                for k, m in enumerate(msgs, start=1):
                    self.assertAlmostEqual(m.header.stamp.to_sec(), k / RATE, delta=0.002, msg=topic)
                    self.assertEqual(m.header.frame_id, frame)
            scan = got[f"sls_{i}/scan"][-1]
            self.assertAlmostEqual(scan.angle_max - scan.angle_min, math.radians(100), places=5)
            self.assertLess(scan.angle_min, scan.angle_max)
            self.assertEqual(len(scan.ranges), 200)

    def test_points_are_in_front_of_their_camera_within_the_laser_range(self):
        got = self.record()
        for i in UNITS:
            widths = [c.width for c in got[f"sls_{i}/points"]]
            self.assertGreater(max(widths), 20, f"unit {i} sees its line in the tank")
            for cloud in got[f"sls_{i}/points"]:
                for x, y, z, s in point_cloud2.read_points(cloud, field_names=("x", "y", "z", "intensity")):
                    self.assertGreater(z, 0.0)  # in front of the lens
                    self.assertLess(math.sqrt(x * x + y * y + z * z), 5.0 + 0.5)  # range_max + baseline
                    self.assertGreaterEqual(s, 1.0)  # at or above the detection level

    def test_motor_joints_follow_the_triangle_wave(self):
        self.record()
        js = self.ux.latest("joint_states", JointState)
        self.assertAlmostEqual(js.header.stamp.to_sec(), SECONDS, delta=1e-6)
        for i in UNITS:
            name = f"UX_1/sls_{i}_motor_joint"
            self.assertIn(name, js.name)
            self.assertAlmostEqual(js.position[js.name.index(name)], motor_angle(SECONDS), delta=1e-6, msg=name)
            self.assertAlmostEqual(abs(js.velocity[js.name.index(name)]), MOTOR[2], delta=1e-6, msg=name)


if __name__ == "__main__":
    rostest.rosrun("unexmin", "sls", Sls)

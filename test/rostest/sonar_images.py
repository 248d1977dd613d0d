#!/usr/bin/env python3
"""rostest: the imaging and side-scan sonars through ROS (test/rostest/sonar_images.test, vehicles_sonars.test).

A robot description carrying both (sonar_images.urdf.xacro) in the tank, or a team whose ROV carries the imaging
sonar and whose AUV the side-scan (~imaging_robot, ~side_scan_robot); the test subscribes to every documented
topic, steps the paused simulator by /sim/step until each has delivered an image, and checks the documented layout:
mono8, frame the sensor link, and the sizes of docs/sonars.md for the default parameters; then, subscribed, that a
second of sim time brings one polar image per ping (~imaging_rate, Hz) and one port line per side-scan ping
(~side_scan_rate, Hz): both sonars ping while someone listens."""

import math
import threading
import time
import unittest

import rospy
import rostest
from sensor_msgs.msg import Image

from unexmin.srv import Step

BEAMS, BINS = 512, 500  # imaging sonar defaults
FAN_WIDTH = 2 * math.ceil(30.0 * math.sin(math.radians(65.0)) / (30.0 / 500) - 1e-9)  # 2 ceil(r sin(fov/2) / s)
SIDE_BINS, WATERFALL_LINES = 1000, 400  # side-scan defaults


def sizes(imaging, side_scan):
    """{topic: (height, width, frame)} for the imaging sonar of robot `imaging` and the side-scan of `side_scan`."""
    return {
        f"/{imaging}/imaging_sonar/polar": (BINS, BEAMS, f"{imaging}/imaging_sonar_link"),
        f"/{imaging}/imaging_sonar/fan": (500, FAN_WIDTH, f"{imaging}/imaging_sonar_link"),
        f"/{side_scan}/side_scan/port": (1, SIDE_BINS, f"{side_scan}/side_scan_link"),
        f"/{side_scan}/side_scan/starboard": (1, SIDE_BINS, f"{side_scan}/side_scan_link"),
        f"/{side_scan}/side_scan/waterfall": (WATERFALL_LINES, 2 * SIDE_BINS, f"{side_scan}/side_scan_link"),
    }


class SonarImages(unittest.TestCase):
    def test_one_image_of_each_topic_with_the_documented_size(self):
        rospy.init_node("sonar_images_test")
        # ~imaging_robot, ~side_scan_robot: the robots carrying each sonar (a team: ROV_1 and AUV_1)
        imaging, side_scan = rospy.get_param("~imaging_robot", "UX_1"), rospy.get_param("~side_scan_robot", "UX_1")
        expected = sizes(imaging, side_scan)
        got, seen, lock = {}, {t: [] for t in expected}, threading.Lock()

        def keep(topic):
            def callback(msg):
                with lock:
                    got.setdefault(topic, msg)
                    if topic.endswith("/polar") or topic.endswith("/port"):
                        seen[topic].append(msg)

            return callback

        subs = [rospy.Subscriber(t, Image, keep(t), queue_size=50) for t in expected]
        rospy.wait_for_service("/sim/step", timeout=60.0)
        step = rospy.ServiceProxy("/sim/step", Step)
        deadline = time.monotonic() + 30.0
        while any(s.get_num_connections() == 0 for s in subs):
            self.assertLess(time.monotonic(), deadline, "the simulator never connected to every topic")
            time.sleep(0.05)
        while True:  # 0.2 s of sim time per step: at least one imaging ping (20 Hz) and one side-scan ping (10 Hz)
            t0 = step(duration=0.2).time
            with lock:
                if len(got) == len(expected):
                    break
            self.assertLess(time.monotonic(), deadline, "no image on %s" % sorted(set(expected) - set(got)))
            time.sleep(0.05)
        for topic, (height, width, frame) in expected.items():
            m = got[topic]
            self.assertEqual((m.height, m.width, m.step, m.encoding), (height, width, width, "mono8"), topic)
            self.assertEqual(len(m.data), height * width, topic)
            self.assertEqual(m.header.frame_id, frame, topic)
            self.assertGreater(m.header.stamp.to_sec(), 0.0, topic)
        azimuths = rospy.get_param(f"/{imaging}/imaging_sonar/beam_azimuths")
        self.assertEqual(len(azimuths), BEAMS)
        self.assertAlmostEqual(azimuths[0], math.radians(65.0) - 0.5 * math.radians(130.0) / BEAMS, places=9)
        self.assertAlmostEqual(
            rospy.get_param(f"/{imaging}/imaging_sonar/range_resolution"), (30.0 - 0.1) / BINS, places=9
        )
        self.assertAlmostEqual(
            rospy.get_param(f"/{side_scan}/side_scan/range_resolution"), (50.0 - 0.1) / SIDE_BINS, places=9
        )
        # While subscribed, every ping is built and published: over 1 s of sim time, one image per ping of each sonar.
        rates = {
            f"/{imaging}/imaging_sonar/polar": rospy.get_param("~imaging_rate", 20.0),
            f"/{side_scan}/side_scan/port": rospy.get_param("~side_scan_rate", 10.0),
        }
        t1 = step(duration=1.0).time
        for topic, rate in rates.items():
            expected_count = math.floor(t1 * rate + 1e-6) - math.floor(t0 * rate + 1e-6)
            self.assertGreaterEqual(expected_count, int(rate) - 1)
            deadline = time.monotonic() + 30.0
            while True:
                with lock:
                    stamps = sorted(
                        {m.header.stamp.to_sec() for m in seen[topic] if t0 < m.header.stamp.to_sec() <= t1}
                    )
                if len(stamps) >= expected_count or time.monotonic() > deadline:
                    break
                time.sleep(0.05)
            self.assertEqual(len(stamps), expected_count, f"{topic} in ({t0}, {t1}] s of sim time at {rate} Hz")
            for a, b in zip(stamps, stamps[1:]):
                self.assertAlmostEqual(b - a, 1.0 / rate, places=6)


if __name__ == "__main__":
    rostest.rosrun("unexmin", "sonar_images", SonarImages)

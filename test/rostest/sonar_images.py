#!/usr/bin/env python3
"""rostest: the imaging and side-scan sonars through ROS (test/rostest/sonar_images.test).

A robot description carrying both (sonar_images.urdf.xacro) in the tank; the test subscribes to every documented
topic, steps the paused simulator by /sim/step until each has delivered an image, and checks the documented layout:
mono8, frame the sensor link, and the sizes of docs/sonars.md for the default parameters."""

import math
import threading
import time
import unittest

import rospy
import rostest
from sensor_msgs.msg import Image

from unexmin.srv import Step

NS = "/UX_1/"
BEAMS, BINS = 512, 500  # imaging sonar defaults
FAN_WIDTH = 2 * math.ceil(30.0 * math.sin(math.radians(65.0)) / (30.0 / 500) - 1e-9)  # 2 ceil(r sin(fov/2) / s)
SIDE_BINS, WATERFALL_LINES = 1000, 400  # side-scan defaults
SIZES = {  # topic: (height, width, frame)
    "imaging_sonar/polar": (BINS, BEAMS, "UX_1/imaging_sonar_link"),
    "imaging_sonar/fan": (500, FAN_WIDTH, "UX_1/imaging_sonar_link"),
    "side_scan/port": (1, SIDE_BINS, "UX_1/side_scan_link"),
    "side_scan/starboard": (1, SIDE_BINS, "UX_1/side_scan_link"),
    "side_scan/waterfall": (WATERFALL_LINES, 2 * SIDE_BINS, "UX_1/side_scan_link"),
}


class SonarImages(unittest.TestCase):
    def test_one_image_of_each_topic_with_the_documented_size(self):
        rospy.init_node("sonar_images_test")
        got, lock = {}, threading.Lock()

        def keep(topic):
            def callback(msg):
                with lock:
                    got.setdefault(topic, msg)

            return callback

        subs = [rospy.Subscriber(NS + t, Image, keep(t), queue_size=5) for t in SIZES]
        rospy.wait_for_service("/sim/step", timeout=60.0)
        step = rospy.ServiceProxy("/sim/step", Step)
        deadline = time.monotonic() + 30.0
        while any(s.get_num_connections() == 0 for s in subs):
            self.assertLess(time.monotonic(), deadline, "the simulator never connected to every topic")
            time.sleep(0.05)
        while True:  # 0.2 s of sim time per step: at least one imaging ping (20 Hz) and one side-scan ping (10 Hz)
            step(duration=0.2)
            with lock:
                if len(got) == len(SIZES):
                    break
            self.assertLess(time.monotonic(), deadline, "no image on %s" % sorted(set(SIZES) - set(got)))
            time.sleep(0.05)
        for topic, (height, width, frame) in SIZES.items():
            m = got[topic]
            self.assertEqual((m.height, m.width, m.step, m.encoding), (height, width, width, "mono8"), topic)
            self.assertEqual(len(m.data), height * width, topic)
            self.assertEqual(m.header.frame_id, frame, topic)
            self.assertGreater(m.header.stamp.to_sec(), 0.0, topic)
        azimuths = rospy.get_param(NS + "imaging_sonar/beam_azimuths")
        self.assertEqual(len(azimuths), BEAMS)
        self.assertAlmostEqual(azimuths[0], math.radians(65.0) - 0.5 * math.radians(130.0) / BEAMS, places=9)
        self.assertAlmostEqual(rospy.get_param(NS + "imaging_sonar/range_resolution"), (30.0 - 0.1) / BINS, places=9)
        self.assertAlmostEqual(rospy.get_param(NS + "side_scan/range_resolution"), (50.0 - 0.1) / SIDE_BINS, places=9)


if __name__ == "__main__":
    rostest.rosrun("unexmin", "sonar_images", SonarImages)

#!/usr/bin/env python3
"""rostest: the five cameras through ROS (test/rostest/cameras_visual.test, cameras_operational.test).

Visual mode: camera_<i>/image_raw (sensor_msgs/Image, rgb8) and camera_<i>/camera_info (sensor_msgs/CameraInfo)
exist with those types, one message per 1/fps s of sim time (counted over a /sim/step of SECONDS), frame
camera_<i>_optical_frame, stamps k/fps, the image the size CameraInfo describes, CameraInfo's K from the xacro's
hfov at the render scale. Operational mode: camera_info alone, no image topic and no image."""

import math
import unittest

import rospy
import rostest
from sensor_msgs.msg import CameraInfo, Image

from unexmin import Simulation

NS = "/UX_1/"
CAMERAS = range(5)
FPS = 10.0  # camera_overrides.xacro
SCALE = 0.05  # camera_overrides.xacro: camera_render_scale
WIDTH, HEIGHT = round(SCALE * 2054), round(SCALE * 1544)  # properties.xacro camera_width/height
HFOV = math.radians(80.0)  # properties.xacro camera_hfov
DISTORTION = [-0.1, 0.02, 0.0, 0.0, 0.0]  # properties.xacro camera_distortion
SECONDS = 1.0  # [s] of sim time per record


class Cameras(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sim = Simulation(node_name="cameras_test", timeout=60.0)
        cls.mode = rospy.get_param("/sim/mode")  # set by the launch file's mode:=
        cls.topics = {f"camera_{i}/camera_info": CameraInfo for i in CAMERAS}
        if cls.mode == "visual":
            cls.topics.update({f"camera_{i}/image_raw": Image for i in CAMERAS})
        cls.ux = cls.sim.robot("UX_1", streams=list(cls.topics))
        cls.sim.reset(seed=1)
        collectors = {t: cls.ux.collect(t, c) for t, c in cls.topics.items()}  # every message, none lost
        cls.sim.run_for(SECONDS)
        cls.got = {t: c.messages for t, c in collectors.items()}
        for c in collectors.values():
            c.stop()

    def test_types(self):
        published = dict(rospy.get_published_topics())
        for i in CAMERAS:
            self.assertEqual(published.get(f"{NS}camera_{i}/camera_info"), "sensor_msgs/CameraInfo")
            if self.mode == "visual":
                self.assertEqual(published.get(f"{NS}camera_{i}/image_raw"), "sensor_msgs/Image")
            else:
                self.assertNotIn(f"{NS}camera_{i}/image_raw", published)

    def test_rates_and_frames_in_simulation_time(self):
        for topic in self.topics:
            msgs = self.got[topic]
            self.assertEqual(len(msgs), round(FPS * SECONDS), topic)
            i = topic.split("/")[0].split("_")[1]
            for k, m in enumerate(msgs, start=1):
                # Sample k at the first 2 ms physics step at or after k / fps.
                self.assertGreaterEqual(m.header.stamp.to_sec(), k / FPS - 1e-9, topic)
                self.assertLess(m.header.stamp.to_sec(), k / FPS + 0.002 - 1e-9, topic)
                self.assertEqual(m.header.frame_id, f"UX_1/camera_{i}_optical_frame", topic)

    def test_camera_info_describes_the_published_image(self):
        f = (2054 / 2) / math.tan(HFOV / 2) * (WIDTH / 2054)
        fy = (2054 / 2) / math.tan(HFOV / 2) * (HEIGHT / 1544)
        for i in CAMERAS:
            info = self.got[f"camera_{i}/camera_info"][-1]
            self.assertEqual((info.width, info.height), (WIDTH, HEIGHT))
            self.assertEqual(info.distortion_model, "plumb_bob")
            for a, b in zip(info.D, DISTORTION):
                self.assertAlmostEqual(a, b, places=12)
            expected_k = [f, 0, (WIDTH - 1) / 2, 0, fy, (HEIGHT - 1) / 2, 0, 0, 1]
            for a, b in zip(info.K, expected_k):
                self.assertAlmostEqual(a, b, places=9)
            self.assertEqual(list(info.R), [1, 0, 0, 0, 1, 0, 0, 0, 1])
            self.assertEqual(list(info.P), expected_k[0:3] + [0] + expected_k[3:6] + [0] + expected_k[6:9] + [0])
            if self.mode == "visual":
                image = self.got[f"camera_{i}/image_raw"][-1]
                self.assertEqual((image.width, image.height), (info.width, info.height))
                self.assertEqual(image.encoding, "rgb8")
                self.assertEqual(image.step, 3 * image.width)
                self.assertEqual(len(image.data), 3 * image.width * image.height)

    def test_visual_mode_shows_the_lit_wall_and_operational_mode_no_image(self):
        if self.mode != "visual":
            # Operational: no image was recorded and the simulator advertises none.
            self.assertFalse([t for t in self.got if t.endswith("image_raw")])
            self.assertFalse([t for t, _ in rospy.get_published_topics() if t.endswith("image_raw")])
            return
        self.assertEqual(rospy.get_param("/simulator/visibility"), "low")
        # Camera 0 faces the tank wall, lit by SLS unit 0's LED beside it: not a black image.
        data = self.got["camera_0/image_raw"][-1].data
        self.assertGreater(sum(data) / len(data), 1.0)


if __name__ == "__main__":
    rostest.rosrun("unexmin", "cameras", Cameras)

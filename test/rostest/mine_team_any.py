#!/usr/bin/env python3
"""rostest: any team list in the mine (mine_team_any.test: vehicles:=bluerov2_heavy,ux1,bluerov2_heavy,remus100).

- The simulator runs ROV_1, UX_1, ROV_2, AUV_1 in that order; every namespace publishes its odometry, and tf holds
  world -> <robot>/base_link for each.
- No two robots start within a hull of each other: the distance of every pair of spawn positions is at least the sum
  of their hull radii (half the diagonal of the description's <bounding_box>, else its <radius>).
- Lockstep delivers every cloud: over T s of sim time the test receives rate x T clouds of each ROV's imaging sonar,
  and the mapper takes rate x T clouds of each of its sources (the sonar clouds, the UX-1's M3 scans, 4 DVL beams of
  every robot), the rates read from the robot descriptions.
- The merged map holds voxels only an ROV's imaging sonar could have seen: in that ROV's own map, in no other robot's,
  and on the sonar's central plane (elevation 0 in its frame, where the cloud places its points; the DVL beams point
  25 deg off straight down).
"""

import itertools
import math
import threading
import unittest
import xml.etree.ElementTree as ET

import numpy as np
import rospy
import rostest
from nav_msgs.msg import Odometry
from sensor_msgs import point_cloud2
from sensor_msgs.msg import PointCloud2
from tf2_msgs.msg import TFMessage

from unexmin import Simulation
from unexmin.geometry import rpy_matrix, rpy_of
from unexmin.msg import MapperStats
from unexmin.scripting.launcher import wait_for

NAMES = ["ROV_1", "UX_1", "ROV_2", "AUV_1"]
ROVS = ["ROV_1", "ROV_2"]
SECONDS = 2.0  # sim time of the counted run


def xyz(p):
    return np.array([p.x, p.y, p.z])


def description(robot):
    return ET.fromstring(rospy.get_param(f"/{robot}/robot_description"))


def hull_radius(robot):
    hydro = description(robot).find(".//hydrodynamics")
    box = hydro.find("bounding_box")
    if box is not None:
        return 0.5 * float(np.linalg.norm([float(v) for v in box.get("size").split()]))
    return float(hydro.find("radius").get("value"))


def sensor_rate(robot, kind):
    """Rate [Hz] of the robot's sensor of type `kind` (None when it has none)."""
    found = [s for s in description(robot).iter("sensor") if s.get("type") == kind]
    return float(found[0].get("rate")) if found else None


def sonar_mount(robot):
    """(R, t) of <robot>/imaging_sonar_link in <robot>/base_link through the chain of fixed joints."""
    joints = {j.find("child").get("link"): j for j in description(robot).iter("joint")}
    rot, trans, link = np.eye(3), np.zeros(3), f"{robot}/imaging_sonar_link"
    while link in joints and link != f"{robot}/base_link":
        origin = joints[link].find("origin")
        r = rpy_matrix([float(v) for v in origin.get("rpy", "0 0 0").split()])
        t = np.array([float(v) for v in origin.get("xyz", "0 0 0").split()])
        rot, trans = r @ rot, r @ trans + t
        link = joints[link].find("parent").get("link")
    return rot, trans


class MineTeamAny(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sim = Simulation(node_name="mine_team_any_test", timeout=90.0)
        cls.lock = threading.Lock()
        cls.clouds = {r: 0 for r in ROVS}
        cls.stats = None
        cls.odom = {n: 0 for n in NAMES}
        cls.subs = [
            rospy.Subscriber(f"/{r}/imaging_sonar/points", PointCloud2, cls.on_cloud, r, queue_size=1000) for r in ROVS
        ]
        cls.subs += [rospy.Subscriber(f"/{n}/odom", Odometry, cls.on_odom, n, queue_size=1000) for n in NAMES]
        cls.subs.append(rospy.Subscriber("/mapper/stats", MapperStats, cls.on_stats, queue_size=10))
        wait_for(lambda: all(s.get_num_connections() > 0 for s in cls.subs), 60.0, "the team's topics")
        cls.sim.step(1)
        cls.start = {n: xyz(cls.sim.robot(n, streams="none").odom().pose.pose.position) for n in NAMES}
        wait_for(lambda: cls.stats is not None and cls.stats.pending == 0, 30.0, "the mapper's statistics")
        with cls.lock:
            cls.clouds = {r: 0 for r in ROVS}
            cls.before = cls.stats.clouds_received
        cls.sim.run_for(SECONDS)

    @classmethod
    def on_cloud(cls, msg, robot):
        with cls.lock:
            cls.clouds[robot] += 1

    @classmethod
    def on_odom(cls, msg, robot):
        with cls.lock:
            cls.odom[robot] += 1

    @classmethod
    def on_stats(cls, msg):
        with cls.lock:
            cls.stats = msg

    def test_the_simulator_runs_the_list_in_order_and_every_namespace_publishes_odometry(self):
        self.assertEqual(list(self.sim.robots), NAMES)
        with self.lock:
            for n in NAMES:
                self.assertGreater(self.odom[n], 0, f"/{n}/odom")

    def test_tf_has_every_base_frame(self):
        children, lock = set(), threading.Lock()

        def on_tf(msg):
            with lock:
                children.update((t.header.frame_id, t.child_frame_id) for t in msg.transforms)

        sub = rospy.Subscriber("/tf", TFMessage, on_tf, queue_size=100)
        wait_for(lambda: sub.get_num_connections() > 0, 30.0, "/tf")

        def complete():
            self.sim.step(10)
            with lock:
                return {("world", f"{n}/base_link") for n in NAMES} <= children

        wait_for(complete, 30.0, "world -> <robot>/base_link of every robot")
        sub.unregister()

    def test_no_two_robots_start_within_a_hull_of_each_other(self):
        rospy.loginfo("spawns: %s", {n: p.round(3).tolist() for n, p in self.start.items()})
        for a, b in itertools.combinations(NAMES, 2):
            gap = np.linalg.norm(self.start[a] - self.start[b])
            self.assertGreaterEqual(gap, hull_radius(a) + hull_radius(b), f"{a} and {b} start {gap:.2f} m apart")

    def test_lockstep_delivers_every_cloud(self):
        rate = sensor_rate("ROV_1", "imaging_sonar")
        expected = round(rate * SECONDS)
        wait_for(lambda: all(c >= expected for c in self.clouds.values()), 30.0, "every ROV's sonar clouds")
        with self.lock:
            self.assertEqual(self.clouds, {r: expected for r in ROVS})
        # the mapper's sources: sonar clouds of the ROVs, M3 scans of the UX-1, 4 DVL beams of every robot
        per_source = [sensor_rate(r, "imaging_sonar") for r in ROVS] + [sensor_rate("UX_1", "m3")]
        per_source += [sensor_rate(n, "dvl") for n in NAMES for _ in range(4)]
        want = self.before + sum(round(r * SECONDS) for r in per_source)
        wait_for(lambda: self.stats.clouds_received >= want and self.stats.pending == 0, 60.0, "the mapper's clouds")
        with self.lock:
            self.assertEqual(self.stats.clouds_received, want)
            self.assertEqual(self.stats.clouds_dropped, 0)

    def voxels(self, topic):
        """Centres of the occupied voxels of the latched map `topic`, as integer cells of 0.1 m."""
        msg = rospy.wait_for_message(topic, PointCloud2, timeout=30.0)
        return {tuple(np.floor(np.array(p) / 0.1).astype(int)) for p in point_cloud2.read_points(msg, ("x", "y", "z"))}

    def test_the_merged_map_holds_voxels_only_an_rovs_sonar_saw(self):
        wait_for(lambda: self.stats.clouds_received > self.before and self.stats.pending == 0, 60.0, "the mapper")
        merged = self.voxels("/octomap_point_cloud_centers")
        own = {n: self.voxels(f"/{n}/octomap_point_cloud_centers") for n in NAMES}
        self.assertTrue(own["AUV_1"], "the AUV's DVL ranges put nothing in its map")
        for rov in ROVS:
            others = set().union(*(own[n] for n in NAMES if n != rov))
            only = (own[rov] - others) & merged
            odom = self.sim.robot(rov, streams="none").odom().pose.pose
            body, at = rpy_matrix(rpy_of(odom.orientation)), xyz(odom.position)
            mount_r, mount_t = sonar_mount(rov)
            sonar_r, sonar_t = body @ mount_r, body @ mount_t + at
            plane = [
                v for v in only if abs((sonar_r.T @ ((np.array(v) + 0.5) * 0.1 - sonar_t))[2]) <= 0.1 * math.sqrt(3)
            ]
            rospy.loginfo("%s: %d voxels of its own, %d on its sonar plane", rov, len(only), len(plane))
            self.assertGreater(len(plane), 20, f"{rov}: {len(only)} voxels of its own, {len(plane)} on its sonar plane")


if __name__ == "__main__":
    rostest.rosrun("unexmin", "mine_team_any", MineTeamAny)

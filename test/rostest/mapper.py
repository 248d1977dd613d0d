#!/usr/bin/env python3
"""rostest: the mapper node (launch: mapper.test; docs/mapping.md).

- Every cloud the simulator publishes reaches the map: over a lockstep run of T s, the mapper receives and
  inserts exactly (40 + 4 x 10) T clouds per mapped robot (M3 at 40 Hz, four SLS units at 10 Hz), drops none.
- The tank mapped by two robots turning in place: occupied voxels on the tank's walls and anchor
  (precision against the collision meshes >= 0.95); the saved .bt is read by OctoMap's own bt2vrml with the
  number of occupied leaves the node reports; the one map covers what each robot's own map holds, and each
  robot contributes voxels the other did not see.
- The outputs (octomap_binary, occupied_cells_vis_array, octomap_point_cloud_centers) carry the same map.
- A simulation reset (time back to 0) with the robots turning the other way, while a second node publishes
  UX_1's base_link 50 m away on /tf: the map is still the tank (the mapper clears its tf buffer on the jump back
  and takes each frame from its first publisher only), and no cloud is dropped.
- ~reset empties the map; SIGINT to the mapper leaves a valid map in ~map_file.
"""

import os
import re
import signal
import subprocess
import tempfile
import unittest
from xmlrpc.client import ServerProxy

import numpy as np
import rosgraph
import rospy
import rostest
from geometry_msgs.msg import TransformStamped
from octomap_msgs.msg import Octomap
from sensor_msgs import point_cloud2
from sensor_msgs.msg import PointCloud2
from std_srvs.srv import Empty
from tf2_msgs.msg import TFMessage
from visualization_msgs.msg import MarkerArray

from unexmin import Simulation
from unexmin.control.allocation import ThrusterAllocator
from unexmin.map_quality import expand, read_bt
from unexmin.msg import MapperStats
from unexmin.scripting.launcher import wait_for
from unexmin.srv import SaveMap
from unexmin.worlds.files import world_path, world_triangles
from unexmin.worlds.meshes import sample_surface

MAPPED = ("UX_1", "UX_3")
CLOUDS_PER_S = 40 + 4 * 10
TURN_S = 12.0


def precision(centres, tris, tau):
    """Fraction of centres within tau of an area sample (spacing tau/4) of the triangles: a cell hash of the
    samples (cell = tau), each centre checked against the 27 cells around it (no scipy under rostest)."""
    samples, _ = sample_surface(tris, tau / 4.0)
    cells = {}
    for key, p in zip(map(tuple, np.floor(samples / tau).astype(int)), samples):
        cells.setdefault(key, []).append(p)
    cells = {k: np.array(v) for k, v in cells.items()}
    near = 0
    for c in centres:
        k = np.floor(c / tau).astype(int)
        best = np.inf
        for d in np.ndindex(3, 3, 3):
            pts = cells.get((k[0] + d[0] - 1, k[1] + d[1] - 1, k[2] + d[2] - 1))
            if pts is not None:
                best = min(best, float(np.min(np.linalg.norm(pts - c, axis=1))))
        near += best <= tau
    return near / len(centres)


def bt2vrml_count(path):
    with tempfile.TemporaryDirectory() as tmp:
        copy = os.path.join(tmp, "m.bt")
        with open(path, "rb") as src, open(copy, "wb") as dst:
            dst.write(src.read())
        out = subprocess.run(["bt2vrml", copy], capture_output=True, text=True, timeout=120)
    m = re.search(r"Finished writing (\d+) voxels", out.stdout)
    assert m, out.stdout + out.stderr
    return int(m.group(1))


class Mapper(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sim = Simulation(node_name="mapper_test", timeout=60.0)
        cls.stats = None
        rospy.Subscriber("/mapper/stats", MapperStats, cls._on_stats, queue_size=10)
        wait_for(lambda: cls.stats is not None, 60.0, "/mapper/stats")
        master = rosgraph.Master(rospy.get_name())
        topics = {f"/{r}/m3/scan" for r in MAPPED} | {f"/{r}/sls_{i}/points" for r in MAPPED for i in range(4)}

        def connected():
            bus = ServerProxy(master.lookupNode("/simulator")).getBusInfo(rospy.get_name())[2]
            return topics <= {c[4] for c in bus if c[1] == "/mapper" and c[2] == "o" and c[5]}

        wait_for(connected, 60.0, "the simulator's sensor topics to connect to the mapper")
        cls.save = rospy.ServiceProxy("/mapper/save_map", SaveMap)
        cls.reset = rospy.ServiceProxy("/mapper/reset", Empty)
        cls.save.wait_for_service(30.0)
        cls.tmp = tempfile.mkdtemp(prefix="unexmin_mapper_")
        cls.before = cls.settled()
        allocator = ThrusterAllocator()
        for name, n in (("UX_1", 2.0), ("UX_3", -2.0)):
            cls.sim.robot(name).thrusts(allocator.allocate((0, 0, 0, 0, 0, n))[0])
        cls.sim.run_for(TURN_S)
        cls.after = cls.settled(cls.before.clouds_received + int(round(CLOUDS_PER_S * TURN_S)) * len(MAPPED))

    @classmethod
    def _on_stats(cls, msg):
        cls.stats = msg

    @classmethod
    def settled(cls, received=0):
        """The stats once the mapper has received `received` clouds and inserted all it received."""

        def done():
            s = cls.stats
            return (
                s
                if s.clouds_received >= received
                and s.pending == 0
                and s.clouds_inserted + s.clouds_dropped == s.clouds_received
                else None
            )

        # One stats message is one consistent snapshot (the mapper inserts and reports in one thread).
        return wait_for(done, 60.0, f"the mapper to receive {received} clouds and insert them")

    def test_every_published_cloud_is_inserted(self):
        got = self.after.clouds_received - self.before.clouds_received
        self.assertEqual(got, int(round(CLOUDS_PER_S * TURN_S)) * len(MAPPED))
        self.assertEqual(self.after.clouds_dropped, 0)
        self.assertEqual(self.after.clouds_inserted, self.after.clouds_received)
        self.assertGreater(self.after.points_inserted, 1000)

    def test_map_is_the_tank_and_octomap_tools_read_it(self):
        path = os.path.join(self.tmp, "all.bt")
        res = self.save(path=path, robot="")
        self.assertTrue(res.success, res.message)
        self.assertGreater(res.occupied_leaves, 500)
        self.assertEqual(bt2vrml_count(path), res.occupied_leaves)
        centres, sizes = expand(*read_bt(path))
        self.assertGreaterEqual(precision(centres, world_triangles(world_path("tank")), 0.1), 0.95)

    def test_one_map_covers_both_robots(self):
        maps = {}
        for robot in ("",) + MAPPED:
            path = os.path.join(self.tmp, f"map_{robot or 'all'}.bt")
            res = self.save(path=path, robot=robot)
            self.assertTrue(res.success, res.message)
            centres, _ = expand(*read_bt(path))
            maps[robot] = {tuple(k) for k in np.rint(centres * 20).astype(int)}  # keys of 0.05 m half-voxels
        only_1, only_3 = maps["UX_1"] - maps["UX_3"], maps["UX_3"] - maps["UX_1"]
        self.assertGreater(len(only_1), 100)
        self.assertGreater(len(only_3), 100)
        union = maps["UX_1"] | maps["UX_3"]
        self.assertGreaterEqual(len(union & maps[""]) / len(union), 0.95)
        self.assertGreaterEqual(len(only_1 & maps[""]) / len(only_1), 0.9)
        self.assertGreaterEqual(len(only_3 & maps[""]) / len(only_3), 0.9)
        bad = self.save(path=os.path.join(self.tmp, "x.bt"), robot="UX_2")
        self.assertFalse(bad.success)
        self.assertIn("UX_2", bad.message)

    def test_outputs_carry_the_map(self):
        leaves = self.stats.occupied_leaves
        got = {}
        subs = [
            rospy.Subscriber("/octomap_binary", Octomap, lambda m: got.update(binary=m)),
            rospy.Subscriber("/occupied_cells_vis_array", MarkerArray, lambda m: got.update(markers=m)),
            rospy.Subscriber("/octomap_point_cloud_centers", PointCloud2, lambda m: got.update(centers=m)),
        ]
        try:
            wait_for(lambda: len(got) == 3, 30.0, "the three map outputs")
        finally:
            for s in subs:
                s.unregister()
        b = got["binary"]
        self.assertTrue(b.binary)
        self.assertEqual(b.id, "OcTree")
        self.assertAlmostEqual(b.resolution, 0.1)
        self.assertEqual(b.header.frame_id, "world")
        self.assertGreater(len(b.data), 1000)
        cubes = sum(len(m.points) for m in got["markers"].markers)
        self.assertEqual(cubes, leaves)
        for m in got["markers"].markers:
            self.assertEqual(len(m.colors), len(m.points))
        zs = [(p.z, c.b - c.r) for m in got["markers"].markers for p, c in zip(m.points, m.colors)]
        zs.sort()
        self.assertGreater(zs[0][1], zs[-1][1])  # low cubes bluer than high ones
        self.assertEqual(got["centers"].width * got["centers"].height, leaves)
        pts = np.array(list(point_cloud2.read_points(got["centers"], field_names=("x", "y", "z"))))
        self.assertTrue(np.all(np.abs(pts[:, 0]) < 3.3) and np.all(np.abs(pts[:, 1]) < 2.3))  # inside the tank

    def test_y_sim_reset_and_a_second_tf_publisher_leave_the_map_right(self):
        self.reset()
        wait_for(lambda: self.stats.occupied_leaves == 0, 10.0, "an empty map after ~reset")
        rogue = rospy.Publisher("/tf", TFMessage, queue_size=100)
        wait_for(lambda: rogue.get_num_connections() >= 1, 30.0, "the mapper to hear /tf of the test")
        before = self.stats
        self.sim.reset()
        allocator = ThrusterAllocator()
        for name, n in (("UX_1", -2.0), ("UX_3", 2.0)):  # the other way round than before the reset
            self.sim.robot(name).thrusts(allocator.allocate((0, 0, 0, 0, 0, n))[0])
        for k in range(41):  # UX_1 50 m away over the whole run to come, a sample every 0.05 s
            t = TransformStamped()
            t.header.frame_id = "world"
            t.header.stamp = rospy.Time.from_sec(0.05 * k)
            t.child_frame_id = "UX_1/base_link"
            t.transform.translation.x = 50.0
            t.transform.rotation.w = 1.0
            rogue.publish(TFMessage([t]))
        self.sim.run_for(2.0)
        after = self.settled(before.clouds_received + int(round(CLOUDS_PER_S * 2.0)) * len(MAPPED))
        rogue.unregister()
        self.assertEqual(after.clouds_dropped, before.clouds_dropped)
        path = os.path.join(self.tmp, "after_reset.bt")
        res = self.save(path=path, robot="")
        self.assertTrue(res.success, res.message)
        self.assertGreater(res.occupied_leaves, 200)
        centres, _ = expand(*read_bt(path))
        self.assertTrue(np.all(np.abs(centres[:, 0]) < 3.3) and np.all(np.abs(centres[:, 1]) < 2.3))
        self.assertGreaterEqual(precision(centres, world_triangles(world_path("tank")), 0.1), 0.95)

    def test_z_reset_then_sigint_leaves_a_valid_map(self):
        self.reset()
        wait_for(lambda: self.stats.occupied_leaves == 0, 10.0, "an empty map after ~reset")
        received = self.stats.clouds_received
        self.sim.run_for(2.0)
        s = self.settled(received + int(round(CLOUDS_PER_S * 2.0)) * len(MAPPED))
        wait_for(lambda: self.stats.occupied_leaves > 0, 10.0, "a map again after stepping")
        leaves = self.stats.occupied_leaves
        map_file = rospy.get_param("/mapper/map_file")
        master = rosgraph.Master(rospy.get_name())
        pid = ServerProxy(master.lookupNode("/mapper")).getPid(rospy.get_name())[2]
        os.kill(pid, signal.SIGINT)
        wait_for(
            lambda: not os.path.exists(f"/proc/{pid}") or open(f"/proc/{pid}/stat").read().split()[2] == "Z",
            30.0,
            "the mapper to exit on SIGINT",
        )
        self.assertTrue(os.path.exists(map_file), map_file)
        self.assertEqual(bt2vrml_count(map_file), leaves)
        self.assertGreater(s.clouds_inserted, 0)
        os.remove(map_file)


if __name__ == "__main__":
    rostest.rosrun("unexmin", "mapper", Mapper)

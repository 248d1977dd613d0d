#!/usr/bin/env python3
"""rostest: three UX robots in the mine through a real roscore (launch: mine_multi.test).

- Each robot follows its own command and only its own: with all three commanded differently, every
  robot ends exactly where it ends when it alone is commanded (lockstep is deterministic), and moves
  along the commanded axis (surge, heave down, yaw) by the amount the thesis allocation predicts.
- No topic crosses namespaces: every /UX_k/ topic is used only by the simulator, nodes of /UX_k/ and
  this test; nodes of /UX_k/ use no other robot's topics; every frame a robot publishes is UX_k/...
- Robots collide with each other and with the mine (Bullet spheres against the 1.13M-triangle mesh).
"""

import json
import math
import os
import threading
import unittest

import numpy as np
import rosgraph
import rospkg
import rospy
import rostest
import rostopic
from tf2_msgs.msg import TFMessage

from unexmin import Simulation
from unexmin.geometry import yaw_of
from unexmin.scripting.launcher import wait_for
from unexmin.topics import ESC_COMMAND_TOPIC

NAMES = ["UX_1", "UX_2", "UX_3"]
R_HULL = 0.3  # [m]
# Thesis allocation matrix (eq. 5.12): rows X, Y, Z, N (K and M are zero), columns M0..M7.
A_X = np.array([0.5, 0.0, -0.5, 0.0, 0.5, 0.0, -0.5, 0.0])
A_Y = np.array([-0.25, -0.25, -0.25, 0.25, 0.25, -0.25, 0.25, -0.25])
A_Z = np.array([0.0, -0.5, 0.0, -0.5, 0.0, 0.5, 0.0, -0.5])
A_N = np.array([-0.25, 0.0, 0.25, 0.0, 0.25, 0.0, -0.25, 0.0])
SCALE = 20.0  # [N] per unit of an allocation row
COMMANDS = {"UX_1": SCALE * A_X, "UX_2": -SCALE * A_Z, "UX_3": 0.5 * SCALE * A_N}  # surge, heave down, yaw
GLOBAL_TOPICS = {"/rosout", "/rosout_agg", "/clock", "/tf", "/tf_static", "/current"}
SEED = 2


def pose(odom):
    p = odom.pose.pose.position
    return np.array([p.x, p.y, p.z, yaw_of(odom.pose.pose.orientation)])


def surge_1d(force, seconds, dt=1e-4):
    """Distance [m] from rest of a UX-1 (rigid + added mass 1.5 rho V, quadratic drag 1/2 rho Cd pi R^2,
    Stokes drag 6 pi mu R) under a force [N] applied through first-order thrusters (tau 0.1 s)."""
    rho, volume = 1000.0, 4.0 / 3.0 * math.pi * R_HULL**3
    mass, k_quad, k_lin = 1.5 * rho * volume, 0.5 * rho * 0.47 * math.pi * R_HULL**2, 6.0 * math.pi * 1e-3 * R_HULL
    v = x = thrust = 0.0
    alpha = 1.0 - math.exp(-dt / 0.1)
    for _ in range(int(round(seconds / dt))):
        thrust += alpha * (force - thrust)
        v += dt * (thrust - k_quad * v * abs(v) - k_lin * v) / mass
        x += dt * v
    return x


def manifest():
    path = os.path.join(rospkg.RosPack().get_path("unexmin"), "worlds", "meshes", "mine", "mine.json")
    with open(path) as f:
        return json.load(f)


class MineMulti(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sim = Simulation(node_name="mine_multi_test", timeout=60.0)
        cls.ux = {n: cls.sim.robot(n, streams="none") for n in NAMES}  # dynamics; the topics test subscribes its own

    def start(self):
        self.sim.reset(seed=SEED)
        self.sim.step(1)
        return {n: pose(self.ux[n].odom()) for n in NAMES}

    def run_commands(self, commands, seconds):
        start = self.start()
        for n, thrusts in commands.items():
            self.ux[n].thrusts(thrusts)
        self.sim.run_for(seconds)
        return start, {n: pose(self.ux[n].odom()) for n in NAMES}

    def test_each_robot_follows_its_own_command_and_only_its_own(self):
        seconds = 3.0
        start, together = self.run_commands(COMMANDS, seconds)
        _, idle = self.run_commands({}, seconds)
        for n in NAMES:
            _, alone = self.run_commands({n: COMMANDS[n]}, seconds)
            np.testing.assert_allclose(together[n], alone[n], atol=1e-6, err_msg=f"{n} is moved by the others")
            for other in NAMES:
                if other != n:
                    np.testing.assert_allclose(
                        alone[other], idle[other], atol=1e-6, err_msg=f"{n}'s command moved {other}"
                    )
        # Each along its own axis, net of the current's drift (the idle run); surge by the distance of
        # the 1-D model of tank_thrust.py (the current, 0.03 m/s, shifts the quadratic drag by ~1 %).
        moved = {n: together[n] - idle[n] for n in NAMES}
        expected = surge_1d(SCALE * np.abs(A_X).sum() * math.cos(math.pi / 4), seconds - 1.0 / self.sim.physics_rate)
        self.assertAlmostEqual(moved["UX_1"][0], expected, delta=0.03 * expected)
        self.assertLess(moved["UX_2"][2], -0.5)
        self.assertLess(np.abs(moved["UX_1"][1:]).max(), 0.01)
        self.assertLess(np.abs(moved["UX_2"][[0, 1, 3]]).max(), 0.01)
        self.assertGreater(abs(math.remainder(moved["UX_3"][3], 2 * math.pi)), 0.3)
        self.assertLess(np.abs(moved["UX_3"][:3]).max(), 0.01)

    def test_no_topic_crosses_namespaces(self):
        frames, lock = {}, threading.Lock()

        def on_tf(msg):
            caller = msg._connection_header["callerid"]
            with lock:
                for t in msg.transforms:
                    frames.setdefault(caller, set()).add((t.header.frame_id, t.child_frame_id))

        subs = [rospy.Subscriber(t, TFMessage, on_tf, queue_size=100) for t in ("/tf", "/tf_static")]
        headers = {}
        master = rosgraph.Master(rospy.get_name())
        for topic, _ in master.getPublishedTopics("/"):
            if any(topic.startswith(f"/{n}/") for n in NAMES):
                cls = rostopic.get_topic_class(topic)[0]
                if cls is not None and "header" in cls.__slots__:
                    headers[topic] = None
                    subs.append(
                        rospy.Subscriber(topic, cls, lambda m, t=topic: headers.__setitem__(t, m.header), queue_size=1)
                    )
        wait_for(lambda: all(s.get_num_connections() > 0 for s in subs), 30.0, "connections to every robot topic")
        self.start()

        def complete():
            self.sim.run_for(0.1)
            with lock:
                nodes = set(frames)
            return (
                all(headers.get(f"/{n}/{t}") is not None for n in NAMES for t in ("odom", "joint_states"))
                and {"/simulator", *(f"/{n}/robot_state_publisher" for n in NAMES)} <= nodes
            )

        wait_for(complete, 30.0, "odometry, joint states and tf of every robot")
        publishers, subscribers, _ = master.getSystemState()
        me = rospy.get_name()
        for kind, table in (("published", publishers), ("subscribed", subscribers)):
            for topic, nodes in table:
                owner = next((n for n in NAMES if topic.startswith(f"/{n}/")), None)
                for node in nodes:
                    node_ns = next((n for n in NAMES if node.startswith(f"/{n}/")), None)
                    if owner is not None:
                        self.assertTrue(node in ("/simulator", me) or node_ns == owner, f"{topic} is {kind} by {node}")
                    elif node_ns is not None and topic not in GLOBAL_TOPICS:
                        # a robot's node on a global topic: only the real UX-1's ESC command
                        self.assertEqual((topic, node), (ESC_COMMAND_TOPIC, "/UX_1/thruster_allocator"))
        with lock:
            by_node = dict(frames)
        for n in NAMES:
            rsp = f"/{n}/robot_state_publisher"
            self.assertIn(rsp, by_node, f"no tf from {rsp}")
            for parent, child in by_node[rsp]:
                self.assertTrue(parent.startswith(n + "/") and child.startswith(n + "/"), (rsp, parent, child))
            self.assertIn(("world", f"{n}/base_link"), by_node["/simulator"])
        self.assertEqual({c.split("/")[0] for p, c in by_node["/simulator"] if p == "world"}, set(NAMES))
        received = {t: h for t, h in headers.items() if h is not None}
        for n in NAMES:
            self.assertIn(f"/{n}/odom", received)
            self.assertIn(f"/{n}/joint_states", received)
        for topic, header in received.items():
            robot = topic.split("/")[1]
            if header.frame_id:  # joint_states carry none
                self.assertTrue(
                    header.frame_id == "world" or header.frame_id.startswith(robot + "/"),
                    f"{topic} stamped in frame {header.frame_id}",
                )
        for s in subs:
            s.unregister()

    def test_robots_collide_with_each_other(self):
        start = self.start()
        self.ux["UX_2"].thrusts(SCALE * A_Y)  # UX_2 sways (+y) into UX_3, 1.73 m away
        closest = math.inf
        for _ in range(80):  # 8 s in 0.1 s steps
            self.sim.run_for(0.1)
            p = {n: pose(self.ux[n].odom()) for n in ("UX_2", "UX_3")}
            closest = min(closest, float(np.linalg.norm(p["UX_2"][:3] - p["UX_3"][:3])))
        self.assertGreater(closest, 2 * R_HULL - 0.02)  # touched, did not interpenetrate
        self.assertLess(closest, 2 * R_HULL + 0.02)  # and did touch
        self.assertGreater(p["UX_3"][1] - start["UX_3"][1], 0.2)  # UX_3 was pushed along +y

    def test_robot_stops_at_the_shaft_wall(self):
        m = manifest()
        axis_x, half, noise = m["shaft_xy"][0], m["preset"]["shaft_half"], m["wall_noise_max"]
        start = self.start()
        self.ux["UX_1"].thrusts(SCALE * A_X)  # 28 N forward: about 0.65 m/s in open water
        self.sim.run_for(15.0)  # > 10 m of open water; the wall is 4 m ahead
        end = self.ux["UX_1"].odom()
        x = end.pose.pose.position.x
        # The wall ahead lies between axis + half -/+ noise (rounded square, rough walls).
        self.assertGreater(x, axis_x + half - noise - R_HULL - 0.05)
        self.assertLess(x, axis_x + half + noise - R_HULL + 0.02)
        self.assertGreater(x - start["UX_1"][0], 3.0)
        self.assertLess(abs(end.twist.twist.linear.x), 0.05)  # held by the wall


if __name__ == "__main__":
    rostest.rosrun("unexmin", "mine_multi", MineMulti)

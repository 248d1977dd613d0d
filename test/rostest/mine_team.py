#!/usr/bin/env python3
"""rostest: a mixed team in the mine (launch: mine_team.test, mine_world.launch vehicles:=ux1,bluerov2_heavy,remus100).

- The simulator runs the listed vehicles as the world's UX_1, ROV_1 and AUV_1, each with its own thrusters.
- Each follows a body wrench through its own allocator (force_moments): the ROV rises and the AUV speeds along the
  gallery by the distances 1-D models of their published parameters give, and the others stay where they are.
- Each robot's frames are its own: robot_state_publisher of /<robot> publishes <robot>/... only, the simulator
  world -> <robot>/base_link for all three.
"""

import math
import threading
import unittest

import numpy as np
import rospy
import rostest
from std_msgs.msg import Float64
from tf2_msgs.msg import TFMessage

from unexmin import Simulation
from unexmin.scripting.launcher import wait_for
from unexmin.srv import Step

NAMES = ["UX_1", "ROV_1", "AUV_1"]
ALLOCATED = {"ROV_1": 8, "AUV_1": 7}  # messages per wrench: the ROV's 8 thrusters; the AUV's propeller and 6 fins
G = 9.81


def distance_1d(force, seconds, mass, k_lin, k_quad, tau, dt=1e-4):
    """Distance [m] from rest of a body of mass [kg] (rigid + added) under a force [N] applied through a first-order
    lag tau [s], against linear k_lin [N s/m] and quadratic k_quad [N s^2/m^2] damping."""
    v = x = f = 0.0
    alpha = 1.0 - math.exp(-dt / tau)
    for _ in range(int(round(seconds / dt))):
        f += alpha * (force - f)
        v += dt * (f - k_lin * v - k_quad * v * abs(v)) / mass
        x += dt * v
    return x


def position(robot):
    p = robot.odom().pose.pose.position
    return np.array([p.x, p.y, p.z])


class MineTeam(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sim = Simulation(node_name="mine_team_test", timeout=60.0)
        cls.robots = {n: cls.sim.robot(n, streams="none") for n in NAMES}
        cls.step_srv = rospy.ServiceProxy("/sim/step", Step, persistent=True)
        cls.cond = threading.Condition()
        cls.sent = {n: 0 for n in ALLOCATED}  # command messages each allocator has published
        topics = [
            (n, f"thrusters/{i}/input") for n in ALLOCATED for i in range(rospy.get_param(f"/sim/thruster_count/{n}"))
        ]
        topics += [("AUV_1", f"fins/{i}/input") for i in range(6)]
        cls.subs = [rospy.Subscriber(f"/{n}/{t}", Float64, cls.on_command, n, queue_size=100) for n, t in topics]
        wait_for(lambda: all(s.get_num_connections() > 0 for s in cls.subs), 60.0, "the allocators to connect")

    @classmethod
    def on_command(cls, msg, robot):
        if msg._connection_header.get("callerid") == f"/{robot}/thruster_allocator":
            with cls.cond:
                cls.sent[robot] += 1
                cls.cond.notify_all()

    def run_wrenches(self, wrenches, seconds):
        """Positions [m] of every robot at the start and after `seconds` with the wrenches {robot: [X..N]} held."""
        self.sim.reset(seed=3)
        self.sim.step(1)
        start = {n: position(r) for n, r in self.robots.items()}
        for n in ALLOCATED:  # the wrench through the allocator, applied before this robot's first step
            with self.cond:
                want = self.sent[n] + ALLOCATED[n]
            self.robots[n].wrench(*wrenches.get(n, [0.0] * 6))
            with self.cond:
                self.assertTrue(self.cond.wait_for(lambda n=n, w=want: self.sent[n] >= w, 20.0), f"{n}: no allocation")
            self.step_srv(steps=1, client=f"/{n}/thruster_allocator", commands=want, hold=True)
        self.step_srv(duration=seconds, hold=True)  # the commands hold: no watchdog while the test is in control
        self.sim.step(1)
        return start, {n: position(r) for n, r in self.robots.items()}

    def test_the_simulator_runs_the_listed_vehicles(self):
        self.assertEqual(list(self.sim.robots), NAMES)
        self.assertEqual([rospy.get_param(f"/sim/thruster_count/{n}") for n in NAMES], [8, 8, 1])

    def test_each_vehicle_follows_its_own_wrench_through_its_allocator(self):
        seconds = 4.0
        _, idle = self.run_wrenches({}, seconds)
        start, end = self.run_wrenches({"ROV_1": [0, 0, 30, 0, 0, 0], "AUV_1": [3, 0, 0, 0, 0, 0]}, seconds)
        moved = {n: end[n] - idle[n] for n in NAMES}
        # ROV [vB22]: (m + Z_wdot) w' = Z - Z_w w - Z_ww w|w| (the 0.98 N of net weight is in the idle run), thrust
        # through the T200's 0.05 s lag
        rov = distance_1d(30.0, seconds, 13.5 + 18.6863, 33.0, 190.0, 0.05)
        self.assertAlmostEqual(moved["ROV_1"][2], rov, delta=0.05 * rov)
        self.assertLess(np.abs(moved["ROV_1"][:2]).max(), 0.02, "a heave wrench moved the ROV sideways")
        # AUV [P01]: (m + X_udot) u' = X - X_uu u|u|, the propeller's 0.1 s lag
        auv = distance_1d(3.0, seconds, 299.0 / G + 0.93, 0.0, 1.62, 0.1)
        self.assertAlmostEqual(moved["AUV_1"][0], auv, delta=0.05 * auv)
        self.assertLess(abs(moved["AUV_1"][1]), 0.02, "a surge wrench turned the AUV")
        np.testing.assert_allclose(moved["UX_1"], 0.0, atol=1e-9, err_msg="the UX-1 moved with the others' wrenches")
        self.assertGreater(end["AUV_1"][0] - start["AUV_1"][0], 0.5, "the AUV should run 0.74 m in 4 s")

    def test_each_robot_publishes_its_own_frames(self):
        frames, lock = {}, threading.Lock()

        def on_tf(msg):
            with lock:
                for t in msg.transforms:
                    frames.setdefault(msg._connection_header["callerid"], set()).add(
                        (t.header.frame_id, t.child_frame_id)
                    )

        subs = [rospy.Subscriber(t, TFMessage, on_tf, queue_size=100) for t in ("/tf", "/tf_static")]
        wait_for(lambda: all(s.get_num_connections() > 0 for s in subs), 30.0, "the tf publishers")

        def complete():
            self.sim.run_for(0.1)
            with lock:
                return {"/simulator", *(f"/{n}/robot_state_publisher" for n in NAMES)} <= set(frames)

        wait_for(complete, 30.0, "tf of the simulator and of every robot_state_publisher")
        with lock:
            by_node = {k: set(v) for k, v in frames.items()}
        for n in NAMES:
            for parent, child in by_node[f"/{n}/robot_state_publisher"]:
                self.assertTrue(parent.startswith(n + "/") and child.startswith(n + "/"), (n, parent, child))
        self.assertEqual({c for p, c in by_node["/simulator"] if p == "world"}, {f"{n}/base_link" for n in NAMES})
        for s in subs:
            s.unregister()


if __name__ == "__main__":
    rostest.rosrun("unexmin", "mine_team", MineTeam)

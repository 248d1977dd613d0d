#!/usr/bin/env python3
"""rostest: thrusters commanded through ROS move the UX-1 the way the physics says."""

import math
import unittest

import numpy as np
import rostest
from std_msgs.msg import Float64

from unexmin import Simulation
from unexmin.geometry import yaw_of
from unexmin.scripting.launcher import wait_for
from unexmin.topics import sync_publisher

# Thesis allocation matrix (eq. 5.12) rows X and N, columns M0..M7.
A_X = np.array([0.5, 0.0, -0.5, 0.0, 0.5, 0.0, -0.5, 0.0])
A_N = np.array([-0.25, 0.0, 0.25, 0.0, 0.25, 0.0, -0.25, 0.0])


def surge_1d(force, seconds, mass, k_quad, k_lin, tau, dt=1e-4):
    """Distance (or angle) covered from rest along one axis under a force (or moment) with a
    first-order lag, against linear + quadratic drag: m x'' = F(1 - exp(-t/tau)) - k_q |x'| x' - k_l x'."""
    v = x = thrust = 0.0
    alpha = 1.0 - math.exp(-dt / tau)
    for _ in range(int(round(seconds / dt))):
        thrust += alpha * (force - thrust)
        v += dt * (thrust - k_quad * v * abs(v) - k_lin * v) / mass
        x += dt * v
    return x


class TankThrust(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sim = Simulation(node_name="tank_thrust_test", timeout=60.0)
        cls.ux = cls.sim.robot("UX_1", streams="none")  # dynamics only: no sensor messages

    def setUp(self):
        self.sim.reset(seed=1)
        self.sim.step(1)
        self.start = self.ux.odom()

    def test_surge_column_moves_robot_forward_by_the_predicted_distance(self):
        scale = 20.0  # [N] per unit of the allocation column
        self.ux.thrusts(scale * A_X)
        seconds = 3.0
        self.sim.run_for(seconds)
        end = self.ux.odom()
        p0, p1 = self.start.pose.pose.position, end.pose.pose.position
        yaw = yaw_of(self.start.pose.pose.orientation)
        dx, dy = p1.x - p0.x, p1.y - p0.y
        forward = dx * math.cos(yaw) + dy * math.sin(yaw)
        lateral = -dx * math.sin(yaw) + dy * math.cos(yaw)
        # Net surge force of the four horizontal thrusters at 45 deg: sum |A_X| * scale * cos 45.
        force = scale * np.abs(A_X).sum() * math.cos(math.pi / 4)
        rho, radius = 1000.0, 0.3
        volume = 4.0 / 3.0 * math.pi * radius**3
        mass = 1.5 * rho * volume  # rigid body (neutral) + added mass 1/2 rho V
        k_quad = 0.5 * rho * 0.47 * math.pi * radius**2
        k_lin = 6.0 * math.pi * 1.0e-3 * radius
        expected = surge_1d(force, seconds - 1.0 / self.sim.physics_rate, mass, k_quad, k_lin, tau=0.1)
        self.assertAlmostEqual(forward, expected, delta=0.02 * expected)
        self.assertLess(abs(lateral), 0.01 * expected)
        self.assertLess(abs(p1.z - p0.z), 0.01)

    def test_yaw_column_turns_robot_in_place_at_the_predicted_rate(self):
        scale = 20.0
        self.ux.thrusts(scale * A_N)
        seconds = 2.0
        self.sim.run_for(seconds)
        end = self.ux.odom()
        # Yaw moment of the four horizontal thrusters: thrust * arm (0.3 m, tangential).
        moment = scale * np.abs(A_N).sum() * 0.3
        rho, radius = 1000.0, 0.3
        inertia = 0.4 * rho * 4.0 / 3.0 * math.pi * radius**3 * radius**2  # solid sphere, no added inertia
        # the protrusions' drag 1/2 rho Cd A r^3, itemised (docs/identification.md): (count, Cd, A [m^2], r [m])
        items = [
            (4, 1.0, math.pi * 0.035**2, radius),
            (4, 1.0, 0.07 * 0.08, radius / math.sqrt(2.0)),
            (4, 1.0, 0.05 * 0.04, 0.32),
            (4, 1.0, 0.04 * 0.04, 0.32),
            (1, 1.05, 0.15 * 0.10, radius),
            (1, 1.0, 0.0034, 0.13),
        ]
        k_quad = sum(n * 0.5 * rho * cd * a * r**3 for n, cd, a, r in items)
        k_lin = 8.0 * math.pi * 1.0e-3 * radius**3
        t = seconds - 1.0 / self.sim.physics_rate
        expected_angle = surge_1d(moment, t, inertia, k_quad, k_lin, tau=0.1)
        expected_rate = (surge_1d(moment, t + 1e-3, inertia, k_quad, k_lin, tau=0.1) - expected_angle) / 1e-3
        self.assertAlmostEqual(end.twist.twist.angular.z, expected_rate, delta=0.02 * expected_rate)
        turned = yaw_of(end.pose.pose.orientation) - yaw_of(self.start.pose.pose.orientation)
        self.assertAlmostEqual(math.remainder(turned - expected_angle, 2 * math.pi), 0.0, delta=0.02 * expected_angle)
        p0, p1 = self.start.pose.pose.position, end.pose.pose.position
        self.assertLess(math.hypot(p1.x - p0.x, p1.y - p0.y), 0.01)

    def test_bad_commands_are_rejected_at_the_ros_edge(self):
        bad, pend, vbs = (sync_publisher(f"/UX_1/{t}", Float64) for t in ("thrusters/0/input", "pendulum", "vbs"))
        wait_for(
            lambda: all(p.get_num_connections() > 0 for p in (bad, pend, vbs)),
            30.0,
            "the simulator to subscribe to the command topics",
        )
        for value in (float("nan"), float("inf"), -float("inf"), 1e9):
            bad.publish(Float64(value))
            pend.publish(Float64(value))
            vbs.publish(Float64(value))
            self.sim.note_published(3)
        self.sim.run_for(2.0)
        end = self.ux.odom()
        p0, p1 = self.start.pose.pose.position, end.pose.pose.position
        for v in (p1.x, p1.y, p1.z, end.twist.twist.linear.x):
            self.assertTrue(math.isfinite(v))
        self.assertLess(math.dist((p0.x, p0.y, p0.z), (p1.x, p1.y, p1.z)), 1e-3)


if __name__ == "__main__":
    rostest.rosrun("unexmin", "tank_thrust", TankThrust)

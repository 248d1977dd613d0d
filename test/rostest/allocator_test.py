#!/usr/bin/env python3
"""rostest (allocator.test): the thruster allocator node between force_moments and the simulator.

1. A unit wrench on X, Y, Z or N gives, on /UX_1/thrusters/<i>/input, the thesis matrix's row for that
   axis (eq. 5.12, typed in below) and, on /ux1/command/motors, the same thrusts as T200 rpm
   (interpolated here from the datasheet rows).
2. A wrench on one axis moves the robot in the tank along (or about) that axis only, by the
   distance a 1-D model of the sphere predicts: the achieved force is the allocation times the
   thruster geometry (sqrt 2 per unit on X, Y, Z; 0.3 m per unit on N, from the thrusters' poses on
   the 0.3 m hull), mass 1.5 rho V (rigid body + added mass), quadratic drag 1/2 rho Cd pi R^2.

Stepping is deterministic: /sim/step is asked to wait for every thruster message the allocator
node has published (client = the allocator, commands = messages counted here).
"""

import math
import threading
import unittest

import rospy
import rostest
from geometry_msgs.msg import Wrench
from std_msgs.msg import Float64
from ux1_msgs.msg import MotorCommand

from unexmin import Simulation
from unexmin.geometry import yaw_of
from unexmin.scripting.launcher import wait_for
from unexmin.srv import Step
from unexmin.topics import ESC_COMMAND_TOPIC, sync_publisher

ALLOCATOR = "/UX_1/thruster_allocator"
A = {  # thesis eq. 5.12, rows used here
    "X": [0.5, 0.0, -0.50, 0.0, 0.50, 0.0, -0.50, 0.0],
    "Y": [-0.25, -0.25, -0.25, 0.25, 0.25, -0.25, 0.25, -0.25],
    "Z": [0.0, -0.50, 0.0, -0.5, 0.0, 0.50, 0.0, -0.50],
    "N": [-0.25, 0.0, 0.25, 0.0, 0.25, 0.0, -0.25, 0.0],
}
AXES = ("X", "Y", "Z", "K", "M", "N")
G = 9.80665
# T200 16 V rows around +-0.5 N and +-40 N (signed rpm, kgf), from the published sheet
T200 = [
    (-3465, -4.07),
    (-3207, -3.45),
    (-578, -0.10),
    (-317, -0.04),
    (0, 0.0),
    (308, 0.04),
    (573, 0.13),
    (2888, 3.42),
    (3260, 4.51),
]
RHO, R = 1000.0, 0.3
V = 4.0 / 3.0 * math.pi * R**3


def rpm_for(thrust):
    """T200 rpm for `thrust` [N] by linear interpolation in the rows above (clamped at the ends)."""
    kgf = thrust / G
    if kgf <= T200[0][1]:
        return T200[0][0]
    for (x0, y0), (x1, y1) in zip(T200, T200[1:]):
        if y0 <= kgf <= y1:
            return x0 if y1 == y0 else x0 + (kgf - y0) * (x1 - x0) / (y1 - y0)
    raise ValueError(thrust)


def response_1d(force, seconds, mass, k_quad, k_lin, tau=0.1, dt=1e-4):
    """Distance (angle) from rest under a first-order-lagged force (moment) with linear + quadratic drag."""
    v = x = f = 0.0
    alpha = 1.0 - math.exp(-dt / tau)
    for _ in range(int(round(seconds / dt))):
        f += alpha * (force - f)
        v += dt * (f - k_quad * v * abs(v) - k_lin * v) / mass
        x += dt * v
    return x


class AllocatorInSimulator(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sim = Simulation(node_name="allocator_test", timeout=60.0)
        cls.ux = cls.sim.robot("UX_1", streams="none")  # dynamics only: no sensor messages
        cls.cond = threading.Condition()
        cls.thrusts = {}  # thruster -> list of values from the allocator
        cls.motors = []  # MotorCommand values
        cls.from_allocator = 0  # thruster messages published by the allocator node
        cls.subs = [
            rospy.Subscriber(f"/UX_1/thrusters/{i}/input", Float64, cls.on_thrust, i, queue_size=100) for i in range(8)
        ]
        cls.motor_sub = rospy.Subscriber(ESC_COMMAND_TOPIC, MotorCommand, cls.on_motors, queue_size=100)
        cls.wrench_pub = sync_publisher("/UX_1/force_moments", Wrench)
        cls.step_srv = rospy.ServiceProxy("/sim/step", Step, persistent=True)
        wait_for(
            lambda: cls.wrench_pub.get_num_connections() > 0
            and cls.motor_sub.get_num_connections() > 0
            and all(s.get_num_connections() > 0 for s in cls.subs),
            60.0,
            "the allocator to connect",
        )

    @classmethod
    def on_thrust(cls, msg, i):
        with cls.cond:
            if msg._connection_header.get("callerid") == ALLOCATOR:
                cls.thrusts.setdefault(i, []).append(msg.data)
                cls.from_allocator += 1
                cls.cond.notify_all()

    @classmethod
    def on_motors(cls, msg):
        with cls.cond:
            cls.motors.append(list(msg.values))
            cls.cond.notify_all()

    def send(self, axis, value):
        """Publish a wrench with `value` on `axis`; returns the allocator's 8 thrusts and MotorCommand values."""
        w = [0.0] * 6
        w[AXES.index(axis)] = value
        return self.send_wrench(w)

    def send_wrench(self, w):
        """Publish the wrench w [X Y Z K M N]; wait for the allocator's 8 thrusts and its MotorCommand."""
        msg = Wrench()
        msg.force.x, msg.force.y, msg.force.z = w[:3]
        msg.torque.x, msg.torque.y, msg.torque.z = w[3:]
        with self.cond:
            want, want_motors = self.from_allocator + 8, len(self.motors) + 1
        self.wrench_pub.publish(msg)
        with self.cond:
            ok = self.cond.wait_for(lambda: self.from_allocator >= want and len(self.motors) >= want_motors, 20.0)
        self.assertTrue(ok, "the allocator did not publish 8 thrusts and a MotorCommand within 20 s")
        with self.cond:
            return [self.thrusts[i][-1] for i in range(8)], self.motors[-1]

    def step(self, steps):
        """Advance `steps` physics steps once the simulator has every thrust the allocator sent; returns
        the odometry at the new time."""
        with self.cond:
            count = self.from_allocator
        res = self.step_srv(duration=0.0, steps=steps, client=ALLOCATOR, commands=count, hold=True)
        return res.odometry[0]

    def test_unit_wrenches_give_the_matrix_rows(self):
        for axis, row in A.items():
            thrusts, motors = self.send(axis, 1.0)
            for i in range(8):
                self.assertAlmostEqual(thrusts[i], row[i], places=12, msg=f"{axis}: M{i}")
                self.assertAlmostEqual(motors[i], rpm_for(row[i]), places=6, msg=f"{axis}: rpm of M{i}")
        for axis in ("K", "M"):  # no thruster can roll or pitch the sphere in this layout
            thrusts, motors = self.send(axis, 1.0)
            self.assertEqual(thrusts, [0.0] * 8)
            self.assertEqual(motors, [0.0] * 8)
        self.send("X", 0.0)

    def test_nan_wrench_is_dropped_and_saturation_keeps_the_direction(self):
        with self.cond:
            before = self.from_allocator
        nan = Wrench()
        nan.force.x = float("nan")
        self.wrench_pub.publish(nan)
        # 200 forward + 100 left: unsaturated |m| up to 0.5*200 + 0.25*100 = 125 N > 40 N, so every
        # thruster is scaled by 40/125
        thrusts, motors = self.send_wrench([200.0, 100.0, 0, 0, 0, 0])
        with self.cond:  # one connection delivers in order: a NaN output would have come first
            self.assertEqual(self.from_allocator, before + 8, "the NaN wrench must publish nothing")
        raw = [A["X"][i] * 200.0 + A["Y"][i] * 100.0 for i in range(8)]
        scale = 40.0 / max(abs(v) for v in raw)
        self.assertAlmostEqual(scale, 40.0 / 125.0, places=12)
        for i in range(8):
            self.assertAlmostEqual(thrusts[i], raw[i] * scale, places=9, msg=f"M{i}")
        self.assertAlmostEqual(thrusts[4], 40.0, places=9)
        self.assertAlmostEqual(motors[4], rpm_for(40.0), places=6)  # 3112.9 rpm
        self.assertAlmostEqual(thrusts[2], -40.0, places=9)
        self.assertAlmostEqual(motors[2], -3465.0, places=6)  # beyond the reverse maximum: table end
        self.send("X", 0.0)

    def drive(self, axis, value, seconds):
        """Reset, hold the wrench for `seconds` (re-sent every 0.5 s: the thrusters' watchdog is 1 s)."""
        self.sim.reset(seed=2)
        start = self.step(1)
        chunk = int(round(0.5 * self.sim.physics_rate))
        total = int(round(seconds * self.sim.physics_rate))
        done = 0
        while done < total:
            self.send(axis, value)
            n = min(chunk, total - done)
            end = self.step(n)
            done += n
        self.send(axis, 0.0)
        # the wrench is on the wire before the first chunk and applies from its first step
        return start, end, total / self.sim.physics_rate

    def body_displacement(self, start, end):
        p0, p1 = start.pose.pose.position, end.pose.pose.position
        yaw = yaw_of(start.pose.pose.orientation)
        dx, dy, dz = p1.x - p0.x, p1.y - p0.y, p1.z - p0.z
        return dx * math.cos(yaw) + dy * math.sin(yaw), -dx * math.sin(yaw) + dy * math.cos(yaw), dz

    def check_translation(self, axis, index):
        scale = 10.0
        start, end, t = self.drive(axis, scale, 2.0)
        d = self.body_displacement(start, end)
        mass = 1.5 * RHO * V
        k_quad = 0.5 * RHO * 0.47 * math.pi * R**2
        k_lin = 6.0 * math.pi * 1.0e-3 * R
        expected = response_1d(math.sqrt(2.0) * scale, t, mass, k_quad, k_lin)
        print(f"{axis} {scale}: moved {d} m in {t} s, expected {expected:.4f} m along the axis")
        self.assertAlmostEqual(d[index], expected, delta=0.03 * expected, msg=f"{axis}: along the axis")
        for j in range(3):
            if j != index:
                self.assertLess(abs(d[j]), 0.02 * expected, msg=f"{axis}: across the axis ({j})")
        turned = math.remainder(yaw_of(end.pose.pose.orientation) - yaw_of(start.pose.pose.orientation), 2 * math.pi)
        self.assertLess(abs(turned), math.radians(0.5))

    def test_x_moves_forward(self):
        self.check_translation("X", 0)

    def test_y_moves_left(self):
        self.check_translation("Y", 1)

    def test_z_moves_up(self):
        self.check_translation("Z", 2)

    def test_n_turns_counter_clockwise_in_place(self):
        scale = 4.0
        start, end, t = self.drive("N", scale, 2.0)
        inertia = 0.4 * RHO * V * R**2
        k_quad = 8 * 0.5 * RHO * 1.0 * 0.005 * R**3
        k_lin = 8.0 * math.pi * 1.0e-3 * R**3
        expected = response_1d(0.3 * scale, t, inertia, k_quad, k_lin)
        turned = math.remainder(yaw_of(end.pose.pose.orientation) - yaw_of(start.pose.pose.orientation), 2 * math.pi)
        print(f"N {scale}: turned {math.degrees(turned):.3f} deg in {t} s, expected {math.degrees(expected):.3f} deg")
        self.assertAlmostEqual(turned, expected, delta=0.03 * expected)
        d = self.body_displacement(start, end)
        self.assertLess(math.sqrt(sum(v * v for v in d)), 0.01)


if __name__ == "__main__":
    rostest.rosrun("unexmin", "allocator", AllocatorInSimulator)

#!/usr/bin/env python3
"""rostest: joystick events (kernel js_event records on a FIFO) move the UX-1 in the tank the way the sticks say.

With the shipped mapping (config/joystick.yaml) and the default speeds (linear 10 N, angular 2 N m), the
joystick node commands the wrench, the thruster allocator (thesis matrix, eq. 5.12) the thrusters: full left
stick up is X = 10 N, a surge force of 10 · Σ|A_X| · cos 45° = 14.1 N; full right stick left is N = 2 N m, a
yaw moment of 2 · Σ|A_N| · 0.3 m = 0.6 N m. Starting from rest, the distance (angle) covered in T seconds is
below the drag-free bound F T² / (2 m): with the UX-1's drag and the thrusters' 0.1 s lag, the closed-form
answer is 0.90 of it (both motions); the test asks for 0.85..0.94 (measured: 0.897, 0.896), which a wrong sign, axis,
speed step (11 N: 0.99) or allocation breaks.
"""

import math
import os
import threading
import time
import unittest

import rospy
import rostest
from sensor_msgs.msg import Joy
from std_msgs.msg import Float64

from unexmin import Simulation
from unexmin.control.joystick import JS_EVENT_AXIS, JS_EVENT_BUTTON, JS_EVENT_INIT, pack_event
from unexmin.geometry import yaw_of
from unexmin.scripting.launcher import wait_for

LEFT_Y, RIGHT_X, BTN_LB = 1, 3, 4
RHO, RADIUS = 1000.0, 0.3
VOLUME = 4.0 / 3.0 * math.pi * RADIUS**3


class FifoPad:
    """A fake joystick: a FIFO fed with the pad's state every 0.1 s, as a pad held still keeps answering."""

    def __init__(self, path):
        self.path = path
        if os.path.exists(path):
            os.unlink(path)
        os.mkfifo(path)
        self.fd = os.open(path, os.O_RDWR)
        self.axes, self.buttons = {n: 0 for n in range(8)}, {n: 0 for n in range(11)}
        self.lock = threading.Lock()
        self.write(JS_EVENT_INIT)
        self.running = True
        self.thread = threading.Thread(target=self._repeat, daemon=True)
        self.thread.start()

    def write(self, flags=0):
        with self.lock:
            data = b"".join(
                [pack_event(0, v, JS_EVENT_AXIS | flags, n) for n, v in self.axes.items()]
                + [pack_event(0, v, JS_EVENT_BUTTON | flags, n) for n, v in self.buttons.items()]
            )
            os.write(self.fd, data)

    def set(self, axes=None, buttons=None):
        with self.lock:
            self.axes.update(axes or {})
            self.buttons.update(buttons or {})
        self.write()

    def _repeat(self):
        while self.running:
            time.sleep(0.1)
            self.write()

    def close(self):
        self.running = False
        self.thread.join()
        os.close(self.fd)
        os.unlink(self.path)


class Joystick(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sim = Simulation(node_name="joystick_test", timeout=60.0)
        cls.ux = cls.sim.robot("UX_1", streams="none")
        cls.pad = FifoPad(rospy.get_param("~device"))
        cls.inputs = []
        rospy.Subscriber("/UX_1/thrusters/0/input", Float64, lambda m: cls.inputs.append(m.data), queue_size=100)
        joys = []
        rospy.Subscriber("/UX_1/joy", Joy, joys.append, queue_size=100)
        wait_for(lambda: joys, 30.0, "the joystick node to read the FIFO (/UX_1/joy)")

    @classmethod
    def tearDownClass(cls):
        cls.pad.close()

    def setUp(self):
        self.pad.set(axes={n: 0 for n in range(8)}, buttons={BTN_LB: 0})
        self.wait_input(0.0)
        self.sim.reset(seed=1)
        self.sim.step(1)
        self.start = self.ux.odom()

    def wait_input(self, value):
        """Wait for a thruster 0 command equal to `value` [N] newer than the ones seen so far."""
        n = len(self.inputs)
        wait_for(lambda: any(abs(v - value) < 1e-9 for v in self.inputs[n:]), 10.0, f"thruster 0 input = {value}")

    def hold(self, seconds, thruster0):
        """Advance `seconds` of sim time in 0.5 s chunks, each after a fresh allocator command (the
        joystick republishes at 10 Hz wall clock; the thrusters' watchdog is 1 s of sim time)."""
        for _ in range(round(seconds / 0.5)):
            self.wait_input(thruster0)
            self.sim.run_for(0.5)

    def moved(self):
        end = self.ux.odom()
        p0, p1 = self.start.pose.pose.position, end.pose.pose.position
        yaw = yaw_of(self.start.pose.pose.orientation)
        dx, dy = p1.x - p0.x, p1.y - p0.y
        forward = dx * math.cos(yaw) + dy * math.sin(yaw)
        lateral = -dx * math.sin(yaw) + dy * math.cos(yaw)
        turned = math.remainder(yaw_of(end.pose.pose.orientation) - yaw, 2 * math.pi)
        return forward, lateral, p1.z - p0.z, turned

    def test_left_stick_up_with_the_deadman_moves_the_robot_forward(self):
        self.pad.set(axes={LEFT_Y: -32767})  # no dead-man: nothing moves
        self.hold(1.0, 0.0)
        forward, lateral, dz, turned = self.moved()
        self.assertLess(math.sqrt(forward**2 + lateral**2 + dz**2), 1e-3)
        self.pad.set(buttons={BTN_LB: 1})
        self.start = self.ux.odom()
        seconds = 3.0
        self.hold(seconds, 5.0)  # X 10 N -> 0.5 * 10 N on thruster 0
        forward, lateral, dz, turned = self.moved()
        force = 10.0 * 2.0 * math.cos(math.pi / 4)  # Σ|A_X| = 2
        bound = force * seconds**2 / (2 * 1.5 * RHO * VOLUME)  # rigid + added mass 1/2 rho V
        self.assertGreater(forward, 0.85 * bound)
        self.assertLess(forward, 0.94 * bound)
        self.assertLess(abs(lateral), 0.02 * forward)
        self.assertLess(abs(dz), 0.01)
        self.assertLess(abs(turned), 0.01)

    def test_right_stick_left_turns_the_robot_counter_clockwise(self):
        self.pad.set(axes={RIGHT_X: -32767}, buttons={BTN_LB: 1})
        seconds = 2.0
        self.hold(seconds, -0.5)  # N 2 N m -> -0.25 * 2 on thruster 0
        forward, lateral, dz, turned = self.moved()
        moment = 2.0 * 1.0 * RADIUS  # Σ|A_N| = 1, tangential arm 0.3 m
        inertia = 0.4 * RHO * VOLUME * RADIUS**2
        bound = moment * seconds**2 / (2 * inertia)
        self.assertGreater(turned, 0.85 * bound)
        self.assertLess(turned, 0.94 * bound)
        self.assertLess(math.hypot(forward, lateral), 0.01)


if __name__ == "__main__":
    rostest.rosrun("unexmin", "joystick_tank", Joystick)

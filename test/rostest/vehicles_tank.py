#!/usr/bin/env python3
"""rostest: the BlueROV2 Heavy and the REMUS 100 move under commands on their own topics, and under a body wrench
through their own allocators (force_moments); a bad command is rejected and leaves the vehicle where the good ones
put it."""

import math
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import Wrench
from nav_msgs.msg import Odometry
from std_msgs.msg import Float64

TIMEOUT = 30.0  # [s of wall time] for a condition


class Vehicle:
    """Odometry and command publishers of one robot namespace."""

    def __init__(self, name, thrusters, fins):
        self.odom = None
        rospy.Subscriber("/%s/odom" % name, Odometry, self._on_odom, queue_size=1)
        self.thrusters = [
            rospy.Publisher("/%s/thrusters/%d/input" % (name, i), Float64, queue_size=1) for i in range(thrusters)
        ]
        self.fins = [rospy.Publisher("/%s/fins/%d/input" % (name, i), Float64, queue_size=1) for i in range(fins)]
        self.wrench = rospy.Publisher("/%s/force_moments" % name, Wrench, queue_size=1)

    def _on_odom(self, msg):
        self.odom = msg

    def position(self):
        p = self.odom.pose.pose.position
        return (p.x, p.y, p.z)

    def yaw(self):
        q = self.odom.pose.pose.orientation
        return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))

    def drive_until(self, thrusts, fins, done, timeout=TIMEOUT, wrench=None):
        """Publish the commands (or the body wrench [X Y Z K M N] to the allocator) every 0.05 s of wall time until
        done() holds or `timeout` passes; returns done()."""
        end = time.monotonic() + timeout
        while not rospy.is_shutdown() and time.monotonic() < end:
            for pub, value in zip(self.thrusters, thrusts):
                pub.publish(Float64(value))
            for pub, value in zip(self.fins, fins):
                pub.publish(Float64(value))
            if wrench is not None:
                msg = Wrench()
                msg.force.x, msg.force.y, msg.force.z, msg.torque.x, msg.torque.y, msg.torque.z = wrench
                self.wrench.publish(msg)
            if done():
                return True
            time.sleep(0.05)
        return done()


def wait_for(condition, timeout=TIMEOUT):
    end = time.monotonic() + timeout
    while not condition() and time.monotonic() < end and not rospy.is_shutdown():
        time.sleep(0.05)
    return condition()


class VehiclesTank(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("vehicles_tank_test")
        cls.rov = Vehicle("ROV_1", thrusters=8, fins=0)
        cls.auv = Vehicle("AUV_1", thrusters=1, fins=6)
        assert wait_for(lambda: cls.rov.odom is not None and cls.auv.odom is not None), "no odometry"

    def test_the_simulator_runs_the_listed_vehicles_in_order(self):
        self.assertEqual(rospy.get_param("/sim/robots"), ["AUV_1", "ROV_1"])

    def test_rov_surges_forward_on_its_horizontal_thrusters(self):
        x0, y0, _ = self.rov.position()
        moved = self.rov.drive_until([200] * 4 + [0] * 4, [], lambda: self.rov.position()[0] - x0 > 0.3)
        self.assertTrue(moved, "ROV_1 did not move 0.3 m forward: %s" % (self.rov.position(),))
        self.assertLess(abs(self.rov.position()[1] - y0), 0.1, "a pure surge command drifted sideways")

    def test_rov_rises_on_a_heave_wrench_through_its_allocator(self):
        x0, y0, z0 = self.rov.position()
        rose = self.rov.drive_until([], [], lambda: self.rov.position()[2] - z0 > 0.2, wrench=[0, 0, 40, 0, 0, 0])
        x, y, z = self.rov.position()
        self.assertTrue(rose, "ROV_1 did not rise 0.2 m on Z = 40 N: z %.3f -> %.3f" % (z0, z))
        self.assertLess(math.hypot(x - x0, y - y0), 0.05, "a pure heave wrench moved the ROV sideways")

    def test_auv_speeds_up_and_turns_to_port_on_a_wrench_through_its_allocator(self):
        x0, yaw0 = self.auv.position()[0], self.auv.yaw()
        turned = self.auv.drive_until(
            [],
            [],
            lambda: self.auv.position()[0] - x0 > 0.3 and self.auv.yaw() - yaw0 > 0.05,
            wrench=[3, 0, 0, 0, 0, 1],
        )
        self.assertTrue(
            turned,
            "AUV_1 did not move forward and turn to port on X = 3 N, N = 1 N m: x %.3f -> %.3f, yaw %.3f -> %.3f"
            % (x0, self.auv.position()[0], yaw0, self.auv.yaw()),
        )

    def test_auv_turns_on_its_rudder_and_refuses_a_nan_fin_command(self):
        x0 = self.auv.position()[0]
        yaw0 = self.auv.yaw()
        rudder = math.radians(10.0)
        turned = self.auv.drive_until(
            [1500.0],
            [rudder, rudder, 0, 0, 0, 0],
            lambda: self.auv.position()[0] - x0 > 0.3 and self.auv.yaw() - yaw0 < -0.05,
        )
        self.assertTrue(
            turned,
            "AUV_1 did not move forward and turn to starboard: x %.3f -> %.3f, yaw %.3f -> %.3f"
            % (x0, self.auv.position()[0], yaw0, self.auv.yaw()),
        )
        # NaN and an angle beyond the limit are rejected at the ROS edge (a throttled warning): the fins keep the
        # rudder angle until their 1 s watchdog, and the vehicle keeps turning the same way.
        yaw1 = self.auv.yaw()
        still_turning = self.auv.drive_until(
            [1500.0], [float("nan"), 1.0, 0, 0, 0, 0], lambda: self.auv.yaw() - yaw1 < -0.05
        )
        self.assertTrue(still_turning, "a rejected fin command changed the turn")


if __name__ == "__main__":
    rostest.rosrun("unexmin", "vehicles_tank", VehiclesTank)

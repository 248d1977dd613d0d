"""Simulated ESC driver (thesis 5.10.3, "vesc_sim_node"): /ux1/command/motors -> simulated thrusters.

Subscribes the real robot's ESC command (ux1_msgs/MotorCommand: rpm or duty cycle for M0..M7),
converts each value to thrust [N] with the ESC table (unexmin.control.esc) and publishes it on
/<robot>/thrusters/<i>/input. This is how a real robot's commands, live or from a bag, move the
simulated robot. Parameters: docs/esc_driver.md.
"""

import threading

import rospy
from ux1_msgs.msg import MotorCommand

from unexmin.control.esc import MODE_NAMES, EscTableError, converter_from_params
from unexmin.topics import (
    ESC_COMMAND_TOPIC,
    publish_thrusts,
    robot_param,
    run_node,
    thruster_publishers,
)


class EscDriverNode:
    """ROS wrapper of unexmin.control.esc.EscConverter (one per simulated robot)."""

    def __init__(self, robot=None, motor_topic=None, announce=True):
        """robot, motor_topic: override ~robot and ~motor_topic (for an in-process driver, e.g. the replay);
        announce: log the configuration at start (off for an in-process driver)."""
        self.load_params(robot, motor_topic)
        ns = f"/{self.robot}/"
        self.thruster_pubs = thruster_publishers(ns, self.thrusters)
        self.processed = 0  # MotorCommand messages handled (converted and published, or rejected)
        self.published = 0  # thruster input messages published
        self.last_thrusts = None  # [N] the last thrusts published
        self._cond = threading.Condition()
        self.sub = rospy.Subscriber(self.motor_topic, MotorCommand, self.on_motors, queue_size=20, tcp_nodelay=True)
        log = rospy.loginfo if announce else rospy.logdebug
        log(
            "esc_driver: %s -> /%s/thrusters/0..%d/input (rpm table %s rpm -> %s N, max thrust %.1f N)",
            self.motor_topic,
            self.robot,
            self.thrusters - 1,
            self.converter.tables[0].command_range,
            self.converter.tables[0].thrust_range,
            self.converter.max_thrust,
        )

    def load_params(self, robot=None, motor_topic=None):
        """Every parameter, checked in one place (ValueError names the parameter)."""
        self.robot = robot_param(robot)
        self.motor_topic = str(motor_topic or rospy.get_param("~motor_topic", ESC_COMMAND_TOPIC))
        self.thrusters = rospy.get_param("~thrusters", 8)
        if not isinstance(self.thrusters, int) or not 1 <= self.thrusters <= 8:
            raise ValueError(
                f"parameter ~thrusters = {self.thrusters!r}: expected an integer in [1, 8] "
                "(MotorCommand carries 8 values)"
            )
        self.converter = converter_from_params(lambda name, default: rospy.get_param("~" + name, default))

    def on_motors(self, msg):
        try:
            thrusts, clamped = self.converter.to_thrust(msg.mode, list(msg.values)[: self.thrusters])
        except EscTableError as e:
            rospy.logwarn_throttle(1.0, f"esc_driver: rejected MotorCommand on {self.motor_topic}: {e}")
            self._done(None)
            return
        if clamped:
            rospy.logwarn_throttle(
                1.0,
                f"esc_driver: {MODE_NAMES[msg.mode]} command {list(msg.values)} needs more "
                f"than +-{self.converter.max_thrust} N; thrust clamped",
            )
        publish_thrusts(self.thruster_pubs, thrusts)
        self._done(thrusts, len(self.thruster_pubs))

    def _done(self, thrusts, published=0):
        with self._cond:
            self.processed += 1
            self.published += published
            if thrusts is not None:
                self.last_thrusts = thrusts
            self._cond.notify_all()

    def close(self):
        """Unregister the driver's subscriber and publishers (an in-process driver, e.g. the replay's)."""
        self.sub.unregister()
        for pub in self.thruster_pubs:
            pub.unregister()

    def wait_processed(self, count, timeout):
        """Block until `count` messages have been handled; False on timeout [s] (wall clock)."""
        with self._cond:
            return self._cond.wait_for(lambda: self.processed >= count, timeout)


def main():
    """Entry point of nodes/esc_driver."""
    run_node("esc_driver", EscDriverNode)  # EscTableError is a ValueError

"""Thruster allocator node (thesis 5.10.2, Thruster_allocator_sim): body wrench -> thruster commands.

Subscribes /<robot>/force_moments (geometry_msgs/Wrench, body frame: force [N], torque [N m]),
computes m = A^T tau with direction-preserving saturation (unexmin.control.allocation) and publishes

- each simulated thruster's command, /<robot>/thrusters/<i>/input (std_msgs/Float64, thrust [N]);
- if ~publish_motor_command, the real robot's ESC command /ux1/command/motors (ux1_msgs/MotorCommand),
  the same thrusts converted to rpm or duty cycle with the inverse ESC table (unexmin.control.esc), so a
  simulated and a real robot can be driven together (hardware in the loop).

NaN/inf wrenches are rejected with a throttled warning. Parameters: docs/thruster_allocator.md.
"""

import rospy
from geometry_msgs.msg import Wrench
from ux1_msgs.msg import MotorCommand

from unexmin.control.allocation import DEFAULT_MAX_THRUST, THESIS_MATRIX, AllocationError, ThrusterAllocator
from unexmin.control.esc import MODE_NAMES, converter_from_params, parse_mode
from unexmin.topics import (
    ESC_COMMAND_TOPIC,
    publish_thrusts,
    robot_param,
    run_node,
    sync_publisher,
    thruster_publishers,
)


def wrench_to_list(msg):
    """[X Y Z K M N] of a geometry_msgs/Wrench."""
    return [msg.force.x, msg.force.y, msg.force.z, msg.torque.x, msg.torque.y, msg.torque.z]


class ThrusterAllocatorNode:
    """ROS wrapper of unexmin.control.allocation.ThrusterAllocator for one robot."""

    def __init__(self):
        self.load_params()
        ns = f"/{self.robot}/"
        self.thruster_pubs = thruster_publishers(ns, self.allocator.thrusters)
        self.motor_pub = sync_publisher(self.motor_topic, MotorCommand) if self.publish_motor_command else None
        self.sub = rospy.Subscriber(f"{ns}force_moments", Wrench, self.on_wrench, queue_size=10, tcp_nodelay=True)
        rospy.loginfo(
            "thruster_allocator: /%sforce_moments -> /%sthrusters/0..%d/input%s, max thrust %.1f N",
            ns[1:],
            ns[1:],
            self.allocator.thrusters - 1,
            f" and {self.motor_topic} ({MODE_NAMES[self.motor_mode]})" if self.motor_pub else "",
            self.allocator.max_thrust,
        )

    def load_params(self):
        """Every parameter, checked in one place (errors name the parameter)."""
        self.robot = robot_param()
        matrix = rospy.get_param("~allocation_matrix", [list(r) for r in THESIS_MATRIX])
        max_thrust = rospy.get_param("~max_thrust", DEFAULT_MAX_THRUST)
        try:
            self.allocator = ThrusterAllocator(matrix, max_thrust)
        except AllocationError as e:
            raise AllocationError(str(e).replace("parameter ", "parameter ~", 1)) from None
        self.publish_motor_command = rospy.get_param("~publish_motor_command", True)
        if not isinstance(self.publish_motor_command, bool):
            raise AllocationError(
                f"parameter ~publish_motor_command = {self.publish_motor_command!r}: expected true or false"
            )
        self.motor_topic = str(rospy.get_param("~motor_command_topic", ESC_COMMAND_TOPIC))
        self.motor_mode = parse_mode(rospy.get_param("~motor_command_mode", "rpm"), "~motor_command_mode")
        # The ESC tables (same parameters as the ESC driver) give the inverse conversion thrust -> rpm/duty.
        self.converter = converter_from_params(lambda name, default: rospy.get_param("~" + name, default))
        if self.publish_motor_command and self.allocator.thrusters != 8:
            raise AllocationError(
                f"parameter ~allocation_matrix: has {self.allocator.thrusters} thruster columns "
                "but ux1_msgs/MotorCommand carries exactly 8; set ~publish_motor_command false"
            )

    def on_wrench(self, msg):
        try:
            thrusts, scale = self.allocator.allocate(wrench_to_list(msg))
        except AllocationError as e:
            rospy.logwarn_throttle(1.0, f"thruster_allocator: rejected /{self.robot}/force_moments: {e}")
            return
        if scale < 1.0:
            rospy.logwarn_throttle(
                5.0,
                f"thruster_allocator: wrench {wrench_to_list(msg)} needs more than "
                f"{self.allocator.max_thrust} N on a thruster; scaled by {scale:.3f}",
            )
        publish_thrusts(self.thruster_pubs, thrusts)
        if self.motor_pub is not None:
            cmd = MotorCommand()
            cmd.header.stamp = rospy.Time.now()
            cmd.mode = self.motor_mode
            cmd.values = [float(v) for v in self.converter.to_command(self.motor_mode, thrusts)]
            self.motor_pub.publish(cmd)


def main():
    """Entry point of nodes/thruster_allocator."""
    run_node("thruster_allocator", ThrusterAllocatorNode)  # AllocationError, EscTableError: ValueErrors

"""Thruster allocator node (thesis 5.10.2, Thruster_allocator_sim): body wrench -> thruster commands.

Subscribes /<robot>/force_moments (geometry_msgs/Wrench, body frame: force [N], torque [N m]),
computes m = A^T tau with direction-preserving saturation (unexmin.control.allocation) and publishes

- each simulated thruster's command, /<robot>/thrusters/<i>/input (std_msgs/Float64, thrust [N]);
- if ~publish_motor_command, the real robot's ESC command /ux1/command/motors (ux1_msgs/MotorCommand),
  the same thrusts converted to rpm or duty cycle with the inverse ESC table (unexmin.control.esc), so a
  simulated and a real robot can be driven together (hardware in the loop).

With ~from_description the allocation comes from the robot's own description instead (any vehicle: the BlueROV2
Heavy's eight thrusters, the REMUS 100's propeller and fins; unexmin.control.vehicle_allocation): the commands go
out in each thruster's own unit and, for fins, as angles on /<robot>/fins/<i>/input [rad], the fins' authority
taken at the surge speed of /<robot>/odom.

NaN/inf wrenches are rejected with a throttled warning. Parameters: docs/thruster_allocator.md.
"""

import rospy
from geometry_msgs.msg import Wrench
from nav_msgs.msg import Odometry
from std_msgs.msg import Float64
from ux1_msgs.msg import MotorCommand

from unexmin.control.allocation import DEFAULT_MAX_THRUST, DOF, THESIS_MATRIX, AllocationError, ThrusterAllocator
from unexmin.control.esc import MODE_NAMES, converter_from_params, parse_mode
from unexmin.control.vehicle_allocation import DEFAULT_FIN_MIN_SPEED, DEFAULT_WATER_DENSITY, VehicleAllocator
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
        self.vehicle = None  # VehicleAllocator with ~from_description
        self.surge_speed = 0.0  # [m/s] from /<robot>/odom, for the fins
        self.load_params()
        ns = f"/{self.robot}/"
        if self.vehicle is not None:
            self.thruster_pubs = thruster_publishers(ns, len(self.vehicle.thrusters))
            self.fin_pubs = [sync_publisher(f"{ns}fins/{i}/input", Float64) for i in range(self.vehicle.fin_count)]
            self.motor_pub = None
            if self.vehicle.fins:
                self.odom_sub = rospy.Subscriber(f"{ns}odom", Odometry, self.on_odom, queue_size=1, tcp_nodelay=True)
            self.sub = rospy.Subscriber(
                f"{ns}force_moments", Wrench, self.on_vehicle_wrench, queue_size=10, tcp_nodelay=True
            )
            rospy.loginfo(
                "thruster_allocator: /%sforce_moments -> %d thruster(s), %d fin(s) of /%srobot_description (%s)",
                ns[1:],
                len(self.vehicle.thrusters),
                len(self.vehicle.fins),
                ns[1:],
                " ".join(DOF[i] for i in self.vehicle.dofs),
            )
            return
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

    def load_vehicle_params(self):
        """~from_description: the allocation from /<robot>/robot_description (or ~description_param)."""
        param = str(rospy.get_param("~description_param", f"/{self.robot}/robot_description"))
        xml = rospy.get_param(param, None)
        if not isinstance(xml, str) or not xml:
            raise AllocationError(f"parameter {param} is not set: load the robot description first (robot.launch)")
        self.vehicle = VehicleAllocator(
            xml,
            dofs=rospy.get_param("~dofs", "X Y Z K M N"),
            rho=float(rospy.get_param("~water_density", DEFAULT_WATER_DENSITY)),
            fin_min_speed=float(rospy.get_param("~fin_min_speed", DEFAULT_FIN_MIN_SPEED)),
            source=param,
        )

    def load_params(self):
        """Every parameter, checked in one place (errors name the parameter)."""
        self.robot = robot_param()
        from_description = rospy.get_param("~from_description", False)
        if not isinstance(from_description, bool):
            raise AllocationError(f"parameter ~from_description = {from_description!r}: expected true or false")
        if from_description:
            try:
                self.load_vehicle_params()
            except AllocationError as e:
                raise AllocationError(str(e).replace("parameter ", "parameter ~", 1)) from None
            return
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

    def on_odom(self, msg):
        self.surge_speed = msg.twist.twist.linear.x  # body frame (REP-105)

    def on_vehicle_wrench(self, msg):
        try:
            commands, angles, scale = self.vehicle.allocate(wrench_to_list(msg), self.surge_speed)
        except AllocationError as e:
            rospy.logwarn_throttle(1.0, f"thruster_allocator: rejected /{self.robot}/force_moments: {e}")
            return
        if scale < 1.0:
            rospy.logwarn_throttle(
                5.0, f"thruster_allocator: wrench {wrench_to_list(msg)} beyond the thrusters; scaled by {scale:.3f}"
            )
        publish_thrusts(self.thruster_pubs, commands)
        for pub, angle in zip(self.fin_pubs, angles):
            pub.publish(Float64(angle))

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

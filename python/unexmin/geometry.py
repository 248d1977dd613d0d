"""Rotation maths shared by the tools, nodes and tests. Pure Python and numpy, no ROS.

Conventions (REP-103, URDF): angles in radians; roll, pitch, yaw are the ZYX Euler angles of
R = Rz(yaw) Ry(pitch) Rx(roll); quaternions are (x, y, z, w), unit length.
"""

import math

import numpy as np


def quaternion_to_rpy(x, y, z, w):
    """Roll, pitch, yaw [rad] (ZYX) of the unit quaternion (x, y, z, w); pitch in [-pi/2, pi/2]."""
    roll = math.atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2.0 * (w * y - z * x))))
    yaw = math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
    return roll, pitch, yaw


def rpy_of(q):
    """Roll, pitch, yaw [rad] of a quaternion message (geometry_msgs/Quaternion, rospy or rosbags)."""
    return quaternion_to_rpy(q.x, q.y, q.z, q.w)


def yaw_of(q):
    """Yaw [rad] in (-pi, pi] of a quaternion message (geometry_msgs/Quaternion, rospy or rosbags)."""
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def rpy_quaternion(rpy):
    """(x, y, z, w) of R = Rz(yaw) Ry(pitch) Rx(roll); rpy = (roll, pitch, yaw) [rad]."""
    r, p, y = (0.5 * a for a in rpy)
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return (
        sr * cp * cy - cr * sp * sy,
        cr * sp * cy + sr * cp * sy,
        cr * cp * sy - sr * sp * cy,
        cr * cp * cy + sr * sp * sy,
    )


def rpy_matrix(rpy):
    """3 x 3 rotation matrix R = Rz(yaw) Ry(pitch) Rx(roll) (URDF convention); rpy = (roll, pitch, yaw) [rad]."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


def wrap_angle(a):
    """Angle(s) [rad] wrapped to [-pi, pi); a scalar or an array."""
    return (np.asarray(a) + math.pi) % (2.0 * math.pi) - math.pi

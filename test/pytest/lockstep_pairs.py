"""What the tests that hold unexmin.core against the ROS simulator share (test_core_lockstep.py, test_core_team.py):
the odometry as a row of numbers, the core's state as the same row, and the ROS environment a launch changes, put
back afterwards."""

import contextlib
import os

ENV_KEYS = ("ROS_MASTER_URI", "ROS_IP", "ROS_LOG_DIR")


def odometry_row(o):
    """x y z, qx qy qz qw, body-frame linear and angular velocity of a nav_msgs/Odometry."""
    p, q, v, w = o.pose.pose.position, o.pose.pose.orientation, o.twist.twist.linear, o.twist.twist.angular
    return [p.x, p.y, p.z, q.x, q.y, q.z, q.w, v.x, v.y, v.z, w.x, w.y, w.z]


def state_row(st):
    """The same numbers from unexmin.core's Robot.state()."""
    return [*st["position"], *st["orientation"], *st["linear_velocity"], *st["angular_velocity"]]


@contextlib.contextmanager
def ros_environment_kept():
    """Puts ROS_MASTER_URI, ROS_IP and ROS_LOG_DIR back as they were when the block ends."""
    saved = {k: os.environ.get(k) for k in ENV_KEYS}
    try:
        yield
    finally:
        for k, v in saved.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v

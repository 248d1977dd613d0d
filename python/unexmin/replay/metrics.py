"""Trajectories of the replay and their comparison: start frames, position and yaw errors. Pure numpy.

A trajectory is an array whose rows are TRAJ_COLUMNS: mission time [s], position [m] (world frame,
or the compared frame once aligned) and roll, pitch, yaw [rad] (ZYX Euler, unexmin.geometry).
"""

import math

import numpy as np

from unexmin.geometry import quaternion_to_rpy, wrap_angle
from unexmin.replay.errors import ReplayError

TRAJ_COLUMNS = ("t", "x", "y", "z", "roll", "pitch", "yaw")  # [s], [m] world frame, [rad] ZYX Euler


def pose_row(t, pose):
    """A TRAJ_COLUMNS row at time t [s] from a geometry_msgs/Pose (rospy or rosbags object)."""
    p, q = pose.position, pose.orientation
    return (t, p.x, p.y, p.z, *quaternion_to_rpy(q.x, q.y, q.z, q.w))


def to_start_frame(traj, t_ref):
    """Trajectory in its own start frame: origin at the position at t_ref [s], x along the heading at
    t_ref, z unchanged in direction; yaw relative to the yaw at t_ref (unwrapped)."""
    out = traj.copy()
    t = traj[:, 0]
    yaw = np.unwrap(traj[:, 6])
    p_ref = [np.interp(t_ref, t, traj[:, i]) for i in (1, 2, 3)]
    yaw_ref = np.interp(t_ref, t, yaw)
    c, s = math.cos(yaw_ref), math.sin(yaw_ref)
    dx, dy = traj[:, 1] - p_ref[0], traj[:, 2] - p_ref[1]
    out[:, 1], out[:, 2] = c * dx + s * dy, -s * dx + c * dy
    out[:, 3] = traj[:, 3] - p_ref[2]
    out[:, 6] = yaw - yaw_ref
    return out


def path_length(traj):
    """Length [m] of the polyline through the trajectory's positions."""
    return float(np.sum(np.linalg.norm(np.diff(traj[:, 1:4], axis=0), axis=1))) if len(traj) > 1 else 0.0


def compare(sim_traj, nav, align=True):
    """Errors of the simulated trajectory against the bag's navigation.

    Both are rows of TRAJ_COLUMNS at mission times. The comparison uses the simulated samples inside
    the navigation's time span, with the navigation interpolated linearly (yaw unwrapped). With
    align, both are first put in their own start frame at the first common time.
    Returns (metrics dict, sim rows used, navigation rows at the same times); the fields of the
    metrics: docs/replay.md, report.json `errors`.
    """
    t_lo, t_hi = max(nav[0, 0], sim_traj[0, 0]), min(nav[-1, 0], sim_traj[-1, 0])
    keep = (sim_traj[:, 0] >= t_lo - 1e-9) & (sim_traj[:, 0] <= t_hi + 1e-9)
    if keep.sum() < 2:
        raise ReplayError(
            f"the navigation ({nav[0, 0]:.2f}..{nav[-1, 0]:.2f} s) and the simulated trajectory "
            f"({sim_traj[0, 0]:.2f}..{sim_traj[-1, 0]:.2f} s) share fewer than 2 samples"
        )
    s = sim_traj[keep]
    n = np.empty_like(s)
    n[:, 0] = s[:, 0]
    yaw_nav = np.unwrap(nav[:, 6])
    for i in range(1, 7):
        n[:, i] = np.interp(s[:, 0], nav[:, 0], yaw_nav if i == 6 else nav[:, i])
    if align:
        s, n = to_start_frame(s, s[0, 0]), to_start_frame(n, n[0, 0])
    else:
        s = s.copy()
        s[:, 6] = np.unwrap(s[:, 6])
    err = np.linalg.norm(s[:, 1:4] - n[:, 1:4], axis=1)
    yaw_err = np.degrees(wrap_angle(s[:, 6] - n[:, 6]))
    metrics = {
        "aligned_to_start_frame": bool(align),
        "samples": int(len(s)),
        "t_start_s": float(s[0, 0]),
        "t_end_s": float(s[-1, 0]),
        "position_error_m": {
            "final": float(err[-1]),
            "max": float(err.max()),
            "mean": float(err.mean()),
            "rms": float(np.sqrt(np.mean(err**2))),
        },
        "final_error_xyz_m": [float(v) for v in (s[-1, 1:4] - n[-1, 1:4])],
        "yaw_error_deg": {
            "final": float(yaw_err[-1]),
            "max_abs": float(np.abs(yaw_err).max()),
            "rms": float(np.sqrt(np.mean(yaw_err**2))),
        },
        "bag_path_length_m": path_length(n),
        "sim_path_length_m": path_length(s),
        "bag_displacement_m": float(np.linalg.norm(n[-1, 1:4] - n[0, 1:4])),
        "sim_displacement_m": float(np.linalg.norm(s[-1, 1:4] - s[0, 1:4])),
    }
    return metrics, s, n

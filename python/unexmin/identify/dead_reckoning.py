"""Navigation by dead reckoning from the robot's own sensors: IMU attitude, DVL velocity, pressure depth.

What a real UX-1 has instead of ground truth (docs/identification.md, "Navigation by dead reckoning"):

- attitude: the IMU's gyroscope (sensor_msgs/Imu, rates in the IMU frame) integrated from an initial
  roll and pitch levelled on the accelerometer (the specific force of a robot at rest is
  R^T (0, 0, g)) over the first `level_time` seconds; the initial yaw is `initial_yaw` (the
  identification does not depend on the heading: gravity is along z);
- velocity: the DVL's bottom-track velocity (geometry_msgs/TwistWithCovarianceStamped, DVL frame,
  only with bottom lock) rotated into the body frame, less the lever-arm velocity w x r_DVL, linearly
  interpolated between pings (and over pings without bottom lock), rotated into the world by the
  attitude and integrated (trapezoids at the IMU rate) to a position;
- depth: the pressure p (sensor_msgs/FluidPressure [Pa]) at the pressure sensor gives its z =
  surface_z - (p - p_atm) / (rho g); the hull centre is below it by the rotated mount offset
  (R r_p)_z. It is fused with the integrated DVL vertical velocity by a complementary filter of
  time constant `depth_time_constant` (the pressure fixes the depth at long periods, the DVL follows
  the motion at short ones; a 1 cm pressure noise would otherwise dominate the second derivative).

The sensor mounts (IMU, DVL and pressure links relative to base_link) come from the robot's expanded
description. Pure numpy/scipy: no ROS needed.
"""

import math
from dataclasses import dataclass

import numpy as np

from unexmin.description import parse
from unexmin.geometry import rpy_matrix

IMU_TYPE = "sensor_msgs/msg/Imu"
DVL_TYPE = "geometry_msgs/msg/TwistWithCovarianceStamped"
PRESSURE_TYPE = "sensor_msgs/msg/FluidPressure"
#: [Pa] standard atmosphere at the free surface (the shipped worlds' `atmospheric_pressure`, worlds/*.world)
ATMOSPHERIC_PRESSURE = 101325.0


@dataclass
class Mounts:
    """Sensor mounts in the body (base_link) frame."""

    imu_R: np.ndarray  # 3 x 3, IMU frame -> body
    dvl_R: np.ndarray  # 3 x 3, DVL frame -> body
    dvl_r: np.ndarray  # [m] DVL origin in the body frame
    pressure_r: np.ndarray  # [m] pressure sensor origin in the body frame


def mounts_from_urdf(urdf, name="UX_1", imu_link="imu_link", dvl_link="dvl_link", pressure_link="pressure_link"):
    """Mounts of an expanded URDF (text): each link <name>/<link> on a chain of fixed joints to the base link (the
    poses composed by unexmin.description)."""
    robot = parse(urdf, f"robot description of {name}")

    def pose(link):
        full = f"{name}/{link}"
        current = full
        while current != robot.base_link:
            joint = next((j for j in robot.joints if j.child == current), None)
            if joint is None:
                break  # link_pose names the missing connection
            if joint.type != "fixed":
                raise ValueError(f"{full} hangs on a {joint.type} joint: a sensor mount must be fixed")
            current = joint.parent
        r, R = robot.link_pose(full)
        return R, r

    imu_R, _ = pose(imu_link)
    dvl_R, dvl_r = pose(dvl_link)
    _, p_r = pose(pressure_link)
    return Mounts(imu_R=imu_R, dvl_R=dvl_R, dvl_r=dvl_r, pressure_r=p_r)


def _stamp(msg):
    s = msg.header.stamp
    return s.sec + 1e-9 * s.nanosec if hasattr(s, "nanosec") else s.secs + 1e-9 * s.nsecs


def sensor_arrays(messages, imu_topic, dvl_topic, pressure_topic, t0=0.0):
    """(imu, dvl, pressure) arrays from bag messages [(topic, type, t, msg)]: imu rows (t, gyro xyz
    [rad/s], specific force xyz [m/s^2]) in the IMU frame, dvl rows (t, v xyz [m/s]) in the DVL frame,
    pressure rows (t, p [Pa]); t = header stamp - t0 [s], sorted."""
    imu, dvl, prs = [], [], []
    for topic, _, _, m in messages:
        if topic == imu_topic:
            w, a = m.angular_velocity, m.linear_acceleration
            imu.append((_stamp(m) - t0, w.x, w.y, w.z, a.x, a.y, a.z))
        elif topic == dvl_topic:
            v = m.twist.twist.linear
            dvl.append((_stamp(m) - t0, v.x, v.y, v.z))
        elif topic == pressure_topic:
            prs.append((_stamp(m) - t0, m.fluid_pressure))

    def arr(rows, width):
        a = np.array(rows, dtype=float).reshape(-1, width)
        a = a[np.all(np.isfinite(a), axis=1)]
        return a[np.argsort(a[:, 0], kind="stable")]

    return arr(imu, 7), arr(dvl, 4), arr(prs, 2)


def _skew_exp(phi):
    """Rotation matrix exp([phi]x) (Rodrigues) of one rotation vector."""
    th = math.sqrt(phi @ phi)
    K = np.array([[0.0, -phi[2], phi[1]], [phi[2], 0.0, -phi[0]], [-phi[1], phi[0], 0.0]])
    if th < 1e-9:
        return np.eye(3) + K + 0.5 * K @ K
    return np.eye(3) + math.sin(th) / th * K + (1.0 - math.cos(th)) / th**2 * K @ K


def matrices_to_rpy(R):
    """(n, 3) ZYX roll, pitch, yaw [rad] of (n, 3, 3) matrices (body -> world)."""
    roll = np.arctan2(R[:, 2, 1], R[:, 2, 2])
    pitch = np.arcsin(np.clip(-R[:, 2, 0], -1.0, 1.0))
    yaw = np.arctan2(R[:, 1, 0], R[:, 0, 0])
    return np.stack([roll, pitch, yaw], -1)


def level(specific_force):
    """(roll, pitch) [rad] of a robot at rest from its mean body-frame specific force f = R^T (0, 0, g)."""
    f = np.asarray(specific_force, float)
    return math.atan2(f[1], f[2]), math.atan2(-f[0], math.hypot(f[1], f[2]))


def dead_reckon(
    imu,
    dvl,
    pressure,
    mounts,
    t_out,
    water_density=1000.0,
    gravity=9.81,
    atmospheric_pressure=ATMOSPHERIC_PRESSURE,
    surface_z=0.0,
    level_time=1.0,
    initial_yaw=0.0,
    initial_xy=(0.0, 0.0),
    depth_time_constant=10.0,
):
    """Pose rows (t, x, y, z, roll, pitch, yaw) [s, m, rad] of the hull centre at the times t_out [s].

    imu (n, 7), dvl (m, 4), pressure (k, 2): see sensor_arrays. The integration runs at the IMU's
    times; t_out outside them is clipped to the IMU's span. Raises ValueError naming what is missing.
    """
    if len(imu) < 10:
        raise ValueError(f"dead reckoning needs IMU samples; found {len(imu)}")
    if len(dvl) < 2:
        raise ValueError(f"dead reckoning needs DVL velocities (bottom lock); found {len(dvl)}")
    if len(pressure) < 2:
        raise ValueError(f"dead reckoning needs pressure samples; found {len(pressure)}")
    if not depth_time_constant > 0:
        raise ValueError(f"depth time constant {depth_time_constant}: expected a positive number of seconds")
    t = imu[:, 0]
    dt = np.diff(t)
    if np.any(dt <= 0):
        keep = np.concatenate([[True], dt > 0])
        imu, t = imu[keep], imu[keep, 0]
        dt = np.diff(t)
    w_b = imu[:, 1:4] @ mounts.imu_R.T
    f_b = imu[:, 4:7] @ mounts.imu_R.T
    # 1. attitude: levelled on the accelerometer at rest, then the gyro integrated (midpoint rates)
    at_rest = t <= t[0] + level_time
    roll0, pitch0 = level(f_b[at_rest].mean(axis=0))
    R = np.empty((len(t), 3, 3))
    R[0] = rpy_matrix((roll0, pitch0, initial_yaw))
    for k in range(len(t) - 1):
        R[k + 1] = R[k] @ _skew_exp(0.5 * (w_b[k] + w_b[k + 1]) * dt[k])
    # 2. velocity: DVL frame -> body, less the lever arm's w x r, interpolated to the IMU times
    w_at_dvl = np.stack([np.interp(dvl[:, 0], t, w_b[:, i]) for i in range(3)], -1)
    v_b_dvl = dvl[:, 1:4] @ mounts.dvl_R.T - np.cross(w_at_dvl, mounts.dvl_r)
    v_b = np.stack([np.interp(t, dvl[:, 0], v_b_dvl[:, i]) for i in range(3)], -1)
    v_w = np.einsum("nij,nj->ni", R, v_b)
    pos = np.zeros((len(t), 3))
    pos[1:] = np.cumsum(0.5 * (v_w[1:] + v_w[:-1]) * dt[:, None], axis=0)
    pos[:, 0] += initial_xy[0]
    pos[:, 1] += initial_xy[1]
    # 3. depth: the pressure sensor's z, moved to the hull centre, fused with the integrated DVL heave
    k_p = np.clip(np.searchsorted(t, pressure[:, 0]), 0, len(t) - 1)
    z_centre = (
        surface_z
        - (pressure[:, 1] - atmospheric_pressure) / (water_density * gravity)
        - np.einsum("nj,j->n", R[k_p, 2, :], mounts.pressure_r)
    )
    z_meas = np.interp(t, pressure[:, 0], z_centre)
    from scipy.signal import lfilter

    # complementary filter: z = I + LP(z_meas - I), I the integrated DVL heave, LP first order of time
    # constant T (exact discretisation at each step's dt is not needed: the IMU rate is uniform)
    alpha = float(np.median(dt)) / depth_time_constant
    alpha = min(alpha, 1.0)
    err = z_meas - pos[:, 2]
    start = err[at_rest].mean()
    low, _ = lfilter([alpha], [1.0, alpha - 1.0], err, zi=[start * (1.0 - alpha)])
    pos[:, 2] += low
    # 4. sample the pose at t_out
    rpy = matrices_to_rpy(R)
    rpy[:, 2] = np.unwrap(rpy[:, 2])
    t_out = np.clip(np.asarray(t_out, float), t[0], t[-1])
    cols = [np.interp(t_out, t, pos[:, i]) for i in range(3)] + [np.interp(t_out, t, rpy[:, i]) for i in range(3)]
    return np.column_stack([t_out] + cols)

"""Dead reckoning from the robot's own sensors (no ROS): the IMU's rates for the attitude, the DVL's bottom-track
velocity for the horizontal position, the pressure for the depth.

- Attitude: the body rates (IMU frame = body frame on the UX-1) integrated as a rotation vector per sample
  (exact for a rate constant over the sample's interval), from the known start attitude.
- Velocity: the DVL's velocity (its own frame) turned into the body frame, less the lever arm's ω × r, and into
  the world frame with the attitude at the ping; held in the world frame until the next ping (held in the body
  frame, a robot that turns all the time would see its velocity turn with it between pings: a drift sideways
  growing with the distance); without bottom lock (no bottom within 75 m, as in a deep shaft) the last locked
  velocity decays with the drag's time constant (`coast_tau`) and the estimate is flagged.
- Position: x, y integrate the world-frame velocity; z = start z - (p - p_start) / (ρ g) (the pressure sensor's
  offset on the hull cancels with the start reading at the start attitude).

The start: the attitude from the first odometry's quaternion (quat_matrix), the DVL's mounting from the robot
description (sensor_joint).
"""

import math
import xml.etree.ElementTree as ET

import numpy as np

from unexmin.geometry import rpy_matrix


def exp_so3(w):
    """Rotation matrix of a rotation vector w [rad] (Rodrigues)."""
    a = float(np.linalg.norm(w))
    if a < 1e-12:
        return np.eye(3)
    k = w / a
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(a) * K + (1 - math.cos(a)) * K @ K


class DeadReckoning:
    """Pose estimate of one robot. `dvl_rotation` (3 x 3) and `dvl_offset` [m]: the DVL frame in the body frame."""

    def __init__(self, position, attitude, time, dvl_rotation, dvl_offset, density, gravity, coast_tau=4.0):
        self.p = np.asarray(position, float).copy()
        self.R = np.asarray(attitude, float).copy()  # body to world
        self.t = float(time)
        self.dvl_R = np.asarray(dvl_rotation, float)
        self.dvl_r = np.asarray(dvl_offset, float)
        self.rho_g = density * gravity
        self.coast_tau = coast_tau
        self.v_world = np.zeros(3)  # [m/s] the last ping's velocity in the world frame
        self.omega = np.zeros(3)
        self.z0 = float(position[2])
        self.p0 = None  # [Pa] pressure at the start
        self.locked = True
        self.lock_lost_s = 0.0  # [s] of sim time without bottom lock

    @property
    def v_body(self):
        """[m/s] the estimated velocity in the body frame now."""
        return self.R.T @ self.v_world

    @property
    def yaw(self):
        return math.atan2(self.R[1, 0], self.R[0, 0])

    def rates(self, samples):
        """IMU samples [(t [s], body rate [rad/s] 3)], oldest first: the attitude integrated over each."""
        for t, w in samples:
            dt = t - self.t
            if dt <= 0:
                continue
            self.omega = np.asarray(w, float)
            self.R = self.R @ exp_so3(self.omega * dt)
            self._advance(dt)
            self.t = t

    def _advance(self, dt):
        if not self.locked:
            self.v_world *= math.exp(-dt / self.coast_tau)
            self.lock_lost_s += dt
        self.p[:2] += self.v_world[:2] * dt

    def dvl(self, lock, velocity):
        """A DVL ping: bottom lock and the velocity [m/s] in the DVL frame."""
        self.locked = bool(lock) and all(math.isfinite(v) for v in velocity)
        if self.locked:
            self.v_world = self.R @ (self.dvl_R @ np.asarray(velocity, float) - np.cross(self.omega, self.dvl_r))

    def pressure(self, pa):
        """A pressure reading [Pa]: the depth."""
        if self.p0 is None:
            self.p0 = float(pa)
        self.p[2] = self.z0 - (float(pa) - self.p0) / self.rho_g


def sensor_joint(description, child):
    """(rotation 3x3, offset [m]) of the fixed joint whose child link is `child`, from a URDF string."""
    root = ET.fromstring(description)
    for joint in root.iter("joint"):
        c = joint.find("child")
        if c is not None and c.get("link") == child:
            o = joint.find("origin")
            xyz = [float(v) for v in (o.get("xyz", "0 0 0") if o is not None else "0 0 0").split()]
            rpy = [float(v) for v in (o.get("rpy", "0 0 0") if o is not None else "0 0 0").split()]
            return rpy_matrix(rpy), np.array(xyz)
    raise LookupError(f"the robot description has no joint whose child is {child}")


def quat_matrix(q):
    """Rotation matrix (body to world) of a quaternion with fields x, y, z, w (geometry_msgs/Quaternion)."""
    x, y, z, w = q.x, q.y, q.z, q.w
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )

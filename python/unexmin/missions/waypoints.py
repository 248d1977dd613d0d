"""A straight route through the shipped mine and a waypoint controller (no ROS): the shaft's axis, then the first
level's gallery's centreline, flown by a velocity command along the error. The batch missions' gallery_traverse
and station_keeping (missions/batch.py) and the gym's gallery task (gym/tasks.py) use them; the main job flies the
survey of survey.py instead."""

import math

import numpy as np

from unexmin.geometry import yaw_of

SPEED = 0.4  # [m/s] cruise speed
TOLERANCE = 0.5  # [m] a waypoint is reached within this distance


def waypoints(gallery_length):
    """A straight path [m, world frame] (the batch missions'): the shaft's axis from the spawn depth down to the
    first level's gallery, then that gallery's centreline (from the mine generator's layout, seed 7)."""
    from unexmin.worlds.generator.generator import PRESETS, make_layout, point_on

    layout = make_layout(PRESETS["full"], 7)
    sx, sy = layout.shaft_xy
    gallery = next(t for t in layout.tunnels if t.kind == "gallery")
    poly = np.asarray(gallery.points, dtype=float)
    z0 = poly[0, 2]
    path = [(sx, sy, -2.5), (sx, sy, z0 + 0.3)]
    for x in np.arange(sx + 4.0, sx + gallery_length + 1e-9, 4.0):
        p = point_on(poly, x)
        path.append((float(p[0]), float(p[1]), float(p[2]) + 0.3))
    return path


def controller(pose, twist, target, yaw_target=0.0, speed=SPEED):
    """Body wrench [X Y Z K M N] (allocation units) towards target: a velocity command along the error
    (`speed` [m/s] at most, SPEED by default), feed-forward for the quadratic drag, proportional on the velocity
    error; yaw held."""
    p = np.array([pose.position.x, pose.position.y, pose.position.z])
    yaw = yaw_of(pose.orientation)
    c, s = math.cos(yaw), math.sin(yaw)
    err = np.array(target) - p
    dist = float(np.linalg.norm(err))
    v_des = err / dist * min(speed, 0.5 * dist) if dist > 1e-6 else np.zeros(3)
    # to the body frame (yaw only; the UX-1 is kept level by its pendulum)
    v_des_b = np.array([c * v_des[0] + s * v_des[1], -s * v_des[0] + c * v_des[1], v_des[2]])
    v_b = np.array([twist.linear.x, twist.linear.y, twist.linear.z])  # odometry twist: child (body) frame
    ff = 10.0 * (v_des_b / 0.4) * np.abs(v_des_b / 0.4)
    force = np.clip(ff + 25.0 * (v_des_b - v_b), -15.0, 15.0)
    yaw_err = math.remainder(yaw_target - yaw, 2 * math.pi)
    n = float(np.clip(3.0 * yaw_err - 4.0 * twist.angular.z, -3.0, 3.0))
    return (float(force[0]), float(force[1]), float(force[2]), 0.0, 0.0, n), dist

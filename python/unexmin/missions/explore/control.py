"""One robot's control on its own estimate (e: the Explorer, a: one of its agents): the sensors feed the dead
reckoning (sense), the M3 guard stops a motion into an echo (sonar_blocked), the path tracker and the thruster
allocator fly the reference (control)."""

import math

import numpy as np

from unexmin.missions.explore.budget import power


def sense(e, a, sim):
    """Feeds `a`'s dead reckoning with what its IMU, DVL and pressure sensor sent since the last call."""
    msgs = a.imu.messages
    a.imu.clear()
    a.nav.rates(
        [(m.header.stamp.to_sec(), (m.angular_velocity.x, m.angular_velocity.y, m.angular_velocity.z)) for m in msgs]
    )
    try:
        dvl = a.handle.latest("dvl")
        if dvl.header.stamp.to_sec() > a.last_dvl:
            a.last_dvl = dvl.header.stamp.to_sec()
            was = a.nav.locked
            a.nav.dvl(dvl.bottom_lock, (dvl.velocity.x, dvl.velocity.y, dvl.velocity.z))
            if was and not a.nav.locked:
                e.event(sim.time, a.name, "dvl_lock_lost", "coasting on the last velocity")
        a.nav.pressure(a.handle.latest("pressure").fluid_pressure)
    except LookupError:
        pass  # before the DVL's first ping (t < 1/8 s)


def control(e, a, t, dt):
    """One controller update of `a` over `dt` [s] at sim time `t` [s]: the reference along its path (or where it
    holds), the M3 guard, the thrusts, the energy spent, and the path given up when stuck, done or blocked."""
    o = e.o
    if a.mode == "home" or a.path is None:
        if a.hold is None:
            a.hold = a.nav.p.copy()
        ref, vel = (a.home if a.mode == "home" else a.hold), np.zeros(3)
    else:
        ref, vel = a.reference(o.speed)
    a.yaw_ref += o.yaw_rate * dt if a.mode != "home" else 0.0
    v_body = a.nav.v_body
    yaw = a.nav.yaw
    c, s = math.cos(yaw), math.sin(yaw)
    # the motion wanted, in the body frame, for the sonar guard
    want = vel + 0.8 * (ref - a.nav.p)
    want_b = np.array([c * want[0] + s * want[1], -s * want[0] + c * want[1], want[2]])
    try:
        scan = a.handle.latest("m3/scan")
    except LookupError:
        scan = None
    blocked, echo = sonar_blocked(scan, want_b, o.sonar_guard)
    if blocked and a.mode != "home":
        m3_offset = np.array([0.27, 0.0, -0.13])  # the M3 on the hull's front, 25 degrees down
        point = a.nav.p + a.nav.R @ (m3_offset + echo)
        e.sonar_points.append(point)
        e.event(t, a.name, "sonar_stop", f"echo {np.linalg.norm(echo):.2f} m ahead at {point.round(2).tolist()}")
        if a.goal is not None:
            e.avoid.append(a.goal)
        a.path, a.goal, a.hold = None, None, a.nav.p.copy()
        ref, vel = a.hold, np.zeros(3)
    from unexmin.missions.survey import track

    pose, twist = _pose_msgs(a, v_body, a.nav.omega[2])
    wrench, dist, _ = track(pose, twist, np.array([*ref, a.yaw_ref]), np.array([*vel, o.yaw_rate]), o.speed + 0.1)
    thrusts, scale = e.allocator.allocate(wrench)
    a.handle.thrusts(thrusts)
    a.energy += power([scale * f for f in wrench[:3]], v_body, scale * wrench[5], a.nav.omega[2]) * dt
    if a.path is not None and dist < o.hold_distance:
        a.s += o.speed * dt
    if a.path is not None:
        if a.s - a.progress_mark[1] >= o.stuck_m:
            a.progress_mark = (t, a.s)
        elif t - a.progress_mark[0] > o.stuck_s:
            e.event(t, a.name, "stuck", f"{dist:.2f} m from its reference for {o.stuck_s:.0f} s")
            if a.goal is not None:
                e.avoid.append(a.goal)
            a.path, a.goal, a.hold = None, None, a.nav.p.copy()
        elif a.s >= a.path_length() and dist < o.goal_tolerance:
            if a.mode == "explore":
                e.avoid.append(a.goal)
                a.path, a.goal, a.hold = None, None, a.nav.p.copy()
            elif a.mode == "return" and np.linalg.norm(a.nav.p - a.home) < max(o.home_tolerance, 0.3):
                a.mode = "home"
                e.event(t, a.name, "home", f"{a.why}; estimated {np.linalg.norm(a.nav.p - a.home):.2f} m off")


def _pose_msgs(agent, twist_v, yaw_rate):
    from geometry_msgs.msg import Pose, Twist

    pose, twist = Pose(), Twist()
    pose.position.x, pose.position.y, pose.position.z = agent.nav.p.tolist()
    yaw = agent.nav.yaw
    pose.orientation.z, pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    twist.linear.x, twist.linear.y, twist.linear.z = twist_v.tolist()
    twist.angular.z = yaw_rate
    return pose, twist


def sonar_blocked(scan, v_body, guard):
    """(True, echo point in the M3 frame [m]) when an M3 echo within 25 degrees of the horizontal motion direction
    is nearer than `guard` [m]."""
    if scan is None or math.hypot(v_body[0], v_body[1]) < 0.05:
        return False, None
    heading = math.atan2(v_body[1], v_body[0])
    r = np.asarray(scan.ranges, float)
    a = scan.angle_min + scan.angle_increment * np.arange(len(r))
    sel = (np.abs(np.remainder(a - heading + math.pi, 2 * math.pi) - math.pi) < math.radians(25)) & np.isfinite(r)
    if not sel.any():
        return False, None
    i = np.flatnonzero(sel)[np.argmin(r[sel])]
    if r[i] >= guard:
        return False, None
    return True, np.array([r[i] * math.cos(a[i]), r[i] * math.sin(a[i]), 0.0])

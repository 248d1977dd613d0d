"""Missions shipped for `python -m unexmin.batch` (docs/batch.md): mission(sim, params) -> dict of metrics.

`sim` is a launched, paused, lockstep Simulation; `params` holds the mission's swept and sampled
parameters and `seed`, `index`, `duration` [s of sim time], `robots`. Every mission here drives UX_1 with
the thesis allocation (eq. 5.12) on thruster commands sent by this process (deterministic in lockstep)
and reads ground-truth odometry.

- tank_survey: the tank mission of the main job (unexmin.missions.tank's legs), cut or padded with coasting to
  `duration`; metrics: where the robot ended and how far it went.
- station_keeping: hold the spawn position against the current with the waypoint controller of the mine
  mission; metrics: position error statistics and effort.
- gallery_traverse: the mine mission's path down the entry shaft and along the first level's gallery
  (`gallery` metres, default 20); metrics: waypoints reached, progress, whether it reached the end.
"""

import math

import numpy as np

from unexmin.control.allocation import ThrusterAllocator
from unexmin.geometry import yaw_of

ROBOT = "UX_1"
CONTROL_DT = 0.1  # [s] sim time between controller updates (as the mine mission's)


def _position(ux):
    p = ux.odom().pose.pose.position
    return np.array([p.x, p.y, p.z])


def _track_metrics(track, times):
    """Metrics of a sampled path: net displacement, path length, top speed, end point."""
    track = np.asarray(track)
    steps = np.linalg.norm(np.diff(track, axis=0), axis=1)
    dt = np.maximum(np.diff(times), 1e-9)
    return {
        "net_displacement_m": float(np.linalg.norm(track[-1] - track[0])),
        "path_length_m": float(steps.sum()),
        "max_speed_m_s": float((steps / dt).max()) if len(steps) else 0.0,
        "end_x_m": float(track[-1, 0]),
        "end_y_m": float(track[-1, 1]),
        "end_z_m": float(track[-1, 2]),
    }


def tank_survey(sim, params):
    """The main job's tank mission (unexmin.missions.tank.LEGS), cut at or coasting to params['duration'] s."""
    from unexmin.missions.tank import LEGS

    ux = sim.robot(ROBOT, streams="none")
    allocator = ThrusterAllocator()
    duration = float(params["duration"])
    sim.step(1)
    yaw0 = yaw_of(ux.odom().pose.pose.orientation)
    track, times = [_position(ux)], [sim.time]
    legs = list(LEGS) + [("coast", (0, 0, 0, 0, 0, 0), math.inf)]
    for _, wrench, seconds in legs:
        end = min(sim.time + seconds, duration)
        ux.thrusts(allocator.allocate(wrench)[0])
        while sim.time < end - 1e-9:  # sampled every 0.5 s for the path metrics
            sim.run_for(min(0.5, end - sim.time))
            track.append(_position(ux))
            times.append(sim.time)
        if sim.time >= duration - 1e-9:
            break
    metrics = _track_metrics(track, times)
    metrics["yaw_change_deg"] = math.degrees(
        math.remainder(yaw_of(ux.odom().pose.pose.orientation) - yaw0, 2 * math.pi)
    )
    metrics["sim_time_s"] = sim.time
    return metrics


def station_keeping(sim, params):
    """Hold the spawn position for params['duration'] s (against the world's current) with the mine
    mission's controller; errors are measured after a settling time of min(5 s, duration / 2)."""
    from unexmin.missions.waypoints import controller

    ux = sim.robot(ROBOT, streams="none")
    allocator = ThrusterAllocator()
    duration = float(params["duration"])
    sim.step(1)
    odom = ux.odom()
    target = _position(ux)
    yaw0 = yaw_of(odom.pose.pose.orientation)
    settle = min(5.0, duration / 2.0)
    errors, effort = [], []
    steps = max(1, round(CONTROL_DT * sim.physics_rate))
    while sim.time < duration - 1e-9:
        odom = ux.odom()
        wrench, dist = controller(odom.pose.pose, odom.twist.twist, target, yaw0)
        thrusts = allocator.allocate(wrench)[0]
        ux.thrusts(thrusts)
        if sim.time >= settle:
            errors.append(dist)
            effort.append(float(np.abs(thrusts).sum()))
        sim.step(steps)
    final = float(np.linalg.norm(_position(ux) - target))
    errors = np.array(errors or [final])
    return {
        "mean_error_m": float(errors.mean()),
        "max_error_m": float(errors.max()),
        "rms_error_m": float(np.sqrt((errors**2).mean())),
        "final_error_m": final,
        "mean_total_thrust_N": float(np.mean(effort)) if effort else 0.0,
        "sim_time_s": sim.time,
    }


def gallery_traverse(sim, params):
    """The mine mission's path (shaft, then params.get('gallery', 20) m of the first level's gallery) flown
    with its waypoint controller for at most params['duration'] s (world: mine)."""
    from unexmin.missions.waypoints import TOLERANCE, controller, waypoints

    ux = sim.robot(ROBOT, streams="none")
    allocator = ThrusterAllocator()
    duration = float(params["duration"])
    path = waypoints(float(params.get("gallery", 20.0)))
    sim.step(1)
    steps = max(1, round(CONTROL_DT * sim.physics_rate))
    reached, t_end = 0, math.nan
    track, times = [_position(ux)], [sim.time]
    for target in path:
        while sim.time < duration - 1e-9:
            odom = ux.odom()
            wrench, dist = controller(odom.pose.pose, odom.twist.twist, target)
            if dist < TOLERANCE:
                break
            ux.thrusts(allocator.allocate(wrench)[0])
            sim.step(steps)
            track.append(_position(ux))
            times.append(sim.time)
        if np.linalg.norm(_position(ux) - np.array(target)) >= TOLERANCE:
            break
        reached += 1
    if reached == len(path):
        t_end = sim.time
    metrics = _track_metrics(track, times)
    metrics.update(
        {
            "waypoints_reached": reached,
            "waypoints": len(path),
            "reached_end": reached == len(path),
            "time_to_end_s": t_end if reached == len(path) else -1.0,
            "sim_time_s": sim.time,
        }
    )
    return metrics

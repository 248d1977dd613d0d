"""The mine survey's plan and its tracking controller (docs/mapping.md, "The mission"). No ROS.

The plan is read from the mine generator's layout (the report `<name>.json` beside the world's collision mesh
gives the seed and the preset), so it follows any generated mine:
1. the entry shaft: a helix around the shaft's axis, `standoff` from its nominal wall, from just under the water
   surface down to `below` metres under the first level (the shaft goes on to the lower levels), the robot
   turning with the helix and facing the axis (the M3 fan across the shaft, the SLS units on the near and
   side walls, every unit's motor sweeping), `helix_pitch` metres down per turn;
2. back up the axis to the first level;
3. the first level's gallery, out and back over `gallery` metres: out off-centre to one side and low, back to
   the other side and high (`standoff` from the nominal walls), the robot turning about its vertical axis all
   the way (every SLS unit and the M3 fan paint the walls, the floor and the roof around it); on the way out,
   each side tunnel (crosscut, chamber, ramp) that opens on that stretch is flown along its first leg, out low
   by one wall and back high by the other (`gallery_standoff` from its nominal walls, `section_offsets`), in
   and out through its axis at the junction, still turning.
Where the water is murky the SLS units see only a short way (`sls_reach`): the passes come closer to the walls,
as close as the rock's roughness allows (`options_for`), where the units do not reach across the gallery it
is flown twice more, out low by the other wall and back high by the first, so that every corner is passed near,
and the helix goes on deeper (MURKY_BELOW: the units see the shaft's walls, not a gallery's floor or roof).
The pendulum pitches the robot (a positive angle: nose down, about 10 degrees at its 30-degree limit;
docs/hydrodynamics.md): nose up for the first turn of the helix (the shaft above), nose down under the first
level (the shaft below), level otherwise (pitched in the gallery, the M3 fan grazes the floor far off and
its wide beam puts points in the water).
A plan is a list of keyframes (x, y, z [m], yaw [rad] unwrapped, pendulum [rad]) with the time [s] to reach
each from the previous one; `Reference` interpolates it.
"""

import json
import math
import os
from dataclasses import dataclass

import numpy as np

HULL_RADIUS = 0.3  # [m] the UX-1's spherical hull
CLEARANCE = 0.2  # [m] of water kept between the planned hull and the rock
MESH_MARGIN = 0.05  # [m] more, for the collision mesh's flat facets across curved, rough walls
# [m] how far the SLS units see a wall of albedo 0.3 facing them, per visibility level (docs/sls.md; test_sls.cpp
# solves the detection formula for it)
SLS_REACH = {"none": 5.0, "low": 4.9, "medium": 1.85, "high": 0.59}
# a unit paints a wall out to this angle off the wall's normal when the wall is at cos(angle) of its reach
PAINT_ANGLE = math.radians(55.0)
# a pass's corner point (by a side wall and the floor or the roof) keeps this share of the stand-off from the
# tunnel's nominal cross-section: the gallery's own corners keep 0.72 (murky water) to 0.82 (clear water)
CORNER_SHARE = 0.7
MURKY_BELOW = 14.0  # [m] the helix's depth under the first level where the SLS units see less than the stand-off


@dataclass
class SurveyOptions:
    gallery: float = 40.0  # [m] along the first level's gallery (out and back)
    standoff: float = 1.4  # [m] from the nominal (noise-free) wall of the shaft
    gallery_standoff: float = 1.3  # [m] from the nominal walls of the gallery (side, floor, roof)
    helix_pitch: float = 2.2  # [m] down per turn in the shaft
    shaft_speed: float = 0.3  # [m/s] along the helix
    below: float = 6.0  # [m] under the first level in the shaft
    surface_clearance: float = 1.2  # [m] the helix's top under the water surface (nearer, the M3 echoes off it)
    gallery_speed: float = 0.25  # [m/s] along the gallery
    gallery_yaw_rate: float = 0.25  # [rad/s] the turn while flying the gallery
    step_deg: float = 15.0  # [deg] of turn between keyframes
    sls_reach: float = 5.0  # [m] how far the SLS units see (SLS_REACH); shorter than across the gallery: 4 passes
    pendulum_deg: float = 30.0  # [deg] pendulum swing for the nose-up and nose-down parts (the model's limit)

    def check(self):
        for name in (
            "gallery",
            "standoff",
            "gallery_standoff",
            "helix_pitch",
            "shaft_speed",
            "gallery_speed",
            "sls_reach",
        ):
            if not getattr(self, name) > 0:
                raise ValueError(f"survey option {name} = {getattr(self, name)}: expected > 0")
        for name in ("below", "surface_clearance", "gallery_yaw_rate", "pendulum_deg"):
            if not getattr(self, name) >= 0:
                raise ValueError(f"survey option {name} = {getattr(self, name)}: expected >= 0")


def options_for(visibility, wall_noise, gallery=40.0):
    """SurveyOptions for a water visibility level (SLS_REACH) in a mine whose walls stray up to wall_noise [m]
    from their nominal surface (the generator's `wall_noise_max`): the stand-offs shrink to cos(PAINT_ANGLE) of
    the SLS reach, but never below the hull's radius, CLEARANCE, MESH_MARGIN and wall_noise; where they shrink
    (murky water) the helix goes down to MURKY_BELOW under the first level."""
    if visibility not in SLS_REACH:
        raise ValueError(f"visibility {visibility!r}: expected one of {', '.join(SLS_REACH)}")
    if not wall_noise >= 0:
        raise ValueError(f"wall_noise {wall_noise} m: expected >= 0")
    o = SurveyOptions(gallery=gallery, sls_reach=SLS_REACH[visibility])
    nearest = HULL_RADIUS + CLEARANCE + MESH_MARGIN + wall_noise
    wanted = math.cos(PAINT_ANGLE) * o.sls_reach
    if wanted < o.standoff:
        # murky: from their stand-off the units see neither the gallery's floor nor its roof (their cameras look
        # 32 degrees up and down at most), but every wall of the shaft from the helix: the helix goes on deeper
        o.below = MURKY_BELOW
    o.standoff = max(nearest, min(o.standoff, wanted))
    o.gallery_standoff = max(nearest, min(o.gallery_standoff, wanted))
    return o


def mine_layout(world_file):
    """(layout, preset) of the generated mine of a world file: the generator report beside its collision mesh."""
    from unexmin.worlds.files import load_world
    from unexmin.worlds.generator.generator import PRESETS, make_layout

    world = load_world(world_file)
    meshes = [m for m in world["meshes"] if m["collision"]]
    if not meshes:
        raise ValueError(f"{world_file}: no collision mesh, expected a generated mine")
    mesh = os.path.join(os.path.dirname(os.path.abspath(world_file)), meshes[0]["file"])
    if not mesh.endswith("_collision.ply"):
        raise ValueError(f"{world_file}: collision mesh {mesh} is not a mine generator's <name>_collision.ply")
    report = mesh[: -len("_collision.ply")] + ".json"
    if not os.path.exists(report):
        raise FileNotFoundError(f"{report}: the mine generator's report of {mesh} (python -m unexmin.worlds.generator)")
    with open(report) as f:
        r = json.load(f)
    preset = PRESETS[r["preset"]["name"]]
    return make_layout(preset, int(r["seed"])), preset


def section_offsets(tunnel, standoff):
    """(across, up) [m]: offsets from a tunnel's axis, towards a side wall and towards the floor or the roof, of a
    pass `standoff` from the nominal side wall and the nominal floor or roof: (a - standoff, b - standoff) (0
    where negative), shrunk together where a corner point (±across, ±up) would come nearer than CORNER_SHARE
    of the stand-off to the tunnel's nominal cross-section (the generator's superellipse: half width a, half
    height b, exponent p_floor below the axis and p_roof above; in a tall, rounded chamber the corners of
    (a - standoff, b - standoff) lie near the curved roof)."""
    theta = np.linspace(0.0, 2.0 * math.pi, 721)[:-1]
    ct, st = np.cos(theta), np.sin(theta)
    p = np.where(st < 0.0, tunnel.p_floor, tunnel.p_roof)
    r = (np.abs(ct / tunnel.a) ** p + np.abs(st / tunnel.b) ** p) ** (-1.0 / p)
    boundary = np.column_stack([r * ct, r * st])
    across, up = max(tunnel.a - standoff, 0.0), max(tunnel.b - standoff, 0.0)
    for _ in range(200):
        corners = np.array([[across, up], [-across, up], [across, -up], [-across, -up]])
        if np.linalg.norm(boundary[None, :, :] - corners[:, None, :], axis=2).min() >= CORNER_SHARE * standoff:
            break
        across, up = 0.98 * across, 0.98 * up
    return across, up


def _turns(yaw0, yaw1, step):
    n = max(1, int(math.ceil(abs(yaw1 - yaw0) / step)))
    return np.linspace(yaw0, yaw1, n + 1)[1:]


def plan(layout, preset, start, options=None):
    """Keyframes N x 5 (x, y, z, yaw, pendulum) and durations N [s] (the first: 0, the start pose)."""
    o = options or SurveyOptions()
    o.check()
    step = math.radians(o.step_deg)
    shaft = next(t for t in layout.tunnels if t.kind == "shaft")
    gallery = next(t for t in layout.tunnels if t.kind == "gallery")
    sx, sy = layout.shaft_xy
    poly = gallery.points
    z_level = float(poly[0, 2])
    r = shaft.a - o.standoff
    if r < 0.2:
        raise ValueError(f"survey standoff {o.standoff} m: the shaft's half width is {shaft.a} m")
    z_top = preset.surface_z - o.surface_clearance
    z_bottom = max(z_level - o.below, float(shaft.points[:, 2].min()) + shaft.c + 1.5)
    up, down = -math.radians(o.pendulum_deg), math.radians(o.pendulum_deg)
    frames = [tuple(float(v) for v in start[:4]) + (0.0,)]
    times = [0.0]

    def go(x, y, z, yaw, speed, yaw_rate=0.2, pendulum=None):
        px, py, pz, pyaw, ppend = frames[-1]
        d = math.dist((px, py, pz), (x, y, z))
        frames.append((x, y, z, yaw, ppend if pendulum is None else pendulum))
        times.append(max(d / speed, abs(yaw - pyaw) / yaw_rate if yaw_rate > 0 else 0.0, 0.1))

    # 1. the helix, facing the axis: position angle theta, yaw theta + pi
    theta0 = math.atan2(start[1] - sy, start[0] - sx)
    yaw0 = start[3] + math.remainder(theta0 + math.pi - start[3], 2 * math.pi)
    go(sx + r * math.cos(theta0), sy + r * math.sin(theta0), z_top, yaw0, o.shaft_speed, pendulum=up)
    turns = (z_top - z_bottom) / o.helix_pitch
    omega = o.shaft_speed / math.hypot(r, o.helix_pitch / (2 * math.pi))
    for yaw in _turns(yaw0, yaw0 + 2 * math.pi * turns, step):
        theta = yaw - math.pi
        z = z_top - (yaw - yaw0) / (2 * math.pi) * o.helix_pitch
        pendulum = up if yaw - yaw0 < 2 * math.pi else down if z < z_level else 0.0
        go(sx + r * math.cos(theta), sy + r * math.sin(theta), z, yaw, o.shaft_speed, 1.05 * omega, pendulum)
    # 2. up the axis to the level, then facing along the gallery (+x)
    yaw = frames[-1][3]
    go(sx, sy, z_bottom, yaw, o.shaft_speed, pendulum=0.0)
    go(sx, sy, z_level, yaw, o.shaft_speed)
    yaw = round(yaw / (2 * math.pi)) * 2 * math.pi
    go(sx, sy, z_level, yaw, o.shaft_speed)

    # 3. the gallery, out (one side, low) and back (other side, high), turning; where the SLS units do not
    # reach across it, out again low by the other side and back high by the first
    g_across, g_up = section_offsets(gallery, o.gallery_standoff)

    def offset_point(x, side, vertical):
        p = np.array([x, np.interp(x, poly[:, 0], poly[:, 1]), np.interp(x, poly[:, 0], poly[:, 2])])
        t = np.array([1.0, np.interp(x + 0.5, poly[:, 0], poly[:, 1]) - np.interp(x - 0.5, poly[:, 0], poly[:, 1])])
        n = np.array([-t[1], t[0]]) / np.linalg.norm(t)
        return p[0] + n[0] * g_across * side, p[1] + n[1] * g_across * side, p[2] + g_up * vertical

    x0 = sx + shaft.a + 0.5
    x1 = min(sx + o.gallery, float(poly[-1, 0]) - 3.0)
    if x1 <= x0:
        raise ValueError(f"survey gallery {o.gallery} m: the first level's gallery is too short")
    per_step = step / o.gallery_yaw_rate * o.gallery_speed if o.gallery_yaw_rate > 0 else 1.0
    murky = o.sls_reach < 2.0 * min(gallery.a, gallery.b) - o.gallery_standoff

    def fly(p, q):
        """Straight from p to q [m], turning."""
        nonlocal yaw
        n = max(1, int(math.ceil(math.dist(p, q) / per_step)))
        for f in np.linspace(0.0, 1.0, n + 1)[1:]:
            yaw += step if o.gallery_yaw_rate > 0 else 0.0
            go(
                *(np.asarray(p) + f * (np.asarray(q) - np.asarray(p))).tolist(),
                yaw,
                o.gallery_speed,
                1.05 * o.gallery_yaw_rate,
            )

    # side tunnels opening on the stretch (crosscuts, chambers, ramps): their first leg, from the end on the
    # gallery to the next point of the tunnel's axis, lies within the sensors' range of the gallery; it is flown
    # out low by one wall and back high by the other, `gallery_standoff` from its nominal walls
    def gap(pt):
        return abs(pt[1] - np.interp(pt[0], poly[:, 0], poly[:, 1])) + abs(pt[2] - z_level)

    sides = []
    for t in layout.tunnels:
        if t.kind not in ("crosscut", "chamber", "ramp") or len(t.points) < 2:
            continue
        near, far = (t.points[0], t.points[1]) if gap(t.points[0]) <= gap(t.points[-1]) else t.points[[-1, -2]]
        u = far - near
        if not (x0 + 1.0 <= near[0] <= x1 - 1.0 and gap(near) < gallery.a + t.a) or math.hypot(u[0], u[1]) < 1e-6:
            continue
        t_across, t_up = section_offsets(t, o.gallery_standoff)
        n = np.array([-u[1], u[0], 0.0]) / math.hypot(u[0], u[1])
        low, high = -t_across * n - [0.0, 0.0, t_up], t_across * n + [0.0, 0.0, t_up]
        # in and out through the tunnel's axis at the junction (a straight line from a pass's corner to the
        # other tunnel's corner would cut the rock between them)
        sides.append((float(near[0]), [near, near + low, far + low, far + high, near + high, near]))
    sides.sort(key=lambda v: v[0])
    passes = [(1, -1, (x0, x1)), (-1, 1, (x1, x0))]
    if murky:
        passes += [(-1, -1, (x0, x1)), (1, 1, (x1, x0))]
    for k, (side, vertical, (xa, xb)) in enumerate(passes):
        go(*offset_point(xa, side, vertical), yaw, o.gallery_speed, pendulum=0.0)
        stops = [v for v in sides if k == 0] + [(xb, None)]
        x = xa
        for xs, corners in stops:
            n = max(1, int(math.ceil(abs(xs - x) / per_step)))
            for xi in np.linspace(x, xs, n + 1)[1:]:
                yaw += step if o.gallery_yaw_rate > 0 else 0.0
                go(*offset_point(float(xi), side, vertical), yaw, o.gallery_speed, 1.05 * o.gallery_yaw_rate)
            x = xs
            if corners is not None:
                route = [offset_point(xs, side, vertical)] + [tuple(c) for c in corners]
                route.append(offset_point(xs, side, vertical))
                for p, q in zip(route, route[1:]):
                    fly(p, q)
    go(sx + shaft.a - 1.0, sy, z_level, yaw, o.gallery_speed, pendulum=0.0)
    return np.array(frames), np.array(times)


class Reference:
    """The plan as a function of progress s [s]: (x, y, z, yaw, pendulum) and its rate (per second of progress)."""

    def __init__(self, frames, times):
        self.frames = np.asarray(frames, dtype=float)
        self.t = np.cumsum(times)
        self.duration = float(self.t[-1])

    def __call__(self, s):
        s = min(max(s, 0.0), self.duration)
        k = int(np.clip(np.searchsorted(self.t, s, side="right"), 1, len(self.t) - 1))
        a, b = self.frames[k - 1], self.frames[k]
        dt = self.t[k] - self.t[k - 1]
        f = (s - self.t[k - 1]) / dt if dt > 0 else 1.0
        rate = (b - a) / dt if dt > 0 and s < self.duration else np.zeros(len(a))
        return a + f * (b - a), rate


def track(pose, twist, ref, rate, speed_limit=0.45):
    """Body wrench [X Y Z K M N] (allocation units) tracking a moving reference: the reference's velocity plus
    a proportional pull to it (at most speed_limit), quadratic-drag feed-forward, a proportional velocity loop;
    yaw: the reference yaw and yaw rate. Returns (wrench, position error [m], yaw error [rad])."""
    from unexmin.geometry import yaw_of

    p = np.array([pose.position.x, pose.position.y, pose.position.z])
    yaw = yaw_of(pose.orientation)
    c, s = math.cos(yaw), math.sin(yaw)
    err = ref[:3] - p
    v_des = rate[:3] + 0.8 * err
    norm = float(np.linalg.norm(v_des))
    if norm > speed_limit:
        v_des *= speed_limit / norm
    v_des_b = np.array([c * v_des[0] + s * v_des[1], -s * v_des[0] + c * v_des[1], v_des[2]])
    v_b = np.array([twist.linear.x, twist.linear.y, twist.linear.z])
    ff = 10.0 * (v_des_b / 0.4) * np.abs(v_des_b / 0.4)
    force = np.clip(ff + 25.0 * (v_des_b - v_b), -15.0, 15.0)
    yaw_err = math.remainder(ref[3] - yaw, 2 * math.pi)
    # yaw: the rotational quadratic drag (0.767 N m s^2/rad^2, urdf/properties.xacro) as feed-forward
    n = 3.0 * yaw_err + 4.0 * (rate[3] - twist.angular.z) + 0.767 * rate[3] * abs(rate[3])
    n = float(np.clip(n, -3.0, 3.0))
    return (float(force[0]), float(force[1]), float(force[2]), 0.0, 0.0, n), float(np.linalg.norm(err)), yaw_err

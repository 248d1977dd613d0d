"""The explorer's loop (docs/explore.md): the world in lockstep with the mapper on, one to three robots flying to
frontiers of the live map on their dead-reckoned poses, back to the start when the budget runs low.

Ground truth (the simulator's odometry and the world's mesh) is read only to score: drift, distance flown,
clearance to the rock (a contact is reported), explored share of the reachable volume.
"""

import math
import os
import time
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

import numpy as np

from unexmin.explore.budget import Budget, power
from unexmin.explore.grid import FREE, OCCUPIED, empty_grid, grid_from_leaves
from unexmin.explore.navigation import DeadReckoning
from unexmin.explore.octree import read_leaves
from unexmin.explore.plan import (
    Graph,
    PlanOptions,
    ball_mask,
    choose_goals,
    frontiers,
    gain_map,
    path_to,
    traversable,
)
from unexmin.geometry import rpy_matrix

SLS_UNITS = 4
CLOUDS_PER_S = 40 + 10 * SLS_UNITS  # per robot: the M3 at 40 Hz, each SLS unit at 10 Hz
STREAMS = ["imu", "dvl", "pressure", "m3/scan"]


@dataclass
class ExploreOptions:
    robots: int = 1  # how many of the world's robots explore (1..3)
    speed: float = 0.3  # [m/s] along the path
    yaw_rate: float = 0.2  # [rad/s] the robot turns all the time (its sensors sweep the walls, floor and roof)
    control_dt: float = 0.2  # [s] of sim time between controller updates
    map_period: float = 5.0  # [s] of sim time between map reads (and replanning)
    cell_voxels: int = 4  # grid cell edge in map voxels (0.4 m at the default resolution)
    resolution: float = 0.1  # [m] the mapper's voxel edge
    bounds: tuple = None  # ((x, y, z), (x, y, z)) [m] the box explored; None: around the start (default_bounds)
    goal_tolerance: float = 0.8  # [m] a goal is reached within this
    home_tolerance: float = 0.5  # [m] the start is reached within this (estimated position)
    hold_distance: float = 0.4  # [m] the reference waits while the robot is farther than this from it
    stuck_s: float = 20.0  # [s] a robot that has not advanced stuck_m along its path in this time is stuck
    stuck_m: float = 0.3  # [m]
    sonar_guard: float = 0.45  # [m] an M3 echo this near the hull ahead of the motion stops the robot
    robot_clearance: float = 1.2  # [m] between robots' centres in their plans
    snapshot: float = 0.0  # [s] of sim time between saved maps (snapshots/, scored at the end); 0: none
    idle_replans: int = 3  # replans in a row without a goal before the robot calls the box explored
    grace_s: float = 120.0  # [s] past the time budget before the run is stopped (a robot not home is reported)

    def check(self):
        if self.robots not in (1, 2, 3):
            raise ValueError(f"explore option robots = {self.robots}: expected 1, 2 or 3")
        for name in ("speed", "control_dt", "map_period", "resolution", "goal_tolerance", "home_tolerance"):
            if not getattr(self, name) > 0:
                raise ValueError(f"explore option {name} = {getattr(self, name)}: expected > 0")
        for name in ("yaw_rate", "snapshot", "sonar_guard", "grace_s"):
            if not getattr(self, name) >= 0:
                raise ValueError(f"explore option {name} = {getattr(self, name)}: expected >= 0")
        if self.cell_voxels not in (1, 2, 4, 8):
            raise ValueError(f"explore option cell_voxels = {self.cell_voxels}: expected 1, 2, 4 or 8")


def default_bounds(start, world_box, surface_z, reach=(40.0, 15.0, 25.0)):
    """A box around the start [m]: reach metres along x and y either way and down, clipped to the world's box
    and to the water surface."""
    start = np.asarray(start, float)
    lo = np.maximum(start - reach, world_box[0])
    hi = np.minimum(start + (reach[0], reach[1], 0.5), world_box[1])
    hi[2] = min(max(hi[2], start[2] + 0.5), surface_z)
    return lo, hi


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


@dataclass
class Agent:
    """One robot's state in the loop."""

    name: str
    handle: object
    imu: object  # Collector of the IMU
    nav: DeadReckoning
    home: np.ndarray
    mode: str = "explore"  # explore, return, home
    why: str = ""
    path: np.ndarray = None  # [m] points of the path followed
    s: float = 0.0  # [m] the reference's arc length along the path
    goal: np.ndarray = None
    hold: np.ndarray = None  # [m] where the robot waits without a path
    idle: int = 0  # replans in a row without a goal
    yaw_ref: float = 0.0
    energy: float = 0.0  # [J]
    flown: float = 0.0  # [m] true distance flown
    last_true: np.ndarray = None
    last_dvl: float = -1.0
    progress_mark: tuple = (0.0, 0.0)  # (sim time, arc length) of the last advance
    travelled_est: float = 0.0  # [m] estimated distance flown
    touching: bool = False
    min_clearance: float = math.inf  # [m] true clearance of the hull's centre to the rock
    home_m: float = 0.0  # [m] last path length home
    rows: list = field(default_factory=list)

    def set_path(self, points, t):
        self.hold = None
        pts = np.vstack([self.nav.p[None], np.asarray(points, float)])
        keep = np.concatenate([[True], np.linalg.norm(np.diff(pts, axis=0), axis=1) > 1e-6])
        self.path = pts[keep]
        self.s = 0.0
        self.progress_mark = (t, 0.0)

    def reference(self, speed):
        """(point [m], velocity [m/s]) of the reference at arc length s."""
        if self.path is None or len(self.path) < 2:
            return (self.nav.p.copy() if self.path is None else self.path[-1]), np.zeros(3)
        seg = np.diff(self.path, axis=0)
        lengths = np.linalg.norm(seg, axis=1)
        ends = np.cumsum(lengths)
        s = min(self.s, ends[-1])
        k = min(int(np.searchsorted(ends, s, side="right")), len(seg) - 1)
        start = ends[k] - lengths[k]
        f = (s - start) / lengths[k] if lengths[k] > 0 else 1.0
        point = self.path[k] + f * seg[k]
        left = ends[-1] - s
        velocity = seg[k] / max(lengths[k], 1e-9) * speed * min(1.0, left / 0.5)
        return point, velocity

    def path_length(self):
        return 0.0 if self.path is None else float(np.linalg.norm(np.diff(self.path, axis=0), axis=1).sum())


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


class Explorer:
    """The loop. run() returns the record (dict) that report.write() turns into the outputs."""

    def __init__(self, out, world_file, options=None, budget=None, plan_options=None, seed=0, visibility=None):
        self.out = os.path.abspath(out)
        self.world_file = os.path.abspath(world_file)
        self.o = options or ExploreOptions()
        self.o.check()
        self.budget = budget or Budget()
        self.budget.check()
        self.po = plan_options or PlanOptions()
        self.po.check()
        self.seed = seed
        self.visibility = visibility
        self.events = []
        self.timeline = []
        self.snapshots = []

    def event(self, t, robot, kind, detail=""):
        self.events.append({"t": round(t, 2), "robot": robot, "kind": kind, "detail": detail})
        print(f"[{t:7.1f} s] {robot}: {kind} {detail}", flush=True)

    def run(self):
        from unexmin.scripting.launcher import WorldProcess
        from unexmin.scripting.simulation import Simulation
        from unexmin.worlds.schema import read_world

        world_cfg = read_world(self.world_file)
        water = world_cfg.get("water") or {}
        self.surface_z = float(water.get("surface_z", 0.0))
        density, gravity = float(water.get("density", 1000.0)), float(world_cfg.get("gravity", 9.81))
        log_dir = os.path.join(self.out, "logs")
        os.makedirs(log_dir, exist_ok=True)
        os.makedirs(os.path.join(self.out, "snapshots"), exist_ok=True)
        self.map_path = os.path.join(self.out, "explore_map.bt")
        self.live_path = os.path.join(self.out, "live_map.bt")
        for stale in (self.map_path, self.live_path):
            if os.path.exists(stale):
                os.remove(stale)
        extra = [
            "mapping:=true",
            f"map_resolution:={self.o.resolution}",
            f"world_file:={self.world_file}",
            "sensors:=imu,dvl,pressure,m3,sls",
        ]
        if self.visibility:
            extra.append(f"visibility:={self.visibility}")
        wall0 = time.monotonic()
        world = WorldProcess(
            world="mine",
            robots=self.o.robots,
            seed=self.seed,
            realtime=False,
            paused=True,
            log_dir=log_dir,
            extra_args=extra,
        )
        sim = None
        self.stats = {}
        stats_sub = None
        try:
            sim = Simulation(timeout=120.0, world=world, node_name="unexmin_explore")
            import rospy

            from unexmin.msg import MapperStats
            from unexmin.srv import SaveMap

            stats_sub = rospy.Subscriber(
                "/mapper/stats", MapperStats, lambda m: self.stats.update(last=m), queue_size=10
            )
            rospy.wait_for_service("/mapper/save_map", 60.0)
            self.save_map = rospy.ServiceProxy("/mapper/save_map", SaveMap)
            self.sim = sim
            self._setup(sim, density, gravity)
            stepping0 = time.monotonic()
            self._loop(sim)
            self.stepping_wall = time.monotonic() - stepping0
            self.sim_time = sim.time
            for a in self.agents:
                a.handle.thrusts([0.0] * a.handle.thruster_count)
            sim.run_for(1.0)
            self._save(self.map_path)
        finally:
            if stats_sub is not None:
                stats_sub.unregister()
            (world if sim is None else sim).close(30.0)  # the Simulation closes the world it owns
        self.mission_wall = time.monotonic() - wall0
        return self

    # -- set-up ---------------------------------------------------------------------------------------
    def _setup(self, sim, density, gravity):
        import rospy

        from unexmin.control.allocation import ThrusterAllocator
        from unexmin.explore.truth import Truth
        from unexmin.worlds.files import world_triangles

        self.allocator = ThrusterAllocator()
        names = list(sim.robots[: self.o.robots])
        handles = [sim.robot(n, streams=STREAMS) for n in names]
        imus = [h.collect("imu") for h in handles]
        sim.step(1)
        self.agents = []
        for name, h, imu in zip(names, handles, imus):
            odom = h.odom()
            p, q = odom.pose.pose.position, odom.pose.pose.orientation
            start = np.array([p.x, p.y, p.z])
            R = _quat_matrix(q)
            desc = rospy.get_param(f"/{name}/robot_description")
            dvl_R, dvl_r = sensor_joint(desc, f"{name}/dvl_link")
            nav = DeadReckoning(start, R, sim.time, dvl_R, dvl_r, density, gravity)
            a = Agent(name, h, imu, nav, start.copy(), last_true=start.copy())
            a.yaw_ref = nav.yaw
            self.agents.append(a)
        tris = world_triangles(self.world_file)
        box = (tris.reshape(-1, 3).min(axis=0), tris.reshape(-1, 3).max(axis=0))
        if self.o.bounds is None:
            lo, hi = default_bounds(self.agents[0].home, box, self.surface_z)
            for a in self.agents[1:]:
                lo2, hi2 = default_bounds(a.home, box, self.surface_z)
                lo, hi = np.minimum(lo, lo2), np.maximum(hi, hi2)
        else:
            lo, hi = (np.asarray(b, float) for b in self.o.bounds)
        for a in self.agents:
            if np.any(a.home < lo) or np.any(a.home > hi):
                raise ValueError(f"explore bounds {lo} .. {hi}: {a.name}'s start {a.home} is outside")
        self.lo, self.hi = lo, hi
        self.grid = empty_grid(lo, hi, self.o.resolution, self.o.cell_voxels)
        self.truth = Truth(self.world_file, lo, hi)
        self.reachable = self.truth.reachable(
            self.grid, self.agents[0].home, self.po.hull_radius, self.surface_z, self.po.surface_margin
        )
        self.reachable_m3 = float(self.reachable.sum()) * self.grid.cell**3
        self.sonar_points = []  # [m] obstacles the M3 guard saw, marked occupied in every plan
        self.avoid = []  # goals given up
        print(
            f"exploring {lo.round(1).tolist()} .. {hi.round(1).tolist()} m with {', '.join(names)}; reachable "
            f"volume {self.reachable_m3:.0f} m3 (grid {self.grid.shape}, cell {self.grid.cell:g} m)",
            flush=True,
        )

    # -- map ------------------------------------------------------------------------------------------
    def _caught_up(self, timeout=60.0):
        from unexmin.scripting.launcher import wait_for

        expected = int(round(self.sim.time * 40.0)) + int(round(self.sim.time * 10.0)) * SLS_UNITS
        expected *= len(self.agents)
        slack = 5 * (1 + SLS_UNITS) * len(self.agents)

        def done():
            m = self.stats.get("last")
            return (
                m is not None
                and m.clouds_inserted + m.clouds_dropped >= m.clouds_received
                and m.pending == 0
                and m.clouds_received >= expected - slack
            )

        try:
            wait_for(done, timeout, "the mapper to insert every cloud")
        except TimeoutError as e:
            self.event(self.sim.time, "mapper", "lagging", str(e))

    def _save(self, path):
        self._caught_up()
        res = self.save_map(path=path, robot="")
        if not res.success:
            raise RuntimeError(f"/mapper/save_map {path} failed: {res.message}")

    def _read_map(self):
        self._save(self.live_path)
        res, keys, sizes, occupied = read_leaves(self.live_path)
        if abs(res - self.o.resolution) > 1e-9:
            raise RuntimeError(f"the mapper's resolution is {res} m, expected {self.o.resolution} m")
        grid_from_leaves(self.grid, res, keys, sizes, occupied, self.o.cell_voxels)
        for a in self.agents:
            # where a robot is, is water: its own cell is not mapped at the start, and its teammates' sensors map
            # its hull as occupied
            near = ball_mask(self.grid, a.nav.p, 0.7)
            self.grid.states[near & (self.grid.states != FREE)] = FREE
        if self.sonar_points:
            idx = self.grid.index(np.array(self.sonar_points))
            idx = idx[self.grid.inside(idx)]
            self.grid.states[tuple(idx.T)] = OCCUPIED

    # -- the loop -------------------------------------------------------------------------------------
    def _loop(self, sim):
        o = self.o
        steps = max(1, round(o.control_dt * sim.physics_rate))
        next_map, next_snap, next_row = o.map_period, o.snapshot if o.snapshot > 0 else math.inf, 0.0
        hard_stop = self.budget.time_s + o.grace_s
        while True:
            t = sim.time
            if t >= next_map:
                self._read_map()
                self._replan(t)
                self._record(t)
                self._progress(t)
                next_map += o.map_period
            if t >= next_snap:
                path = os.path.join(self.out, "snapshots", f"map_{t:07.1f}.bt")
                self._save(path)
                self.snapshots.append((t, path))
                next_snap += o.snapshot
            if all(a.mode == "home" for a in self.agents):
                break
            if t >= hard_stop:
                for a in self.agents:
                    if a.mode != "home":
                        self.event(t, a.name, "not_home", f"{np.linalg.norm(a.nav.p - a.home):.1f} m from the start")
                break
            for a in self.agents:
                self._control(a, t, o.control_dt)
            sim.step(steps)
            for a in self.agents:
                self._sense(a, sim)
            if sim.time >= next_row:
                self._track_truth(sim.time, rows=True)
                next_row += 1.0
            else:
                self._track_truth(sim.time, rows=False)
        self._record(sim.time)

    def _sense(self, a, sim):
        msgs = a.imu.messages
        a.imu.clear()
        a.nav.rates(
            [
                (m.header.stamp.to_sec(), (m.angular_velocity.x, m.angular_velocity.y, m.angular_velocity.z))
                for m in msgs
            ]
        )
        try:
            dvl = a.handle.latest("dvl")
            if dvl.header.stamp.to_sec() > a.last_dvl:
                a.last_dvl = dvl.header.stamp.to_sec()
                was = a.nav.locked
                a.nav.dvl(dvl.bottom_lock, (dvl.velocity.x, dvl.velocity.y, dvl.velocity.z))
                if was and not a.nav.locked:
                    self.event(sim.time, a.name, "dvl_lock_lost", "coasting on the last velocity")
            a.nav.pressure(a.handle.latest("pressure").fluid_pressure)
        except LookupError:
            pass  # before the DVL's first ping (t < 1/8 s)

    def _control(self, a, t, dt):
        o = self.o
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
            self.sonar_points.append(point)
            self.event(t, a.name, "sonar_stop", f"echo {np.linalg.norm(echo):.2f} m ahead at {point.round(2).tolist()}")
            if a.goal is not None:
                self.avoid.append(a.goal)
            a.path, a.goal, a.hold = None, None, a.nav.p.copy()
            ref, vel = a.hold, np.zeros(3)
        from unexmin.missions.survey import track

        pose, twist = _pose_msgs(a, v_body, a.nav.omega[2])
        wrench, dist, _ = track(pose, twist, np.array([*ref, a.yaw_ref]), np.array([*vel, o.yaw_rate]), o.speed + 0.1)
        thrusts, scale = self.allocator.allocate(wrench)
        a.handle.thrusts(thrusts)
        a.energy += power([scale * f for f in wrench[:3]], v_body, scale * wrench[5], a.nav.omega[2]) * dt
        if a.path is not None and dist < o.hold_distance:
            a.s += o.speed * dt
        if a.path is not None:
            if a.s - a.progress_mark[1] >= o.stuck_m:
                a.progress_mark = (t, a.s)
            elif t - a.progress_mark[0] > o.stuck_s:
                self.event(t, a.name, "stuck", f"{dist:.2f} m from its reference for {o.stuck_s:.0f} s")
                if a.goal is not None:
                    self.avoid.append(a.goal)
                a.path, a.goal, a.hold = None, None, a.nav.p.copy()
            elif a.s >= a.path_length() and dist < o.goal_tolerance:
                if a.mode == "explore":
                    self.avoid.append(a.goal)
                    a.path, a.goal, a.hold = None, None, a.nav.p.copy()
                elif a.mode == "return" and np.linalg.norm(a.nav.p - a.home) < max(o.home_tolerance, 0.3):
                    a.mode = "home"
                    self.event(t, a.name, "home", f"{a.why}; estimated {np.linalg.norm(a.nav.p - a.home):.2f} m off")

    def _track_truth(self, t, rows):
        for a in self.agents:
            p = a.handle.odom().pose.pose.position
            true = np.array([p.x, p.y, p.z])
            a.flown += float(np.linalg.norm(true - a.last_true))
            a.travelled_est += float(np.linalg.norm(a.nav.v_body)) * self.o.control_dt
            a.last_true = true
            clearance = float(self.truth.clearance(true)[0])
            touching = clearance < self.po.hull_radius + 0.02
            if touching and not a.touching:
                self.event(t, a.name, "contact", f"clearance {clearance:.3f} m at {true.round(2).tolist()}")
            a.touching = touching
            a.min_clearance = min(a.min_clearance, clearance)
            if rows:
                a.rows.append(
                    {
                        "t": round(t, 2),
                        "true": true.round(3).tolist(),
                        "estimate": a.nav.p.round(3).tolist(),
                        "drift_m": round(float(np.linalg.norm(true - a.nav.p)), 3),
                        "flown_m": round(a.flown, 2),
                        "energy_j": round(a.energy, 1),
                        "clearance_m": round(clearance, 3),
                        "mode": a.mode,
                        "dvl_lock": a.nav.locked,
                    }
                )

    def _progress(self, t):
        r = self.timeline[-1]
        robots = "  ".join(
            f"{a.name} {a.mode} at {np.round(a.nav.p, 1).tolist()}"
            + (f" -> {np.round(a.goal, 1).tolist()}" if a.goal is not None else "")
            for a in self.agents
        )
        print(
            f"[{t:7.1f} s] explored {r['explored_reachable_m3']:.0f} m3 ({100 * r['coverage']:.0f} %)  {robots}",
            flush=True,
        )

    def _record(self, t):
        known = self.grid.states != 0
        self.timeline.append(
            {
                "t": round(t, 2),
                "explored_m3": round(self.grid.known_volume(), 2),
                "explored_reachable_m3": round(float((known & self.reachable).sum()) * self.grid.cell**3, 2),
                "coverage": round(float((known & self.reachable).sum()) / max(1, int(self.reachable.sum())), 4),
            }
        )

    # -- planning -------------------------------------------------------------------------------------
    def _replan(self, t):
        o, po = self.o, self.po
        spheres = [(a.nav.p, 0.7) for a in self.agents]
        base = traversable(self.grid, po, self.surface_z, spheres)
        front = frontiers(self.grid, self.surface_z, po)
        gain = gain_map(self.grid, po)
        searches, graphs = {}, {}
        for a in self.agents:
            if a.mode == "home":
                continue
            mask = base.copy()
            for b in self.agents:  # the other robots are obstacles
                if b is not a:
                    mask &= ~ball_mask(self.grid, b.nav.p, o.robot_clearance)
            g = Graph(self.grid, mask)
            node = g.nearest_node(a.nav.p, 1.0)
            if node < 0:
                self.event(t, a.name, "no_free_cell", f"no traversable cell within 1 m of {a.nav.p.round(2).tolist()}")
                continue
            graphs[a.name] = g
            searches[a.name] = g.distances(node)
        joules_per_m = max([a.energy / a.travelled_est for a in self.agents if a.travelled_est > 5.0] + [20.0])
        for a in self.agents:
            if a.name not in searches:
                continue
            home = path_to(graphs[a.name], searches[a.name], a.home)
            a.home_m = home[1] if home else float(np.linalg.norm(a.nav.p - a.home)) * 1.5
            if a.mode == "explore":
                go, why = self.budget.must_return(t, a.energy, a.home_m, o.speed, joules_per_m)
                if go:
                    self._go_home(a, t, home, "budget " + why)
        exploring = {n: s for n, s in searches.items() if self._agent(n).mode == "explore"}
        goals = {}
        for name in exploring:
            busy = [b.goal for b in self.agents if b.name != name and b.goal is not None and b.mode == "explore"]
            busy += [goal for goal, _, _ in goals.values()]
            chosen = choose_goals(graphs[name], self.grid, front, gain, {name: exploring[name]}, busy, po, self.avoid)
            goals.update(chosen)
            a = self._agent(name)
            if name in chosen:
                goal, path, _ = chosen[name]
                a.goal, a.idle = goal, 0
                a.set_path(path, t)
            elif a.idle + 1 < o.idle_replans or self._crowded(a):
                # turning where it is, its sensors may yet open a way on; a teammate near it may be in its way
                a.idle += 0 if self._crowded(a) else 1
                a.path, a.goal = None, None
            else:
                home = path_to(graphs[name], searches[name], a.home)
                self._go_home(a, t, home, "explored: no frontier left within reach")
        for a in self.agents:
            if a.mode == "return" and a.name in searches:
                home = path_to(graphs[a.name], searches[a.name], a.home)
                if home is not None:
                    a.set_path(home[0], t)

    def _crowded(self, a):
        """True when another robot still out is within 3 m of `a` (it may block a's way, not the frontiers')."""
        return any(b is not a and b.mode != "home" and np.linalg.norm(b.nav.p - a.nav.p) < 3.0 for b in self.agents)

    def _go_home(self, a, t, home, why):
        a.mode, a.why, a.goal = "return", why, None
        if home is not None:
            a.set_path(home[0], t)
        else:
            a.set_path([a.home], t)
            self.event(t, a.name, "no_path_home", "flying straight to the start")
        self.event(t, a.name, "return", why)

    def _agent(self, name):
        return next(a for a in self.agents if a.name == name)


def _quat_matrix(q):
    x, y, z, w = q.x, q.y, q.z, q.w
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )

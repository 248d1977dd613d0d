"""The explorer's loop (docs/explore.md): the world in lockstep with the mapper on, one to three robots flying to
frontiers of the live map on their dead-reckoned poses, back to the start when the budget runs low.

Ground truth (the simulator's odometry and the world's mesh) is read only to score: drift, distance flown,
clearance to the rock (a contact is reported), explored share of the reachable volume.

The loop's parts: options.py (what it is told), agent.py (one robot's state and path), navigation.py (the dead
reckoning), live_map.py (the mapper's map into the grid), replan.py (the team's goals), control.py (each robot's
control step), scoring.py (the ground truth and the timeline).
"""

import math
import os
import time

import numpy as np

from unexmin.missions.explore import live_map
from unexmin.missions.explore.agent import Agent
from unexmin.missions.explore.budget import Budget
from unexmin.missions.explore.control import control, sense
from unexmin.missions.explore.grid import empty_grid
from unexmin.missions.explore.navigation import DeadReckoning, quat_matrix, sensor_joint
from unexmin.missions.explore.options import ExploreOptions, default_bounds
from unexmin.missions.explore.plan import PlanOptions
from unexmin.missions.explore.replan import replan
from unexmin.missions.explore.scoring import print_progress, record_coverage, track_truth

STREAMS = ["imu", "dvl", "pressure", "m3/scan"]


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
        from unexmin.scripting.ros_backend import RosSimulation
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
            sim = RosSimulation(timeout=120.0, world=world, node_name="unexmin_explore")
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
            live_map.save(self, self.map_path)
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
        from unexmin.missions.explore.truth import Truth
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
            R = quat_matrix(q)
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

    # -- the loop -------------------------------------------------------------------------------------
    def _loop(self, sim):
        o = self.o
        steps = max(1, round(o.control_dt * sim.physics_rate))
        next_map, next_snap, next_row = o.map_period, o.snapshot if o.snapshot > 0 else math.inf, 0.0
        hard_stop = self.budget.time_s + o.grace_s
        while True:
            t = sim.time
            if t >= next_map:
                live_map.read(self)
                replan(self, t)
                record_coverage(self, t)
                print_progress(self, t)
                next_map += o.map_period
            if t >= next_snap:
                path = os.path.join(self.out, "snapshots", f"map_{t:07.1f}.bt")
                live_map.save(self, path)
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
                control(self, a, t, o.control_dt)
            sim.step(steps)
            for a in self.agents:
                sense(self, a, sim)
            if sim.time >= next_row:
                track_truth(self, sim.time, rows=True)
                next_row += 1.0
            else:
                track_truth(self, sim.time, rows=False)
        record_coverage(self, sim.time)

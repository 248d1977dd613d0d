"""The mine mission's runner: the plan (plan.py) flown in lockstep. The mine world starts paused with the mapper
on, a bag is recorded (odometry, M3 scans, SLS clouds, the mapper's stats), UX_1 tracks the plan's reference on
ground-truth odometry (survey.track, thesis allocation eq. 5.12; the reference waits for the robot when it lags),
the mapper saves its map every `snapshot_every` s of sim time, and at the end the world gets SIGINT (the mapper
saves mine_map.bt). run() returns the flight record that scoring.py scores."""

import os
import subprocess
import time
from dataclasses import dataclass, field

import numpy as np

from unexmin.control.allocation import ThrusterAllocator
from unexmin.missions.common import recorder_connected, wait_until_written
from unexmin.missions.survey import track
from unexmin.scripting.launcher import WorldProcess, stop_process_group, wait_for

ROBOT = "UX_1"
CONTROL_DT = 0.1  # [s] sim time between controller updates
SLS_UNITS = 4
# [m] the M3's points farther than this are not marked occupied (the mapper's m3_max_range): beyond it the fan's
# 3-degree beam meets the walls at grazing incidence and a share of its echoes land beside them (docs/mapping.md)
M3_MAX_RANGE = 7.0


def topics():
    return [f"/{ROBOT}/odom", f"/{ROBOT}/m3/scan", "/mapper/stats"] + [
        f"/{ROBOT}/sls_{i}/points" for i in range(SLS_UNITS)
    ]


def clouds_published(sim_time):
    """The clouds the simulator publishes in sim_time [s]: the M3 at 40 Hz, each SLS unit at 10 Hz."""
    return int(round(sim_time * 40.0)) + int(round(sim_time * 10.0)) * SLS_UNITS


@dataclass
class MissionFiles:
    """The mission's output folder and the files the runner writes there."""

    out: str

    def __post_init__(self):
        self.out = os.path.abspath(self.out)
        self.log_dir = os.path.join(self.out, "logs")
        self.snap_dir = os.path.join(self.out, "snapshots")
        self.bag = os.path.join(self.out, "mine_mission.bag")
        self.map_path = os.path.join(self.out, "mine_map.bt")

    def prepare(self):
        """Makes the folders and removes what an earlier run left (the bag, the map, the snapshots)."""
        os.makedirs(self.log_dir, exist_ok=True)
        os.makedirs(self.snap_dir, exist_ok=True)
        stale = [self.bag, self.map_path] + [os.path.join(self.snap_dir, f) for f in os.listdir(self.snap_dir)]
        for path in stale:
            if os.path.exists(path):
                os.remove(path)


@dataclass
class Flight:
    """What the runner did: the record scoring.py reads. Times [s]."""

    files: MissionFiles
    seed: int
    resolution: float  # [m] the map's voxel edge
    started: float  # time.monotonic() when the world was launched
    sim_time: float = 0.0  # sim time at the end
    stepping_wall: float = 0.0  # wall time of the stepping
    mission_wall: float = 0.0  # wall time from the launch to the world's end
    progress: float = 0.0  # how far along the plan's reference the robot got
    held: float = 0.0  # sim time the reference waited for the robot
    clouds_expected: int = 0  # clouds the simulator published
    final: object = None  # the mapper's last stats (unexmin/MapperStats)
    legs: list = field(default_factory=list)  # {frame, t, held_s} every 40 frames of the plan
    snapshots: list = field(default_factory=list)  # (sim time, map file) of each saved map


class MineRunner:
    """Flies a MinePlan (plan.py); run() returns the Flight."""

    def __init__(self, plan, out, seed=0, resolution=0.1, snapshot_every=90.0):
        self.plan = plan
        self.files = MissionFiles(out)
        self.seed = seed
        self.resolution = resolution
        self.snapshot_every = snapshot_every

    def run(self):
        self.files.prepare()
        extra = self._launch_args()
        started = time.monotonic()
        log_dir = self.files.log_dir
        world = WorldProcess(
            world="mine", robots=1, seed=self.seed, realtime=False, paused=True, log_dir=log_dir, extra_args=extra
        )
        self.flight = Flight(self.files, self.seed, self.resolution, started)
        self.recorder = self.log = self.sim = self.stats_sub = None
        self.stats = {}
        try:
            self._start(world)
            self._fly()
            self._land()
        finally:
            self._stop(world)
        self.flight.mission_wall = time.monotonic() - self.flight.started
        if not os.path.exists(self.files.map_path):
            raise RuntimeError(f"the mapper did not save {self.files.map_path}: see {self.files.log_dir}")
        return self.flight

    def _launch_args(self):
        extra = [
            "mapping:=true",
            f"map_file:={self.files.map_path}",
            f"map_resolution:={self.resolution}",
            f"map_m3_max_range:={M3_MAX_RANGE}",
            f"world_file:={self.plan.world_file}",
        ]
        if self.plan.visibility:
            extra.append(f"visibility:={self.plan.visibility}")
        return extra

    def _start(self, world):
        """The simulation, the mapper's stats and save_map service, the recorder connected; one step taken."""
        from unexmin.scripting.ros_backend import RosSimulation

        self.sim = sim = RosSimulation(timeout=120.0, world=world, node_name="unexmin_mine_mission")
        import rosgraph
        import rospy

        from unexmin.msg import MapperStats
        from unexmin.srv import SaveMap

        stats = self.stats
        self.stats_sub = rospy.Subscriber("/mapper/stats", MapperStats, lambda m: stats.update(last=m), queue_size=10)
        wait_for(lambda: "last" in stats, 120.0, "the mapper's /mapper/stats")
        rospy.wait_for_service("/mapper/save_map", 60.0)
        self.save_map = rospy.ServiceProxy("/mapper/save_map", SaveMap)
        self.ux = sim.robot(ROBOT)
        self.log = open(os.path.join(self.files.log_dir, "rosbag_record.log"), "w")
        self.recorder = subprocess.Popen(
            ["rosbag", "record", "--tcpnodelay", "-O", self.files.bag, *topics()],
            stdout=self.log,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
        master = rosgraph.Master(rospy.get_name())
        wait_for(
            lambda: recorder_connected(master, ("/simulator",), [f"/{ROBOT}/odom", f"/{ROBOT}/m3/scan"]),
            30.0,
            "rosbag record to connect",
        )
        self.allocator = ThrusterAllocator()
        sim.step(1)
        self.steps = max(1, round(CONTROL_DT * sim.physics_rate))

    def _fly(self):
        """The plan's reference tracked until it is done or the time limit passes; a row printed every 40 frames,
        a map saved every snapshot_every s."""
        sim, ux, reference, f = self.sim, self.ux, self.plan.reference, self.flight
        self.stepping_wall0 = time.monotonic()
        print(f"{'leg':<10}{'t [s]':>8}{'x [m]':>9}{'y [m]':>9}{'z [m]':>9}{'clouds':>9}{'occupied':>10}{'lag [s]':>9}")
        next_frame, next_snapshot, pendulum = 1, self.snapshot_every, 0.0
        while f.progress < reference.duration and sim.time <= self.plan.time_limit:
            odom = ux.odom()
            ref, rate = reference(f.progress)
            wrench, dist, yaw_err = track(odom.pose.pose, odom.twist.twist, ref, rate)
            ux.thrusts(self.allocator.allocate(wrench)[0])
            if ref[4] != pendulum:
                pendulum = float(ref[4])
                ux.pendulum(pendulum)
            sim.step(self.steps)
            # the reference waits for the robot when it lags (a pull, not a chase)
            if dist < 0.6 and abs(yaw_err) < 0.6:
                f.progress += self.steps / sim.physics_rate
            else:
                f.held += self.steps / sim.physics_rate
            if next_frame < len(reference.t) and f.progress >= reference.t[next_frame]:
                next_frame = int(np.searchsorted(reference.t, f.progress, side="right"))
                if next_frame % 40 == 0 or next_frame >= len(reference.t):
                    self._print_leg(next_frame - 1)
            if sim.time >= next_snapshot:
                self._snapshot()
                next_snapshot += self.snapshot_every
        if sim.time > self.plan.time_limit:
            print(f"time limit {self.plan.time_limit:.0f} s of sim time reached")

    def _print_leg(self, frame):
        f, p, m = self.flight, self.ux.odom().pose.pose.position, self.stats["last"]
        f.legs.append({"frame": frame, "t": self.sim.time, "held_s": round(f.held, 1)})
        print(
            f"{frame:<10}{self.sim.time:8.1f}{p.x:9.2f}{p.y:9.2f}{p.z:9.2f}{m.clouds_inserted:9d}"
            f"{m.occupied_leaves:10d}{f.held:9.1f}",
            flush=True,
        )

    def _mapper_caught_up(self, timeout):
        """Waits until the mapper has taken in every cloud published so far; returns their count."""
        expected = clouds_published(self.sim.time)
        stats = self.stats
        wait_for(
            lambda: stats["last"].clouds_inserted + stats["last"].clouds_dropped >= stats["last"].clouds_received
            and stats["last"].pending == 0
            and stats["last"].clouds_received >= expected - 5 * (1 + SLS_UNITS),
            timeout,
            "the mapper to insert every cloud",
        )
        return expected

    def _snapshot(self):
        try:
            self._mapper_caught_up(60.0)
        except TimeoutError as e:
            print(f"warning: {e}")
        path = os.path.join(self.files.snap_dir, f"map_{self.sim.time:07.1f}.bt")
        if self.save_map(path=path, robot="").success:
            self.flight.snapshots.append((self.sim.time, path))

    def _land(self):
        """Thrusters and pendulum to zero, a last second run, the mapper caught up, the bag written."""
        sim, ux, f = self.sim, self.ux, self.flight
        ux.thrusts([0.0] * 8)
        ux.pendulum(0.0)
        sim.run_for(1.0)  # the clouds of the last step find their tf
        f.sim_time, f.stepping_wall = sim.time, time.monotonic() - self.stepping_wall0
        # Every cloud the simulator published reached the map: M3 at 40 Hz, each SLS unit at 10 Hz.
        try:
            f.clouds_expected = self._mapper_caught_up(60.0)
        except TimeoutError as e:
            f.clouds_expected = clouds_published(f.sim_time)
            print(f"warning: {e}")
        f.final = self.stats["last"]
        wait_until_written(self.files.bag + ".active")

    def _stop(self, world):
        if self.recorder is not None:
            stop_process_group(self.recorder, 20.0)
            self.log.close()
        if self.stats_sub is not None:
            self.stats_sub.unregister()
        # This script's topics go first, while the master is up (no "unable to communicate" at exit), then the
        # world gets SIGINT: the mapper saves mine_map.bt.
        if self.sim is not None:
            self.sim.close(30.0)
        else:
            world.close(30.0)

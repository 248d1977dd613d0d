"""The scripting API over the engine in-process (`Simulation.launch(..., backend="core")`, docs/python_api.md).

No ROS master, no nodes, no messages on the wire: the world is a unexmin.core.World of this process. The calls
are the ROS back end's (python/unexmin/scripting/api.py). What differs:

- latest()/collect() give the engine's sample dicts (keys per family in docs/python_api.md, "unexmin.core"),
  named by sensor (`imu`, `dvl`, `pressure`, `m3`, `msis`, `sls_*`, `camera_*`) or by the ROS topic that carries
  the sensor (`kvh/imu_raw`, `m3/scan`, ...: the topic's first name that is a sensor). Each sample dict's
  `time` is its stamp [s].
- A collector gets every sample: while one is active, step() advances one physics step at a time and reads
  the collected sensors after each (a sensor samples at most once per physics step); with none, step(n) is one
  call into the engine.
- wrench() is allocated in this process by the thesis allocation (unexmin.control.allocation) and applied
  from the next step, as thrusts() (the ROS back end's allocator node answers asynchronously).
- odom() is a nav_msgs/Odometry built from the engine's state, the same numbers as the simulator's
  (test/pytest/test_scripting_backends.py).
"""

from unexmin.scripting.api import RobotApi, SimulationApi, check_launch_arguments, finite

#: ROS topic under /<robot>/ -> the sensor that publishes it, where the topic's first name is not the sensor's.
TOPIC_SENSORS = {"kvh/imu_raw": "imu", "kvh/imu": "imu"}


class CoreCollector:
    """Every sample of one sensor from its creation until stop(), oldest first (see the module's doc)."""

    def __init__(self, robot, sensor, topic):
        self._robot, self.sensor, self.topic = robot, sensor, topic
        self._samples = []
        self.active = True

    @property
    def messages(self):
        """The samples collected so far (a copy of the list), oldest first."""
        return list(self._samples)

    def stamps(self):
        """Sample times [s] of the samples collected so far."""
        return [s["time"] for s in self._samples]

    def __len__(self):
        return len(self._samples)

    def clear(self):
        """Forget the samples collected so far; keep collecting."""
        self._samples.clear()

    def stop(self):
        """Stop collecting (the samples stay readable)."""
        if self in self._robot._collectors:
            self._robot._collectors.remove(self)
        self.active = False

    def wait_count(self, n, timeout=30.0):
        """Every sample collected, once there are at least n: in-process, nothing arrives later, so fewer is a
        TimeoutError at once (step further first)."""
        if len(self._samples) < n:
            raise TimeoutError(f"{self.topic}: {len(self._samples)} samples collected, not {n} (step further)")
        return self.messages

    def wait_until(self, stamp, timeout=30.0):
        """Every sample collected, once one stamped >= stamp [s] is among them (TimeoutError at once otherwise)."""
        if not self._samples or self._samples[-1]["time"] < stamp - 1e-9:
            raise TimeoutError(f"{self.topic}: no sample stamped {stamp} s collected yet (step further)")
        return self.messages

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()
        return False


class CoreRobot(RobotApi):
    """One robot of a CoreSimulation (made by CoreSimulation.robot())."""

    def __init__(self, sim, name):
        self.sim = sim
        self.name = name
        self._robot = sim.world.robot(name)
        self.thruster_count = self._robot.thruster_count
        self._collectors = []
        self._allocator = None
        self._base_link = self._robot.base_link

    # -- commands -----------------------------------------------------------------------------------
    def thrusts(self, values):
        """Command every thruster (each thruster's command unit, [N] by default), from the next step."""
        values = list(values)
        if len(values) != self.thruster_count:
            raise ValueError(f"thrusts needs {self.thruster_count} values for {self.name}, got {len(values)}")
        self._robot.thrusts([finite(f"thrust[{i}]", v) for i, v in enumerate(values)])

    def pendulum(self, angle):
        """Pendulum target angle [rad]."""
        self._robot.pendulum(finite("pendulum", angle))

    def vbs(self, mass):
        """Ballast mass [kg]."""
        self._robot.vbs(finite("vbs", mass))

    def wrench(self, X=0.0, Y=0.0, Z=0.0, K=0.0, M=0.0, N=0.0):
        """Desired body wrench [N, N m], allocated here by the thesis allocation (eq. 5.12, saturated as the
        allocator node does) and applied from the next step."""
        from unexmin.control.allocation import ThrusterAllocator

        wrench = [finite(n, v) for n, v in (("X", X), ("Y", Y), ("Z", Z), ("K", K), ("M", M), ("N", N))]
        if self._allocator is None:
            self._allocator = ThrusterAllocator()
        if self._allocator.thrusters != self.thruster_count:
            raise ValueError(
                f"wrench: the thesis allocation drives {self._allocator.thrusters} thrusters, {self.name} has "
                f"{self.thruster_count}: command its thrusts() instead"
            )
        self._robot.thrusts(self._allocator.allocate(wrench)[0])

    # -- state and sensors --------------------------------------------------------------------------
    def state(self):
        """Ground truth as a dict of numpy arrays (unexmin.core.Robot.state())."""
        return self._robot.state()

    def odom(self):
        """Ground truth as nav_msgs/Odometry (frame `world`, child the base link; twist in the body frame), as
        the simulator's /<robot>/odom at sim.time. The one call of this back end that needs a ROS package: the
        message classes of nav_msgs (and genpy under them), no rospy; state() gives the same numbers without."""
        try:
            import genpy
            from nav_msgs.msg import Odometry
        except ImportError as e:
            raise ImportError(
                f"odom() builds a nav_msgs/Odometry and needs the nav_msgs message package ({e}): use state() for "
                "the same ground truth as numpy arrays"
            ) from e

        s = self._robot.state()
        o = Odometry()
        o.header.stamp = genpy.Time.from_sec(s["time"])
        o.header.frame_id = "world"
        o.child_frame_id = self._base_link
        p, q = o.pose.pose.position, o.pose.pose.orientation
        p.x, p.y, p.z = (float(v) for v in s["position"])
        q.x, q.y, q.z, q.w = (float(v) for v in s["orientation"])
        v, w = o.twist.twist.linear, o.twist.twist.angular
        v.x, v.y, v.z = (float(x) for x in s["linear_velocity"])
        w.x, w.y, w.z = (float(x) for x in s["angular_velocity"])
        return o

    @property
    def sensors(self):
        """{sensor name: family} of the sensors that run."""
        return self._robot.sensors

    @property
    def topics(self):
        """{sensor name: family} (the core back end's streams are its sensors)."""
        return self._robot.sensors

    def _sensor(self, topic, msg_class, caller):
        if msg_class is not None:
            raise TypeError(f"{caller}('{topic}', {msg_class!r}): the core back end gives sample dicts, not messages")
        name = topic[len(f"/{self.name}/") :] if topic.startswith(f"/{self.name}/") else topic
        sensors = self._robot.sensors
        if name in TOPIC_SENSORS:
            name = TOPIC_SENSORS[name]
        elif name not in sensors and name.split("/")[0] in sensors:
            name = name.split("/")[0]
        if name not in sensors:
            raise LookupError(
                f"{caller}('{topic}'): {self.name} has no running sensor of that name (sensors: "
                f"{', '.join(sorted(sensors)) or 'none'}; the world's sensors: {self.sim.world.sensors})"
            )
        return name

    def latest(self, topic, msg_class=None, min_stamp=None, timeout=None):
        """The newest sample of sensor (or topic) `topic` at or before sim.time, a dict; LookupError when the
        sensor has not sampled since the start or the reset, or none is stamped >= min_stamp [s]."""
        name = self._sensor(topic, msg_class, "latest")
        s = self._robot.sample(name)
        if s["time"] < 0 or (min_stamp is not None and s["time"] < min_stamp - 1e-9):
            wanted = f" stamped >= {min_stamp} s" if min_stamp is not None else ""
            raise LookupError(
                f"no sample{wanted} of {self.name}'s {name} up to sim time {self.sim.time:.6f} s (a sensor "
                "samples first at the first physics step at or after 1/rate)"
            )
        return s

    def collect(self, topic, msg_class=None):
        """A CoreCollector of every sample of sensor (or topic) `topic` from now on."""
        c = CoreCollector(self, self._sensor(topic, msg_class, "collect"), topic)
        c._count = self._robot.sample_count(c.sensor)
        self._collectors.append(c)
        return c

    def _poll(self):
        """After one physics step: the new sample of every collected sensor goes to its collectors."""
        for c in self._collectors:
            count = self._robot.sample_count(c.sensor)
            if count != c._count:
                c._count = count
                c._samples.append(self._robot.sample(c.sensor))


class CoreSimulation(SimulationApi):
    """The scripting API over unexmin.core.World (see the module's doc); made by Simulation.launch(backend="core")."""

    backend = "core"

    #: Launch arguments the core cannot honour, with why (a non-default value raises ValueError naming it).
    UNSUPPORTED = {
        "record": "the recorder writes ROS messages",
        "launch_file": "a launch file starts ROS nodes",
        "log_dir": "the core writes no node logs",
        "node_name": "the core runs no ROS node",
    }

    def __init__(self, world="tank", timeout=60.0, map_file="", **world_arguments):
        """world_arguments: those of unexmin.core.World (robots, seed, sensors, visibility, mode, overrides,
        descriptions, physics_rate, ray_caster_threads, vehicles, mapping); map_file: where close() saves the map
        ("" for nowhere); timeout [s] is kept for the ROS back end's sake."""
        from unexmin.core import World

        if map_file and not world_arguments.get("mapping"):
            raise ValueError(f"map_file = {map_file!r}: the map is only made with mapping=True")
        self.world = World(world, **world_arguments)
        self.map_file = map_file
        self.timeout = timeout
        self.physics_rate = 1.0 / self.world.dt
        self.robots = tuple(self.world.robots)
        self.free_running = False
        self._robots = {}
        self._closed = False

    @classmethod
    def launch(cls, world="tank", robots=1, seed=0, mode="operational", visibility="", sensors="all", **kwargs):
        """As Simulation.launch(backend="core"): ValueError naming an argument the core cannot honour."""
        mapping = kwargs.pop("mapping", False)
        map_file = kwargs.pop("map_file", "")
        record = kwargs.pop("record", "")
        sensors = check_launch_arguments(mode, visibility, sensors, mapping, map_file, kwargs.get("overrides"), record)
        given = {"record": record}
        for name in ("launch_file", "log_dir", "node_name"):
            given[name] = kwargs.pop(name, None)
        for name, value in given.items():
            if value:
                raise ValueError(
                    f"{name} = {value!r}: the core back end cannot honour it ({cls.UNSUPPORTED[name]}): "
                    'use backend="ros"'
                )
        if mapping:
            # The mapper as the launch files start it (launch/simulation.launch, launch/mapping.launch).
            vehicles = kwargs.get("vehicles")
            team = vehicles.split(",") if isinstance(vehicles, str) else list(vehicles or [])
            mapping = {"sonar_max_range": 8.0, "dvl": "remus100" in team}
        return cls(
            world,
            robots=robots,
            seed=seed,
            mode=mode,
            visibility=visibility,
            sensors=sensors,
            mapping=mapping,
            map_file=map_file,
            **kwargs,
        )

    @property
    def time(self):
        return self.world.time

    def robot(self, name, streams="all"):
        """Handle on robot `name` (KeyError naming the robots otherwise). `streams` is accepted for the ROS
        back end's sake: in-process every running sensor can be read at any time."""
        if isinstance(streams, str) and streams not in ("all", "none"):
            raise ValueError(f"streams must be 'all', 'none' or a list of topic names, got {streams!r}")
        if name not in self.robots:
            raise KeyError(f"no robot named '{name}' in the simulator (robots: {', '.join(self.robots)})")
        if name not in self._robots:
            self._robots[name] = CoreRobot(self, name)
        return self._robots[name]

    def step(self, n=1):
        """Advance exactly n physics steps (commands held, as the ROS back end's lockstep); returns sim.time [s]."""
        if isinstance(n, bool) or int(n) != n or n < 0:
            raise ValueError(f"step needs a non-negative whole number of steps, got {n!r}")
        polled = [r for r in self._robots.values() if r._collectors]
        if not polled:
            return self.world.step(int(n))
        for _ in range(int(n)):
            self.world.step(1)
            for r in polled:
                r._poll()
        return self.world.time

    def reset(self, seed=None):
        """Back to t = 0 (robots at spawn, actuators zero), a new seed if given; collectors keep their samples
        and go on collecting."""
        self.world.reset(seed)
        for r in self._robots.values():
            for c in r._collectors:
                c._count = 0

    def note_published(self, n):
        """Accepted for the ROS back end's sake: in-process, a command applies from the next step anyway."""
        int(n)

    def pause(self):
        """Nothing to do: the in-process world only moves when stepped."""

    def unpause(self):
        raise RuntimeError("unpause: the core back end has no free-running clock; step the world (step, run_for)")

    def close(self):
        """Release the world (idempotent)."""
        if not self._closed:
            self._closed = True
            if self.map_file:
                self.world.save_map(self.map_file)  # as the mapper node saves ~map_file at shutdown
            for r in self._robots.values():
                for c in list(r._collectors):
                    c.stop()
            self._robots.clear()
            self.world = None

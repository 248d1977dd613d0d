"""The scripting API over the ROS simulator (`Simulation.launch(..., backend="ros")` and `Simulation()`,
docs/python_api.md): the simulator's topics and /sim services, through this process's rospy node.

    from unexmin import Simulation
    with Simulation.launch("tank", robots=1, seed=3) as sim:   # or Simulation() to join a running one
        ux = sim.robot("UX_1")
        ux.thrusts([10, 0, -10, 0, 10, 0, -10, 0])
        sim.run_for(5.0)      # deterministic: commands sent before the call apply from the next step
        print(sim.time, ux.odom().pose.pose.position, ux.latest("kvh/imu_raw").header.stamp)

The facade (python/unexmin/scripting/simulation.py) imports this module only when the ROS back end is chosen.
"""

import atexit
import os
import weakref

import rosgraph
import rospy
from geometry_msgs.msg import Wrench
from rosgraph_msgs.msg import Clock
from std_msgs.msg import Float64
from std_srvs.srv import Empty

from unexmin.scripting.api import RobotApi, SimulationApi, check_launch_arguments, finite
from unexmin.scripting.launcher import WorldProcess, wait_for
from unexmin.scripting.rospy_node import master_online, node_master_uri, register_again
from unexmin.scripting.streams import StreamSet, header_stamp
from unexmin.srv import Reset, Step
from unexmin.topics import sync_publisher

#: Longest burst of one /sim/step call [s of sim time] while sensor streams are subscribed: half of
#: the 20 s of sim time the simulator's outgoing queue holds per topic (SensorPublisher::queueSize),
#: so no message is dropped however slowly this process reads.
MAX_BURST = 10.0

_SERVICES = ("/sim/step", "/sim/pause", "/sim/unpause", "/sim/reset", "/sim/reset_seed")
_open = None  # weakref to this process's open RosSimulation (rospy: one node per process, one master)


class RosRobot(RobotApi):
    """Handle on one simulated robot's topics (names relative to /<name>/). Made by RosSimulation.robot()."""

    def __init__(self, sim, name, thrusters):
        self.sim = sim
        self.name = name
        self.thruster_count = thrusters
        ns = f"/{name}/"
        self._thr = [sync_publisher(f"{ns}thrusters/{i}/input", Float64) for i in range(thrusters)]
        self._pendulum = sync_publisher(f"{ns}pendulum", Float64)
        self._vbs = sync_publisher(f"{ns}vbs", Float64)
        self._wrench = sync_publisher(f"{ns}force_moments", Wrench)
        self._pubs = self._thr + [self._pendulum, self._vbs, self._wrench]
        self._all_streams = False
        wait_for(
            lambda: all(p.get_num_connections() > 0 for p in self._thr + [self._pendulum, self._vbs]),
            sim.timeout,
            f"the simulator to subscribe to {name}'s command topics",
        )

    def _resolve(self, topic):
        return topic if topic.startswith("/") else f"/{self.name}/{topic}"

    # -- streams ------------------------------------------------------------------------------------
    def subscribe_streams(self, streams="all"):
        """Subscribe topics the simulator publishes under /<name>/ so that latest() and collect() have
        them from the next step on: "all", "none" or topic names (relative to /<name>/ or absolute).
        The simulator then builds their messages at every step, which costs simulation speed."""
        if isinstance(streams, str) and streams not in ("all", "none"):
            raise ValueError(f"streams must be 'all', 'none' or a list of topic names, got {streams!r}")
        if streams == "none" or not streams or (streams == "all" and self._all_streams):
            return []
        offered = self.sim._streams.simulator_topics(f"/{self.name}/")
        self._all_streams = self._all_streams or streams == "all"
        wanted = sorted(offered) if streams == "all" else [self._resolve(t) for t in streams]
        unknown = [t for t in wanted if t not in offered]
        if unknown:
            raise LookupError(
                f"the simulator publishes no {', '.join(unknown)} (topics of /{self.name}/: "
                f"{', '.join(sorted(offered)) or 'none'})"
            )
        return self.sim._streams.subscribe({t: self._message_class(t, offered[t]) for t in wanted}, synced=True)

    @property
    def topics(self):
        """Subscribed topics of this robot (absolute names) with their message type names."""
        prefix = f"/{self.name}/"
        return {t: s.msg_class._type for t, s in self.sim._streams.streams.items() if t.startswith(prefix)}

    @staticmethod
    def _message_class(topic, type_name):
        import roslib.message

        cls = roslib.message.get_message_class(type_name) if type_name else None
        if cls is None:
            raise LookupError(
                f"{topic}: cannot load the message class of type '{type_name}' (is its package "
                "built and the workspace sourced?)"
            )
        return cls

    def _stream(self, topic, msg_class, caller):
        """The Stream of `topic`, subscribed now if needed; checks msg_class against the topic's type."""
        full = self._resolve(topic)
        streams = self.sim._streams
        stream = streams.streams.get(full)
        if stream is None:
            published = streams.published(full)
            type_name, nodes = published.get(full, ("", []))
            if not nodes and msg_class is None:
                mine = sorted(t for t in streams.published(f"/{self.name}/"))
                raise LookupError(
                    f"{caller}('{topic}'): nobody publishes {full} (topics of /{self.name}/: "
                    f"{', '.join(mine) or 'none'}); give its message class to wait for it"
                )
            cls = msg_class or self._message_class(full, type_name)
            if type_name and cls._type != type_name:
                raise TypeError(f"{caller}('{topic}', {cls._type}): {full} carries {type_name}")
            stream = streams.subscribe({full: cls}, synced=streams.sim_node in nodes, wait=bool(nodes))[0]
        elif msg_class is not None and msg_class._type != stream.msg_class._type:
            raise TypeError(f"{caller}('{topic}', {msg_class._type}): {full} carries {stream.msg_class._type}")
        return stream

    def latest(self, topic, msg_class=None, min_stamp=None, timeout=None):
        """The newest message on /<name>/<topic> (or an absolute topic) at or before sim.time.

        msg_class: optional; the class comes from the topic's type, and a different one raises TypeError.
        min_stamp [s]: the message must be stamped at or after it.
        For a topic of the simulator subscribed before the last step (every topic of the robot, unless
        the robot was made with streams="none"), the answer is immediate and exact: the newest message
        the simulator published up to sim.time; LookupError if there is none (the sensor has not
        sampled yet, or the topic was subscribed only now: step, then ask again). While the world runs
        free (unpause()), and for other nodes' topics (translators), it waits up to `timeout` s of wall
        time (default: the Simulation's) for a message, then raises TimeoutError.
        """
        stream = self._stream(topic, msg_class, "latest")
        streams = self.sim._streams

        def ready(msg):
            stamp = header_stamp(msg)
            return min_stamp is None or stamp is None or stamp >= min_stamp - 1e-9

        msg = streams.newest(stream)
        if msg is not None and ready(msg):
            return msg
        wanted = f" stamped >= {min_stamp} s" if min_stamp is not None else ""
        if stream.synced and not self.sim.free_running:
            why = (
                "it was subscribed after the last step call (e.g. robot(..., streams='none')): step, then ask again"
                if stream.fresh
                else "nothing was published on it since the start or the last reset "
                "(a sensor publishes its first sample at t = 1/rate)"
            )
            raise LookupError(f"no message{wanted} on {stream.topic} up to sim time {self.sim.time:.6f} s: {why}")
        timeout = self.sim.timeout if timeout is None else timeout
        msg = streams.wait_newest(stream, ready, timeout)
        if msg is None:
            raise TimeoutError(f"no message{wanted} on {stream.topic} within {timeout} s of wall time")
        return msg

    def collect(self, topic, msg_class=None):
        """A Collector of every message on /<name>/<topic> (or an absolute topic) from now on:
        start it, step, then read collector.messages (see unexmin.scripting.streams.Collector). For a topic of
        the simulator the list is complete after each step call, none lost."""
        stream = self._stream(topic, msg_class, "collect")
        return self.sim._streams.collector(stream)

    # -- commands -----------------------------------------------------------------------------------
    def thrusts(self, values):
        """Command every thruster (command unit of each thruster, [N] by default)."""
        values = list(values)
        if len(values) != len(self._thr):
            raise ValueError(
                f"thrusts needs {len(self._thr)} values for {self.name} "
                f"(/sim/thruster_count/{self.name}), got {len(values)}"
            )
        msgs = [Float64(finite(f"thrust[{i}]", v)) for i, v in enumerate(values)]
        for pub, msg in zip(self._thr, msgs):
            self._send(pub, msg)

    def wrench(self, X=0.0, Y=0.0, Z=0.0, K=0.0, M=0.0, N=0.0):
        """Desired body wrench [N, N m] on force_moments (needs the thruster allocator running)."""
        w = Wrench()
        w.force.x, w.force.y, w.force.z = (finite(n, v) for n, v in (("X", X), ("Y", Y), ("Z", Z)))
        w.torque.x, w.torque.y, w.torque.z = (finite(n, v) for n, v in (("K", K), ("M", M), ("N", N)))
        self._send(self._wrench, w)

    def pendulum(self, angle):
        """Pendulum target angle [rad]."""
        self._send(self._pendulum, Float64(finite("pendulum", angle)))

    def vbs(self, mass):
        """Ballast mass [kg]."""
        self._send(self._vbs, Float64(finite("vbs", mass)))

    def _send(self, pub, msg):
        pub.publish(msg)
        if pub is not self._wrench:  # force_moments goes to the allocator, not the simulator
            self.sim.note_published(1)

    def odom(self):
        """Ground-truth odometry (nav_msgs/Odometry, as on /<robot>/odom) at the current sim time.

        It comes back with every step call, so reading it costs no stream at RTF x 50 Hz."""
        if self.name not in self.sim._odometry:
            self.sim.step(0)
        return self.sim._odometry[self.name]

    def _close(self):
        for p in self._pubs:
            p.unregister()


class RosSimulation(SimulationApi):
    """Client of a running simulator (its ROS master is ROS_MASTER_URI), or of a world it launched.

    One per process at a time: rospy runs one ROS node per process, talking to one master. A
    Simulation is a context manager; close() (or the end of the `with` block, also on an exception)
    stops the world it launched. After close(), another Simulation can be made in the same process.
    """

    backend = "ros"

    def __init__(self, node_name="unexmin_script", timeout=30.0, world=None):
        """Connect to the simulator of ROS_MASTER_URI (waits up to `timeout` s of wall time for its
        /sim services); `world`: the WorldProcess this Simulation owns and closes (Simulation.launch)."""
        global _open
        _refuse_a_second("Simulation")
        self.timeout = timeout
        self._world = world
        self._robots = {}
        self._streams = None
        self._closed = False
        self.master_uri = rosgraph.get_master_uri()
        _open = weakref.ref(self)
        try:
            self._connect(node_name)
        except BaseException:
            self._close(world_timeout=3.0)  # a failed world: no need to wait for nodes stuck in their start-up
            raise

    def _connect(self, node_name):
        world = self._world
        node_master = node_master_uri()
        if node_master is not None and node_master.rstrip("/") != self.master_uri.rstrip("/"):
            raise RuntimeError(
                f"this process's ROS node was started on the master {node_master}, and rospy cannot "
                f"move it to {self.master_uri}: use another process for that simulator"
            )

        probe = rosgraph.Master("/unexmin_probe", master_uri=self.master_uri)

        def alive():
            if world is None:
                return True
            log = world.log_path or "the roslaunch output"
            if not world.alive():
                raise RuntimeError(
                    f"the world's roslaunch exited (code {world.proc.returncode}) before the simulator "
                    f"offered /sim/step: see {log}"
                )
            if world.simulator_died(probe):
                raise RuntimeError(f"the simulator node exited at start-up: see {log}")
            return True

        wait_for(
            lambda: alive() and master_online(self.master_uri), self.timeout, f"the ROS master at {self.master_uri}"
        )
        if not rospy.core.is_initialized():
            rospy.init_node(node_name, anonymous=True, disable_signals=True)
        else:  # maybe a new master at the node's URI (a world launched again): tell it about rospy's own topics
            register_again()

        def up():
            alive()
            try:
                for srv in _SERVICES:
                    rospy.wait_for_service(srv, 0.2)
                return True
            except rospy.ROSException:
                return False

        wait_for(up, self.timeout, "the simulator's /sim services")
        if world is not None:  # and the world's other nodes (allocator, translators): ready for use, and
            # a world closed at once does not interrupt a node in its start-up (a rospy node can then hang)
            wait_for(lambda: alive() and world.nodes_up(probe), self.timeout, "every node of the world to start")
        self._step = rospy.ServiceProxy("/sim/step", Step, persistent=True)
        self._pause = rospy.ServiceProxy("/sim/pause", Empty)
        self._unpause = rospy.ServiceProxy("/sim/unpause", Empty)
        self._reset = rospy.ServiceProxy("/sim/reset", Empty)
        self._reset_seed = rospy.ServiceProxy("/sim/reset_seed", Reset)
        self.physics_rate = float(rospy.get_param("/simulator/physics_rate", 500.0))
        names = rospy.get_param("/sim/robots", None)
        if names is None:
            raise RuntimeError(
                "the simulator did not set /sim/robots: it is older than this script (rebuild the workspace)"
            )
        self.robots = tuple(names)
        self._thruster_count = {n: int(rospy.get_param(f"/sim/thruster_count/{n}")) for n in self.robots}
        self._time = 0.0
        self._step_count = 0  # physics steps of the simulator after the last step call
        self.free_running = world is None and not rospy.get_param("/simulator/paused", False)
        self._commands_sent = 0  # command messages published to the simulator by this node
        self._odometry = {}  # robot name -> Odometry at self._time
        master = rosgraph.Master(rospy.get_name(), master_uri=self.master_uri)
        sim_node = next(nodes[0] for srv, nodes in master.getSystemState()[2] if srv == "/sim/step")
        self._streams = StreamSet(master, sim_node, self.timeout)
        self._clock = rospy.Subscriber("/clock", Clock, self._on_clock, queue_size=1)

    @classmethod
    def launch(
        cls,
        world="tank",
        robots=1,
        seed=0,
        log_dir=None,
        timeout=60.0,
        launch_file=None,
        vehicles=None,
        mode="operational",
        visibility="",
        sensors="all",
        mapping=False,
        map_file="",
        overrides=None,
        record="",
        **kwargs,
    ):
        """Start a headless lockstep world, paused, on a private master and connect to it.

        world: `<world>_world.launch` of the package (tank, mine, test_box); robots: how many of the
        world's robots to spawn; seed: the simulator's seed; log_dir: folder for roslaunch.log and the
        nodes' logs; timeout [s] of wall time for the world to offer its services; launch_file: a
        launch file to run instead of `<world>_world.launch` (it must start the simulator paused in
        lockstep; it gets none of the launch arguments). mode, visibility, sensors, mapping, map_file,
        overrides ({robot: xacro file}, as `<robot>_overrides:=`) and record: the launch file's arguments
        of the same names. vehicles: a mixed team instead of `robots` UX-1s, vehicle types in order (a
        list, as unexmin.vehicles.parse_vehicles gives; robots UX_1, ROV_1, AUV_1). kwargs go to
        RosSimulation() (node_name).
        The first launch of a process picks a free port; later ones (after close()) reuse it, because
        rospy stays bound to the master it first registered with.
        """
        arguments = dict(
            mode=mode,
            visibility=visibility,
            sensors=sensors,
            mapping=mapping,
            map_file=map_file,
            overrides=overrides,
            record=record,
        )
        extra_args = launch_arguments(launch_file, **arguments)
        if vehicles:
            extra_args = (*extra_args, f"vehicles:={','.join(vehicles)}")
        _refuse_a_second("Simulation.launch")
        port = None
        node_master = node_master_uri()
        if node_master is not None:
            from urllib.parse import urlparse

            url = urlparse(node_master)
            if url.hostname not in ("127.0.0.1", "localhost") or master_online(node_master):
                raise RuntimeError(
                    f"Simulation.launch: this process's ROS node is bound to the master {node_master}"
                    ", which is not a closed world of this process (rospy cannot move a node to "
                    "another master): launch the world from another process"
                )
            port = url.port
        proc = WorldProcess(
            world=world,
            robots=robots,
            seed=seed,
            realtime=False,
            paused=True,
            log_dir=log_dir,
            port=port,
            launch_file=launch_file,
            extra_args=extra_args,
        )
        try:
            return cls(timeout=timeout, world=proc, **kwargs)
        except BaseException:  # Ctrl-C (KeyboardInterrupt) while connecting too: no roslaunch left behind
            proc.close(timeout=3.0)  # a failed world: no need to wait for nodes stuck in their start-up
            raise

    def _on_clock(self, msg):
        if self.free_running:  # in lockstep the time comes with each step's answer
            self._time = max(self._time, msg.clock.to_sec())

    @property
    def time(self):
        """Simulation time [s] after the last step (or as last seen on /clock while running free)."""
        return self._time

    def robot(self, name, streams="all"):
        """Handle on robot `name` (one of self.robots; KeyError naming them otherwise).

        streams: which topics the simulator publishes under /<name>/ to subscribe now, so that
        latest() and collect() have them from the next step on: "all" (default), "none" (commands and
        odom() only: the simulator then builds no sensor message for this script, which is faster), or
        a list of topic names. A later call can add topics; none is ever dropped.
        """
        if name not in self.robots:
            raise KeyError(f"no robot named '{name}' in the simulator (robots: {', '.join(self.robots)})")
        if name not in self._robots:
            self._robots[name] = RosRobot(self, name, self._thruster_count[name])
        self._robots[name].subscribe_streams(streams)
        return self._robots[name]

    def note_published(self, n):
        """Count `n` command messages this node sent to the simulator on publishers of its own
        (the Robot handles count theirs): the next step waits until they are applied."""
        self._commands_sent += int(n)

    def _gone(self, what):
        """Error text when a call to the simulator failed: whether its world is still running, and its log."""
        if self._world is not None and not self._world.alive():
            return (
                f"{what}: the simulator world exited (code {self._world.proc.returncode}); "
                f"see {self._world.log_path or 'the roslaunch output'}"
            )
        return f"{what}: the simulator is not answering (has it died? see its log)"

    def pause(self):
        """Stop free running. When it returns, sim.time and odom() are those of the paused world and
        every message published until then has arrived (it asks for a step of 0 steps, which also
        publishes the odometry of that instant on /<robot>/odom)."""
        self._pause()
        self._step_once(0)

    def unpause(self):
        """Run free (real time or as fast as possible, as launched) until pause() or a step call."""
        self._unpause()
        self.free_running = True

    def step(self, n=1):
        """Advance exactly n physics steps; returns the sim time [s].

        When it returns, every message the simulator published during the steps on a subscribed
        stream has arrived (latest(), collectors). With streams subscribed, a long advance is made in
        bursts of at most MAX_BURST s of sim time, cut at whole multiples of it: the physics is the
        same as in one call, and so are the streams but for the /clock and joint state messages that
        the end of every call publishes."""
        if int(n) != n or n < 0:
            raise ValueError(f"step needs a non-negative whole number of steps, got {n!r}")
        remaining = int(n)
        burst = max(1, round(MAX_BURST * self.physics_rate))
        while True:
            chunk = remaining
            if any(s.synced for s in self._streams.streams.values()):
                chunk = min(remaining, burst - self._step_count % burst)
            self._step_once(chunk)
            remaining -= chunk
            if remaining <= 0:
                return self._time

    def _step_once(self, n):
        # hold: this script is in control, so the simulator's command watchdog (a safety net for
        # live nodes that die) does not zero its commands while it steps.
        try:
            res = self._step(duration=0.0, steps=n, client=rospy.get_name(), commands=self._commands_sent, hold=True)
        except (rospy.ServiceException, rospy.ROSException, OSError) as e:
            raise RuntimeError(self._gone(f"/sim/step failed ({e})")) from None
        self.free_running = False
        self._time = res.time
        self._step_count = res.step
        self._odometry = {o.child_frame_id.split("/")[0]: o for o in res.odometry}
        self._streams.sync()
        for s in self._streams.streams.values():
            s.fresh = False

    def reset(self, seed=None):
        """Everything back to t = 0 (robots at spawn, actuators zero); a new seed if given. The newest
        message of every stream is forgotten (collectors keep theirs and go on collecting)."""
        self._streams.forget_newest()
        if seed is None:
            self._reset()
        else:
            self._reset_seed(seed=int(seed))
        self._time = 0.0
        self._step_count = 0
        self._odometry = {}
        self._streams.sync()

    def close(self, timeout=15.0):
        """Unsubscribe this script's topics and stop the world this object launched (if any; it gets
        `timeout` s of wall time after SIGINT before SIGKILL); idempotent. Another Simulation can then be
        made (or launched) in this process."""
        self._close(timeout)

    def _close(self, world_timeout=15.0):
        global _open
        if self._closed:
            return
        self._closed = True
        try:
            if self._streams is not None:
                self._streams.close()
            for r in self._robots.values():
                r._close()
            self._robots.clear()
            if hasattr(self, "_clock"):
                self._clock.unregister()
            if hasattr(self, "_step"):
                self._step.close()
        finally:
            if self._world is not None:
                self._world.close(world_timeout)
                self._world = None
            if _open is not None and _open() is self:
                _open = None


def launch_arguments(launch_file, mode, visibility, sensors, mapping, map_file, overrides, record):
    """The `name:=value` arguments of `<world>_world.launch` for Simulation.launch's world arguments (only those
    that differ from the launch file's defaults); ValueError naming an argument out of its domain, or one given
    with a launch_file of the caller's (which gets no arguments)."""
    sensors = check_launch_arguments(mode, visibility, sensors, mapping, map_file, overrides, record)
    args = []
    for name, value, default in (
        ("mode", mode, "operational"),
        ("visibility", visibility, ""),
        ("sensors", sensors, "all"),
        ("mapping", mapping, False),
        ("map_file", map_file, ""),
        ("record", record, ""),
    ):
        if value != default:
            args.append(f"{name}:={str(value).lower() if isinstance(value, bool) else value}")
    for robot, file in (overrides or {}).items():
        if file and not os.path.isfile(file):
            raise FileNotFoundError(f"overrides['{robot}'] = {file}: no such xacro file")
        args.append(f"{robot}_overrides:={file}")
    if args and launch_file:
        raise ValueError(
            f"launch_file = {launch_file}: a launch file of the caller's gets no arguments, yet "
            f"{', '.join(a.split(':=')[0] for a in args)} were given: set them in that file"
        )
    return args


def _refuse_a_second(caller):
    """RuntimeError naming `caller` when this process already has an open Simulation: rospy runs one ROS node per
    process, talking to one master."""
    other = _open() if _open is not None else None
    if other is not None:
        raise RuntimeError(
            f"{caller}: this process already has an open Simulation (master {other.master_uri}); rospy runs one "
            "ROS node per process, talking to one master, so only one Simulation can be open at a time: close() "
            "the first one (or use `with Simulation.launch(...) as sim:`), or use another process"
        )


def _close_at_exit():
    """A Simulation still open when Python exits stops its world (a roslaunch would outlive the script)."""
    sim = _open() if _open is not None else None
    if sim is not None:
        sim.close()


atexit.register(_close_at_exit)

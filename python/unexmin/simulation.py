"""Script the simulator from Python as if it were bound in-process, through ROS 1.

    from unexmin import Simulation
    sim = Simulation.launch("tank", robots=1, seed=3)   # or Simulation() to join a running one
    ux = sim.robot("UX_1")
    ux.thrusts([10, 0, -10, 0, 10, 0, -10, 0])
    sim.run_for(5.0)          # deterministic: commands sent before the call apply from the next step
    print(sim.time, ux.odom().pose.pose.position)

See docs/python_api.md.
"""

import atexit
import math
import threading
import warnings

import rospy
from geometry_msgs.msg import Wrench
from rosgraph_msgs.msg import Clock
from std_msgs.msg import Float64
from std_srvs.srv import Empty

from unexmin.launcher import WorldProcess, wait_for
from unexmin.srv import Reset, Step


def _finite(name, value):
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name} must be a finite number, got {value!r}")
    return value


def sync_publisher(topic, msg_class):
    """A publisher whose publish() writes synchronously (queue_size=None), so a command is on the
    wire before the next /sim/step request and applies from the next physics step."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SyntaxWarning)  # rospy's advice to set queue_size
        return rospy.Publisher(topic, msg_class, queue_size=None)


class Robot:
    """Handle on one simulated robot's topics (names relative to /<name>/)."""

    def __init__(self, sim, name, thrusters=8):
        self.sim = sim
        self.name = name
        ns = f"/{name}/"
        self._thr = [sync_publisher(f"{ns}thrusters/{i}/input", Float64) for i in range(thrusters)]
        self._pendulum = sync_publisher(f"{ns}pendulum", Float64)
        self._vbs = sync_publisher(f"{ns}vbs", Float64)
        self._wrench = sync_publisher(f"{ns}force_moments", Wrench)
        self._latest = {}
        self._cond = threading.Condition()
        self._subs = {}
        wait_for(lambda: all(p.get_num_connections() > 0 for p in self._thr + [self._pendulum, self._vbs]),
                 sim.timeout, f"the simulator to subscribe to {name}'s command topics")

    def subscribe(self, topic, msg_class):
        if topic not in self._subs:
            self._subs[topic] = rospy.Subscriber(f"/{self.name}/{topic}", msg_class, self._store, topic,
                                                 queue_size=50, tcp_nodelay=True)
        return self._subs[topic]

    def _store(self, msg, topic):
        with self._cond:
            self._latest[topic] = msg
            self._cond.notify_all()

    def thrusts(self, values):
        """Command every thruster (command unit of each thruster, [N] by default)."""
        values = list(values)
        if len(values) != len(self._thr):
            raise ValueError(f"thrusts needs {len(self._thr)} values, got {len(values)}")
        msgs = [Float64(_finite(f"thrust[{i}]", v)) for i, v in enumerate(values)]
        for pub, msg in zip(self._thr, msgs):
            self._send(pub, msg)

    def wrench(self, X=0.0, Y=0.0, Z=0.0, K=0.0, M=0.0, N=0.0):
        """Desired body wrench [N, N m] on force_moments (needs the thruster allocator running)."""
        w = Wrench()
        w.force.x, w.force.y, w.force.z = (_finite(n, v) for n, v in (("X", X), ("Y", Y), ("Z", Z)))
        w.torque.x, w.torque.y, w.torque.z = (_finite(n, v) for n, v in (("K", K), ("M", M), ("N", N)))
        self._send(self._wrench, w)

    def pendulum(self, angle):
        """Pendulum target angle [rad]."""
        self._send(self._pendulum, Float64(_finite("pendulum", angle)))

    def vbs(self, mass):
        """Ballast mass [kg]."""
        self._send(self._vbs, Float64(_finite("vbs", mass)))

    def _send(self, pub, msg):
        pub.publish(msg)
        if pub is not self._wrench:  # force_moments goes to the allocator, not the simulator
            self.sim.note_published(1)

    def latest(self, topic, msg_class=None, min_stamp=None, timeout=None):
        """Latest message on /<robot>/<topic>; waits for the first one (or one stamped >= min_stamp [s])."""
        if topic not in self._subs:
            if msg_class is None:
                raise ValueError(f"latest('{topic}') needs its message class the first time")
            self.subscribe(topic, msg_class)
        timeout = self.sim.timeout if timeout is None else timeout

        def ready():
            msg = self._latest.get(topic)
            if msg is None:
                return False
            stamp = getattr(getattr(msg, "header", None), "stamp", None)
            return min_stamp is None or stamp is None or stamp.to_sec() >= min_stamp - 1e-9

        with self._cond:
            if not self._cond.wait_for(ready, timeout):
                raise TimeoutError(f"no message on /{self.name}/{topic} within {timeout} s")
            return self._latest[topic]

    def odom(self):
        """Ground-truth odometry (nav_msgs/Odometry, as on /<robot>/odom) at the current sim time.

        It comes back with every step call, so reading it costs no stream at RTF x 50 Hz."""
        if self.name not in self.sim._odometry:
            self.sim.step(0)
        try:
            return self.sim._odometry[self.name]
        except KeyError:
            raise KeyError(f"the simulator has no robot named '{self.name}'") from None


class Simulation:
    """Client of a running simulator (its ROS master is ROS_MASTER_URI)."""

    def __init__(self, node_name="unexmin_script", timeout=30.0, world=None):
        self.timeout = timeout
        self._world = world
        if not rospy.core.is_initialized():
            rospy.init_node(node_name, anonymous=True, disable_signals=True)
        services = ("/sim/step", "/sim/pause", "/sim/unpause", "/sim/reset", "/sim/reset_seed")
        if world is None:
            for srv in services:
                rospy.wait_for_service(srv, timeout)
        else:  # fail fast if the world we launched dies (a bad world file, a crash)
            def up():
                if not world.alive():
                    raise RuntimeError(f"the simulator world exited (code {world.proc.returncode}) before it "
                                       f"offered /sim/step: see {world.log_path or 'the roslaunch output'}")
                try:
                    for srv in services:
                        rospy.wait_for_service(srv, 0.2)
                    return True
                except rospy.ROSException:
                    return False

            wait_for(up, timeout, "the simulator's /sim services")
        self._step = rospy.ServiceProxy("/sim/step", Step, persistent=True)
        self._pause = rospy.ServiceProxy("/sim/pause", Empty)
        self._unpause = rospy.ServiceProxy("/sim/unpause", Empty)
        self._reset = rospy.ServiceProxy("/sim/reset", Empty)
        self._reset_seed = rospy.ServiceProxy("/sim/reset_seed", Reset)
        self.physics_rate = float(rospy.get_param("/simulator/physics_rate", 500.0))
        self._time = 0.0
        self._commands_sent = 0  # command messages published to the simulator by this node
        self._odometry = {}  # robot name -> Odometry at self._time
        self._clock = rospy.Subscriber("/clock", Clock, self._on_clock, queue_size=1)
        self._robots = {}

    @classmethod
    def launch(cls, world="tank", robots=1, seed=0, log_dir=None, timeout=60.0, **kwargs):
        """Start a headless lockstep world (paused) on a private master and connect to it."""
        proc = WorldProcess(world=world, robots=robots, seed=seed, realtime=False, paused=True, log_dir=log_dir)
        try:
            sim = cls(timeout=timeout, world=proc, **kwargs)
        except BaseException:  # Ctrl-C (KeyboardInterrupt) while connecting too: no roslaunch left behind
            proc.close()
            raise
        # A script that ends without close() (Ctrl-C, an exception) stops its world on exit all the same.
        atexit.register(sim.close)
        return sim

    def _on_clock(self, msg):
        self._time = max(self._time, msg.clock.to_sec())

    @property
    def time(self):
        """Simulation time [s] after the last step (or as last seen on /clock)."""
        return self._time

    def robot(self, name):
        if name not in self._robots:
            self._robots[name] = Robot(self, name)
        return self._robots[name]

    def note_published(self, n):
        """Count `n` command messages this node sent to the simulator on publishers of its own
        (the Robot handles count theirs): the next step waits until they are applied."""
        self._commands_sent += int(n)

    def _gone(self, what):
        """Error text when a call to the simulator failed: whether its world is still running, and its log."""
        if self._world is not None and not self._world.alive():
            return (f"{what}: the simulator world exited (code {self._world.proc.returncode}); "
                    f"see {self._world.log_path or 'the roslaunch output'}")
        return f"{what}: the simulator is not answering (has it died? see its log)"

    def pause(self):
        self._pause()

    def unpause(self):
        self._unpause()

    def step(self, n=1):
        """Advance exactly n physics steps (pause first); returns the sim time [s]."""
        if int(n) != n or n < 0:
            raise ValueError(f"step needs a non-negative whole number of steps, got {n!r}")
        # hold: this script is in control, so the simulator's command watchdog (a safety net for
        # live nodes that die) does not zero its commands while it steps.
        try:
            res = self._step(duration=0.0, steps=int(n), client=rospy.get_name(), commands=self._commands_sent,
                             hold=True)
        except (rospy.ServiceException, rospy.ROSException, OSError) as e:
            raise RuntimeError(self._gone(f"/sim/step failed ({e})")) from None
        self._time = res.time
        self._odometry = {o.child_frame_id.split("/")[0]: o for o in res.odometry}
        return self._time

    def run_for(self, seconds):
        """Advance by `seconds` of sim time, rounded to whole physics steps; returns the sim time [s]."""
        seconds = _finite("seconds", seconds)
        if seconds < 0:
            raise ValueError(f"run_for needs seconds >= 0, got {seconds}")
        return self.step(round(seconds * self.physics_rate))

    def reset(self, seed=None):
        """Everything back to t = 0 (robots at spawn, actuators zero); a new seed if given."""
        if seed is None:
            self._reset()
        else:
            self._reset_seed(seed=int(seed))
        self._time = 0.0
        self._odometry = {}
        for r in self._robots.values():
            with r._cond:
                r._latest.clear()

    def close(self):
        """Stop the world this object launched (if any)."""
        if self._world is not None:
            self._world.close()
            self._world = None

"""The scripting API's back-end protocol (docs/python_api.md, "Back ends").

`Simulation.launch(..., backend="ros")` (python/unexmin/scripting/ros_backend.py) drives the ROS simulator through
a private master; `backend="core"` (python/unexmin/scripting/core_backend.py) drives the engine in-process
(unexmin.core); python/unexmin/scripting/simulation.py chooses between them. Both implement the calls below with
the same meaning, units and errors; the messages differ in kind (ROS messages on one side, the engine's sample
dicts on the other), the odometry does not (nav_msgs/Odometry from `odom()` on both). Pure Python: importing it
needs no ROS.
"""

import abc
import math

#: Arguments of Simulation.launch that configure the world (the launch files' arguments of the same names).
LAUNCH_ARGUMENTS = ("mode", "visibility", "sensors", "mapping", "map_file", "overrides", "record")
BACKENDS = ("ros", "core")


def finite(name, value):
    """`value` as a float; ValueError naming `name` when it is not a finite number."""
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name} must be a finite number, got {value!r}")
    return value


def check_launch_arguments(mode, visibility, sensors, mapping, map_file, overrides, record):
    """ValueError naming the first launch argument out of its domain (both back ends check the same way: mode,
    visibility and sensors by the engine's own rules, unexmin._core.check_settings)."""
    from unexmin import _core

    if isinstance(sensors, (list, tuple)):
        sensors = ",".join(sensors)
    if not isinstance(sensors, str) or not sensors:
        raise ValueError(f"sensors = {sensors!r}: expected 'all', 'none' or families such as 'imu,dvl,m3'")
    if not isinstance(mode, str) or not isinstance(visibility, str):
        raise ValueError(f"mode = {mode!r}, visibility = {visibility!r}: expected text")
    _core.check_settings(sensors=sensors, visibility=visibility, mode=mode)
    if not isinstance(mapping, bool):
        raise ValueError(f"mapping = {mapping!r}: expected True or False")
    if not isinstance(map_file, str) or not isinstance(record, str):
        raise ValueError("map_file and record: expected a path (str), '' for none")
    if overrides is not None and not isinstance(overrides, dict):
        raise ValueError(f"overrides = {overrides!r}: expected {{robot name: xacro overrides file}}")
    return sensors


class RobotApi(abc.ABC):
    """One robot of a Simulation: commands, ground truth, sensor data (both back ends)."""

    name: str
    thruster_count: int

    @abc.abstractmethod
    def thrusts(self, values):
        """Command every thruster (each thruster's command unit, [N] by default); ValueError before anything is
        applied for a wrong count or a non-finite value."""

    @abc.abstractmethod
    def pendulum(self, angle):
        """Pendulum target angle [rad]."""

    @abc.abstractmethod
    def vbs(self, mass):
        """Ballast mass [kg]."""

    @abc.abstractmethod
    def wrench(self, X=0.0, Y=0.0, Z=0.0, K=0.0, M=0.0, N=0.0):
        """Desired body wrench [N, N m], allocated to the thrusters by the thesis allocation."""

    @abc.abstractmethod
    def odom(self):
        """Ground truth (nav_msgs/Odometry, as /<robot>/odom) at sim.time."""

    @abc.abstractmethod
    def latest(self, topic, msg_class=None, min_stamp=None, timeout=None):
        """The newest sample of `topic` at or before sim.time; LookupError when there is none yet."""

    @abc.abstractmethod
    def collect(self, topic, msg_class=None):
        """A collector of every sample of `topic` from now on (none lost)."""


class SimulationApi(abc.ABC):
    """A world and its robots, stepped by the script (both back ends). A context manager: close() at the end."""

    backend: str
    physics_rate: float
    robots: tuple

    @property
    @abc.abstractmethod
    def time(self):
        """Simulation time [s] after the last step call."""

    @abc.abstractmethod
    def robot(self, name, streams="all"):
        """Handle on robot `name`; KeyError naming the robots otherwise."""

    @abc.abstractmethod
    def step(self, n=1):
        """Advance exactly `n` physics steps; returns sim.time [s]."""

    @abc.abstractmethod
    def reset(self, seed=None):
        """Back to t = 0 (robots at spawn, actuators zero); a new seed if given."""

    @abc.abstractmethod
    def close(self):
        """Release the world (idempotent)."""

    def run_for(self, seconds):
        """Advance by `seconds` of sim time, rounded to whole physics steps; returns the sim time [s]."""
        seconds = finite("seconds", seconds)
        if seconds < 0:
            raise ValueError(f"run_for needs seconds >= 0, got {seconds}")
        return self.step(round(seconds * self.physics_rate))

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

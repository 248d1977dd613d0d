"""The simulator's engine in-process, no ROS in the loop (docs/python_api.md, "unexmin.core").

``World`` is the C++ World, ray caster and sensor models the simulator node runs (the compiled module
``unexmin._core``, built by catkin from the same libraries), stepped the way the node steps in lockstep: the same
world file, seed and commands give the same trajectory and sensor samples as the ROS simulator, bit for bit.

    from unexmin.core import World
    w = World("tank", seed=3, sensors="imu,dvl,m3")
    ux = w.robot("UX_1")
    ux.thrusts([5, 0, -5, 0, 5, 0, -5, 0])      # [N] per thruster
    w.step(500)                                # 1 s at 500 Hz, the GIL released
    ux.state()["position"], ux.sample("m3")["ranges"]
"""

import math
import os

from unexmin.description import ROBOT_FILE, expand
from unexmin.vehicles import team_names
from unexmin.worlds.files import world_path

try:
    from unexmin import _core
except ImportError as e:  # the module is built by catkin_make into the workspace's devel space
    raise ImportError(
        f"unexmin._core is not built ({e}): build the workspace (catkin_make) and source scripts/env.sh"
    ) from None

__all__ = ["World", "Robot", "ConfigError", "robot_names"]

#: A world file or robot description the engine refuses (a ValueError naming the file and the problem).
ConfigError = _core.ConfigError
robot_names = _core.robot_names


class Robot:
    """One spawned robot of a World (World.robot(name)): commands, ground truth, sensor samples."""

    def __init__(self, world, name):
        self.world = world
        self.name = name
        self.thruster_count = world._core.thruster_count(name)

    def thrusts(self, values):
        """Command every thruster at once (each thruster's command unit, [N] by default): one finite value per
        thruster inside its command range; ValueError naming the value otherwise (nothing is applied then)."""
        self.world._core.set_thrusts(self.name, values)

    def achieved_thrusts(self):
        """Achieved thrust per thruster [N] (numpy array), as on /<robot>/thrusters/<i>/thrust."""
        return self.world._core.thrusts(self.name)

    def pendulum(self, angle):
        """Pendulum target angle [rad] (ValueError when not finite or out of range, or without a pendulum)."""
        self.world._core.set_pendulum(self.name, angle)

    def vbs(self, mass):
        """Ballast mass of the VBS [kg] (ValueError when not finite or out of range)."""
        self.world._core.set_vbs(self.name, mass)

    def state(self):
        """Ground truth of the base link, as the simulator's /<robot>/odom: dict of numpy arrays ``position``
        [m] and ``orientation`` (quaternion x, y, z, w) in the world frame; ``linear_velocity`` [m/s],
        ``angular_velocity`` [rad/s] and ``linear_acceleration`` (over the last step) [m/s^2] in the body
        frame (REP-105); ``time`` [s]."""
        return self.world._core.state(self.name)

    def set_pose(self, position, orientation=(0.0, 0.0, 0.0, 1.0)):
        """Teleport the base link to `position` [m] with `orientation` (unit quaternion x, y, z, w; default level,
        heading +x) in the world frame, at rest (velocities zero; thrusters, pendulum and ballast as they are): the
        next step starts there. ValueError naming a value that is not finite, a position that is not 3 numbers or
        an orientation that is not 4 numbers of norm 1 (within 1e-6); nothing moves then. Whether the hull overlaps
        the rock is not checked: the physics pushes it out at the next step."""
        self.world._core.set_pose(self.name, position, orientation)

    def set_rendering(self, camera, on):
        """Whether camera `camera` (a name of ``sensors`` of family camera) renders its frames in visual mode. Off,
        its samples only move its schedule (``rendered`` False, no ``image``), as when nobody subscribes to its
        image topic: a long run renders only the frames it needs. On by default; kept across reset(). KeyError for an
        unknown sensor, ValueError for one that is not a camera."""
        self.world._core.set_rendering(self.name, camera, bool(on))

    def fire(self, sensor):
        """Fire sensor `sensor` now, between steps (a water sampler starts filling its next bottle over its fill time:
        docs/water_sampler.md); returns what it did ("filling bottle 1 of 4"). KeyError for an unknown sensor,
        ValueError for one whose family does not fire or that cannot now (every bottle full, one filling)."""
        return self.world._core.fire(self.name, sensor)

    def contacts(self):
        """Where the hull touches the world's meshes or another robot after the last step: dict of numpy arrays,
        one row per contact point: ``position`` (N x 3) on the obstacle's surface [m] and ``normal`` (N x 3, unit)
        from the obstacle into the robot, world frame; ``depth`` (N) of penetration [m]; ``impulse`` (N) the
        physics engine's normal impulse over the last step [N s]. Empty (N = 0) when nothing touches."""
        return self.world._core.contacts(self.name)

    @property
    def sensors(self):
        """{sensor name: family} of the sensors that run (the families World's ``sensors`` keeps)."""
        return dict(self.world._core.sensor_names(self.name))

    @property
    def base_link(self):
        """The link of the robot's body frame (its odometry's child frame), from its description."""
        return self.world._core.base_link(self.name)

    def sample_count(self, sensor):
        """How many samples sensor `sensor` has taken since t = 0 (cheaper than sample(sensor)["count"])."""
        return self.world._core.sample_count(self.name, sensor)

    def sample_fields(self, sensor):
        """What a sample of sensor `sensor` holds, as its family describes it: one (name, unit, dtype, shape) per field
        of sample(sensor) after name and type, in the family's order (shape () for a scalar)."""
        return [(n, u, t, tuple(shape)) for n, u, t, shape in self.world._core.sample_fields(self.name, sensor)]

    def sample(self, sensor):
        """The newest sample of sensor `sensor` (a name of ``sensors``; KeyError listing them otherwise) as a dict
        (docs/python_api.md lists the keys of each family); ``time`` < 0 before its first sample."""
        return self.world._core.sample(self.name, sensor)


def _mapper_values(mapping):
    """The `mapping` argument as the engine takes it: None (no mapper), or {name: float, bool or str}."""
    if mapping is False or mapping is None:
        return None
    if mapping is True:
        return {}
    if not isinstance(mapping, dict):
        raise ValueError(f"mapping = {mapping!r}: expected True, False or a dict of mapper parameters")
    values = {}
    for name, value in mapping.items():
        if isinstance(value, (bool, str)):
            values[str(name)] = value
        elif isinstance(value, (int, float)):
            values[str(name)] = float(value)
        else:
            raise ValueError(f"mapping['{name}'] = {value!r}: expected a number, True/False or a text")
    return values


class World:
    """A world file with its robots, in this process (see the module's documentation).

    world: a shipped world's name (tank, mine, test_box) or a world file's path; robots: how many of the world's
    robots to spawn (the first ones) or their names in order (["UX_1", "ROV_1"], as ``spawns:=``); vehicles: a team
    of vehicle types instead (["ux1", "bluerov2_heavy"], as ``vehicles:=``: UX_1, ROV_1); seed: the simulator's seed;
    sensors: "all", "none" or families "imu,dvl,..." (as ``sensors:=``); visibility: a level of the world schema
    overriding the world file's ("": keep it); mode: operational|visual (cameras render, lights and lasers on);
    physics_rate [Hz]; overrides: {robot name: xacro overrides file} (as ``UX_k_overrides:=``); descriptions:
    {robot name: URDF text} instead of expanding the description file the world file names for each robot (urdf/);
    ray_caster_threads: 0 = every hardware thread; mapping: True (the mapper node's defaults) or a dict of mapper
    parameters (docs/mapping.md "In-process") to build the mapper node's OctoMap in this process as the world steps.
    The engine checks every setting (ValueError naming it).
    """

    def __init__(
        self,
        world="tank",
        robots=1,
        seed=0,
        sensors="all",
        visibility="",
        mode="operational",
        physics_rate=500.0,
        overrides=None,
        descriptions=None,
        ray_caster_threads=0,
        vehicles=None,
        mapping=False,
    ):
        path = world_path(world)
        if isinstance(seed, bool) or int(seed) != seed:
            raise ValueError(f"seed = {seed!r}: expected a non-negative whole number")
        spawns = team_names(vehicles) if vehicles is not None else []
        if isinstance(robots, (list, tuple)):
            spawns = [str(r) for r in robots]
        elif isinstance(robots, bool) or int(robots) != robots:
            raise ValueError(f"robots = {robots!r}: expected a count or a list of the world's robot names")
        count = len(spawns) if spawns else int(robots)
        if not isinstance(physics_rate, (int, float)) or not math.isfinite(physics_rate):
            raise ValueError(f"physics_rate = {physics_rate!r}: expected a finite number of Hz")
        spawned = dict(_core.spawned_robots(path, count, spawns))  # name -> description file, as the world file says
        names = list(spawned)
        overrides = dict(overrides or {})
        for name, file in overrides.items():
            if name not in names:
                raise KeyError(f"overrides: robot '{name}' is not spawned (robots: {', '.join(names)})")
            if file and not os.path.isfile(file):
                raise FileNotFoundError(f"overrides['{name}'] = {file}: no such xacro file")
        if descriptions is None:
            descriptions = {
                n: expand(ROBOT_FILE.parent / file, n, overrides.get(n) or None) for n, file in spawned.items()
            }
        self._core = _core.World(
            path,
            dict(descriptions),
            count,
            spawns,
            int(seed),
            str(sensors),
            str(visibility),
            float(physics_rate),
            str(mode),
            int(ray_caster_threads),
            _mapper_values(mapping),
        )
        self.world_file = path
        self._robots = {n: Robot(self, n) for n in self._core.robots}

    @property
    def robots(self):
        """Names of the spawned robots, in the world file's order."""
        return list(self._robots)

    def robot(self, name):
        """Handle on robot `name`; KeyError naming the spawned robots otherwise."""
        if name not in self._robots:
            raise KeyError(f"robot = '{name}': expected one of the spawned robots ({', '.join(self._robots)})")
        return self._robots[name]

    def step(self, n=1, hold=True):
        """Advance exactly `n` physics steps with the GIL released; returns the sim time [s]. hold: keep every
        command alive (the thruster watchdog, docs/simulator_node.md, does not zero them), as a script's
        /sim/step does."""
        if isinstance(n, bool) or int(n) != n or n < 0:
            raise ValueError(f"n = {n!r}: expected a non-negative whole number of steps")
        self._core.step(int(n), bool(hold))
        return self._core.time

    def run_for(self, seconds):
        """Advance by `seconds` [s] of sim time rounded to whole physics steps; returns the sim time [s]."""
        if not math.isfinite(seconds) or seconds < 0:
            raise ValueError(f"seconds = {seconds!r}: expected a finite number >= 0")
        return self.step(round(seconds / self._core.dt))

    def reset(self, seed=None):
        """Back to t = 0 (robots at their spawn poses at rest, actuators zero, sensors at turn-on), with `seed`
        (default: the same)."""
        seed = self._core.seed if seed is None else seed
        if isinstance(seed, bool) or int(seed) != seed or seed < 0:
            raise ValueError(f"seed = {seed!r}: expected a non-negative whole number")
        self._core.reset(int(seed))

    def set_current(self, speed, horizontal_angle=0.0, vertical_angle=0.0, steady=False):
        """Replace the means of the world's current: speed [m/s] (>= 0), horizontal angle [rad, from +x towards +y],
        vertical angle [rad, up positive]; each channel restarts at its new mean (bounds widened to hold it, noise
        and return rate the world file's; steady=True: no noise, the current stays at the means) and keeps it across
        reset(). ValueError naming a bad value."""
        self._core.set_current(float(speed), float(horizontal_angle), float(vertical_angle), bool(steady))

    def water(self, point):
        """The water column at world `point` [m] now, as every instrument reads it: dict of ``depth`` [m],
        ``temperature`` [degC], ``salinity`` [PSU], ``conductivity`` [uS/cm], ``ph``, ``redox`` [mV], ``oxygen``
        [mg/L], ``turbidity`` [NTU], ``density`` [kg/m^3] and ``sound_speed`` [m/s]; None in a world without a
        ``water.profile`` (docs/worlds.md). ValueError for a point that is not 3 finite numbers."""
        return self._core.water([float(v) for v in point])

    def sediment(self):
        """The silt the robots' thrusters raised now (docs/vision.md "Silt-out"), one row per puff: ``centre`` (N x 3)
        world frame [m], ``sigma`` (N) its spread [m], ``strength`` (N) Q, the integral of its extra scattering
        coefficient over space [m^2], ``floor_z`` (N) the floor under the place it was raised [m]. N = 0 in clear
        water (always, when the world's sediment is off)."""
        return self._core.sediment()

    sediment_params = property(
        lambda self: self._core.sediment_params,
        doc="The world file's sediment block in force (docs/worlds.md): enabled, settling_speed [m/s], raise "
        "[m^2/(N s)], reach [m], puff_size [m], diffusivity [m^2/s], interval [s], max_puffs.",
    )

    mapping = property(lambda self: self._core.mapping, doc="Whether this World maps (made with mapping=...).")

    def map_stats(self):
        """The in-process map's counters, as the mapper node's ~stats: clouds_received, clouds_inserted,
        clouds_dropped, pending (waiting for the next tf sample), points_inserted, occupied_leaves, memory_bytes,
        and sources ("<robot>/<sensor>" of every mapped sensor). RuntimeError without mapping."""
        return self._core.map_stats()

    def map_settings(self):
        """The mapper's parameters in force, by name (docs/mapping.md "In-process"); RuntimeError without mapping."""
        return self._core.map_settings()

    def occupied_voxels(self):
        """The map's occupied leaves (pruned: a leaf may be larger than the resolution), N x 4 numpy: centre x, y, z
        and edge [m] in the map's frame (the world's). RuntimeError without mapping."""
        return self._core.occupied_voxels()

    def save_map(self, path):
        """Write the map as OctoMap's binary .bt to `path` (through a temporary file renamed into place), as the
        mapper node's ~save_map; returns the occupied leaves. RuntimeError without mapping or when writing fails."""
        return self._core.save_map(os.fspath(path))

    def clear_map(self):
        """Empty the map (the mapper node's ~reset); the world goes on. RuntimeError without mapping."""
        self._core.clear_map()

    time = property(lambda self: self._core.time, doc="Simulation time [s].")
    step_count = property(lambda self: self._core.step_count, doc="Physics steps since t = 0.")
    dt = property(lambda self: self._core.dt, doc="Physics step [s].")
    seed = property(lambda self: self._core.seed, doc="The seed of the last reset (or the first).")
    visibility = property(lambda self: self._core.visibility, doc="Water visibility level in force.")
    sensors = property(lambda self: self._core.sensors, doc="The sensor families that run: all, none or a list.")
    current = property(lambda self: self._core.current, doc="Water current now, world frame [m/s] (numpy).")

"""The common part of the UX-1's Gymnasium environments (docs/gym.md): the engine in-process (unexmin.core), one
robot, a control step of 0.1 s, observations from the robot's sensors, actions as a body wrench through the
thesis allocation or as thrusts, domain randomisation and Gymnasium's seeding. A task (station keeping, gallery
transit, wall following) adds its spawn pose, its features, its reward and its ends.
"""

import abc
import os
import shutil
import tempfile
import weakref
import xml.etree.ElementTree as ET

import gymnasium
import numpy as np
import yaml

from unexmin.control.allocation import DEFAULT_MAX_THRUST, ThrusterAllocator
from unexmin.gym import randomisation

ROBOT = "UX_1"
#: [N, N, N, N m] the body wrench of an action of 1 on X, Y, Z and N (the allocation saturates beyond).
WRENCH_SCALE = np.array([40.0, 40.0, 40.0, 10.0])
#: [N] the thrust of an action of 1 on a thruster (the simulated thrusters' command range).
THRUST_SCALE = DEFAULT_MAX_THRUST
PRIVILEGED = 16  # position 3, orientation 4, body linear and angular velocity 3 + 3, current 3
_descriptions = {}  # robot description text by (file, name): xacro runs once per process


def description(name=ROBOT):
    """The robot's URDF text (urdf/ux1.urdf.xacro expanded by xacro, as the launch files do), cached."""
    from unexmin.description import ROBOT_FILE, expand

    key = (str(ROBOT_FILE), name)
    if key not in _descriptions:
        _descriptions[key] = expand(ROBOT_FILE, name)
    return _descriptions[key]


def camera_description(urdf, camera, width, height):
    """`urdf` keeping only camera sensor `camera` among the cameras, at width x height pixels."""
    root = ET.fromstring(urdf)
    block = root.find("unexmin")
    kept = False
    for s in list(block.iter("sensor")):
        if s.get("type") != "camera":
            continue
        if s.get("name") != camera:
            block.remove(s)
            continue
        kept = True
        for p in s.iter("param"):
            if p.get("name") == "width":
                p.set("value", str(int(width)))
            elif p.get("name") == "height":
                p.set("value", str(int(height)))
    if not kept:
        raise ValueError(f"camera = {camera!r}: the robot description has no camera of that name")
    return ET.tostring(root, encoding="unicode")


def world_with_spawn(world, xyz, rpy, folder):
    """A copy of world file `world` (a shipped name or a path) in `folder`, its meshes linked, with the first robot
    spawned at xyz [m], rpy [rad]; its path."""
    from unexmin.worlds.files import link_meshes, world_path
    from unexmin.worlds.schema import read_world

    path = world_path(world)
    data = read_world(path)
    link_meshes(data.get("meshes") or [], os.path.dirname(os.path.abspath(path)), folder)
    data["robots"][0]["xyz"] = [float(v) for v in xyz]
    data["robots"][0]["rpy"] = [float(v) for v in rpy]
    out = os.path.join(folder, os.path.basename(path))
    with open(out, "w") as f:
        f.write("# Written by unexmin.gym: the world with the environment's spawn pose (docs/gym.md)\n")
        yaml.safe_dump(data, f, sort_keys=False)
    read_world(out)
    return out


def yaw_of_quaternion(q):
    """Yaw [rad] of a quaternion (x, y, z, w)."""
    x, y, z, w = q
    return float(np.arctan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z)))


def to_body_yaw(vector, yaw):
    """A world-frame vector in the yaw-only body frame (x forward, y left, z up)."""
    c, s = np.cos(yaw), np.sin(yaw)
    return np.array([c * vector[0] + s * vector[1], -s * vector[0] + c * vector[1], vector[2]])


class UnexminEnv(gymnasium.Env, abc.ABC):
    """One UX-1 in a world of the engine, stepped 0.1 s of sim time per env step (docs/gym.md).

    observation: "sensors" (IMU, DVL, pressure depth, M3 sectors, the task's features) or "privileged" (those and
    the ground-truth state and current); action: "wrench" (X, Y, Z, N through the thesis allocation) or "thrusts"
    (the 8 thrusters); images: add camera `camera`'s image (visual mode, width x height); randomise: domain
    randomisation spec (unexmin.gym.randomisation); m3_sectors: M3 beams folded into this many sectors (nearest
    return each) up to m3_max_range [m]; ray_caster_threads: the engine's (1: one core per environment).
    """

    metadata = {"render_modes": []}
    CONTROL_DT = 0.1  # [s] sim time per env step
    WORLD = "tank"
    SPAWN = None  # (xyz, rpy) of the robot, None: the world file's
    MAX_SECONDS = 60.0  # [s] episode length (truncation)
    CURRENT = None  # (speed [m/s], horizontal angle [rad], vertical angle [rad]) of the task, None: the world's
    TASK_FEATURES = ()  # names of the task's features (docs/gym.md)

    def __init__(
        self,
        observation="sensors",
        action="wrench",
        images=False,
        camera="camera_0",
        image_size=(64, 48),
        randomise=None,
        m3_sectors=16,
        m3_max_range=10.0,
        ray_caster_threads=1,
    ):
        if observation not in ("sensors", "privileged"):
            raise ValueError(f"observation = {observation!r}: expected 'sensors' or 'privileged'")
        if action not in ("wrench", "thrusts"):
            raise ValueError(f"action = {action!r}: expected 'wrench' or 'thrusts'")
        if isinstance(m3_sectors, bool) or int(m3_sectors) != m3_sectors or not 1 <= m3_sectors <= 256:
            raise ValueError(f"m3_sectors = {m3_sectors!r}: expected a whole number in [1, 256]")
        if not (isinstance(m3_max_range, (int, float)) and m3_max_range > 0 and np.isfinite(m3_max_range)):
            raise ValueError(f"m3_max_range = {m3_max_range!r}: expected a finite range > 0 m")
        if images and (len(image_size) != 2 or min(image_size) < 8):
            raise ValueError(f"image_size = {image_size!r}: expected (width, height), each >= 8 pixels")
        self.observation_kind, self.action_kind = observation, action
        self.images, self.camera, self.image_size = bool(images), camera, tuple(int(v) for v in image_size)
        self.m3_sectors, self.m3_max_range = int(m3_sectors), float(m3_max_range)
        self.ray_caster_threads = int(ray_caster_threads)
        self.randomise = randomisation.check(randomise)
        self._folder = tempfile.mkdtemp(prefix="unexmin_gym_")
        self._cleanup = weakref.finalize(self, shutil.rmtree, self._folder, True)
        self.world_file = self._world_file()
        from unexmin.worlds.schema import read_world

        data = read_world(self.world_file)
        water = data.get("water", {})
        self._rho_g = float(water.get("density", 1000.0)) * float(data.get("gravity", 9.81))
        self._p_atm = float(data.get("atmospheric_pressure", 101325.0))
        self.allocator = ThrusterAllocator()
        self.world = None
        self._key = None
        self._build(self._world_key({}))
        n = 6 + 5 + 1 + self.m3_sectors + len(self.TASK_FEATURES)
        n += PRIVILEGED if observation == "privileged" else 0
        vector = gymnasium.spaces.Box(-np.inf, np.inf, (n,), np.float32)
        if self.images:
            w, h = self.image_size
            image = gymnasium.spaces.Box(0, 255, (h, w, 3), np.uint8)
            self.observation_space = gymnasium.spaces.Dict({"vector": vector, "image": image})
        else:
            self.observation_space = vector
        k = 4 if action == "wrench" else self.robot.thruster_count
        self.action_space = gymnasium.spaces.Box(-1.0, 1.0, (k,), np.float32)
        self.parameters = {}

    # -- the world ----------------------------------------------------------------------------------
    def _world_file(self):
        if self.SPAWN is None:
            from unexmin.worlds.files import world_path

            return world_path(self.WORLD)
        return world_with_spawn(self.WORLD, *self.SPAWN, self._folder)

    def _world_key(self, values):
        return (values.get("visibility", ""), values.get("buoyancy_offset", 0.0), values.get("damping_scale", 1.0))

    def _build(self, key):
        """(Re)build the engine's World for (visibility, buoyancy offset, damping scale) when it differs."""
        if key == self._key:
            return
        from unexmin.core import World

        visibility, offset, scale = key
        urdf = randomisation.patched_description(description(ROBOT), offset, scale)
        sensors = "imu,dvl,pressure,m3"
        if self.images:
            urdf = camera_description(urdf, self.camera, *self.image_size)
            sensors += ",camera"
        self.world = None  # the old one goes first: one engine world in memory at a time
        self.world = World(
            self.world_file,
            robots=1,
            seed=0,
            sensors=sensors,
            visibility=visibility,
            mode="visual" if self.images else "operational",
            descriptions={ROBOT: urdf},
            ray_caster_threads=self.ray_caster_threads,
        )
        self.robot = self.world.robot(ROBOT)
        self.steps_per_action = round(self.CONTROL_DT / self.world.dt)
        self._key = key
        angles = self.robot.sample("m3")["beam_angles"]
        order = np.argsort(angles)
        self._m3_order = order
        self._m3_bounds = np.linspace(0, len(angles), self.m3_sectors + 1).astype(int)[:-1]
        sorted_angles = angles[order]
        self.m3_sector_angles = np.array(
            [sorted_angles[a:b].mean() for a, b in zip(self._m3_bounds, list(self._m3_bounds[1:]) + [len(angles)])]
        )

    # -- Gymnasium --------------------------------------------------------------------------------
    def reset(self, *, seed=None, options=None):
        """A new episode: the randomised parameters drawn from np_random (seeded by `seed` as Gymnasium defines
        it), the world back to t = 0 with a drawn noise seed, the task's start. Returns (observation, info)."""
        super().reset(seed=seed)
        values = randomisation.draw(self.randomise, self.np_random)
        self._build(self._world_key(values))
        self.world.reset(int(self.np_random.integers(2**31 - 1)))
        speed, angle, vertical = self.CURRENT or (None, None, None)
        if any(k in values for k in ("current_speed", "current_angle", "current_vertical_angle")) or self.CURRENT:
            speed = values.get("current_speed", speed if speed is not None else 0.0)
            angle = values.get("current_angle", angle if angle is not None else 0.0)
            vertical = values.get("current_vertical_angle", vertical if vertical is not None else 0.0)
            self.world.set_current(speed, angle, vertical)
        self.parameters = values
        self._command = np.zeros(self.action_space.shape, np.float32)
        state = self.robot.state()
        self._start(state)
        features, _, _, info = self._task(state, self._command)
        return self._observation(state, features), self._info(state, info)

    def step(self, action):
        """Apply `action` for 0.1 s of sim time; (observation, reward, terminated, truncated, info)."""
        a = np.clip(np.asarray(action, dtype=np.float64).reshape(self.action_space.shape), -1.0, 1.0)
        if not np.all(np.isfinite(a)):
            raise ValueError(f"action = {action!r}: expected finite values in [-1, 1]")
        if self.action_kind == "wrench":
            X, Y, Z, N = a * WRENCH_SCALE
            thrusts = self.allocator.allocate([X, Y, Z, 0.0, 0.0, N])[0]
        else:
            thrusts = a * THRUST_SCALE
        self.robot.thrusts(thrusts)
        self._command = a.astype(np.float32)
        self.world.step(self.steps_per_action)
        state = self.robot.state()
        features, reward, terminated, info = self._task(state, a)
        truncated = not terminated and self.world.time >= self.MAX_SECONDS - 1e-9
        return (
            self._observation(state, features),
            float(reward),
            bool(terminated),
            bool(truncated),
            self._info(state, info),
        )

    def close(self):
        self.world = None
        self._cleanup()

    # -- observation ----------------------------------------------------------------------------------
    def touching(self):
        """True when the hull touches the world's meshes (the engine's contact points after the last step)."""
        return self.robot.contacts()["depth"].size > 0

    def m3_sectors_of(self, ranges):
        """The M3 ranges [m] folded into sectors: the nearest return of each, no return = m3_max_range."""
        r = np.asarray(ranges, dtype=np.float64)[self._m3_order]
        r = np.where(np.isposinf(r), self.m3_max_range, np.where(np.isneginf(r), 0.0, r))
        return np.minimum(np.minimum.reduceat(r, self._m3_bounds), self.m3_max_range)

    def _observation(self, state, features):
        imu, dvl = self.robot.sample("imu"), self.robot.sample("dvl")
        pressure, m3 = self.robot.sample("pressure"), self.robot.sample("m3")
        parts = []
        parts.append(imu["specific_force"] if imu["time"] >= 0 else np.zeros(3))
        parts.append(imu["angular_velocity"] if imu["time"] >= 0 else np.zeros(3))
        lock = dvl["time"] >= 0 and bool(dvl["bottom_lock"])
        parts.append(dvl["velocity"] if lock else np.zeros(3))
        parts.append([1.0 if lock else 0.0, dvl["altitude"] if lock and np.isfinite(dvl["altitude"]) else 0.0])
        parts.append([(pressure["pressure"] - self._p_atm) / self._rho_g if pressure["time"] >= 0 else 0.0])
        if m3["time"] >= 0:
            parts.append(self.m3_sectors_of(m3["ranges"]))
        else:
            parts.append(np.full(self.m3_sectors, self.m3_max_range))
        parts.append(features)
        if self.observation_kind == "privileged":
            parts += [
                state["position"],
                state["orientation"],
                state["linear_velocity"],
                state["angular_velocity"],
                self.world.current,
            ]
        vector = np.concatenate([np.asarray(p, dtype=np.float64).ravel() for p in parts]).astype(np.float32)
        if not self.images:
            return vector
        frame = self.robot.sample(self.camera)
        w, h = self.image_size
        image = frame["image"].copy() if frame.get("rendered") else np.zeros((h, w, 3), np.uint8)
        return {"vector": vector, "image": image}

    def _info(self, state, extra):
        info = {"time": self.world.time, "position": state["position"].copy(), "parameters": dict(self.parameters)}
        info.update(extra)
        return info

    # -- the task ----------------------------------------------------------------------------------------
    @abc.abstractmethod
    def _start(self, state):
        """The task's start of an episode (targets, counters), given the state at t = 0."""

    @abc.abstractmethod
    def _task(self, state, action):
        """(features, reward, terminated, info) of the task after a step (or at the start)."""

"""A PID baseline per environment, acting on the observation only (docs/gym.md, "Baselines").

    env = gymnasium.make("unexmin/StationKeeping-v0")
    policy = baseline_for(env)
    obs, info = env.reset(seed=0); policy.reset()
    obs, reward, terminated, truncated, info = env.step(policy(obs))

Actions are body wrenches (the environments' default action="wrench"), normalised by env.WRENCH_SCALE.
"""

import math

import numpy as np

from unexmin.gym.env import WRENCH_SCALE


class _Features:
    """Index of the task's features and the M3 sectors in an environment's observation vector."""

    def __init__(self, env):
        base = env.unwrapped
        self.env = base
        self.m3 = slice(12, 12 + base.m3_sectors)
        start = 12 + base.m3_sectors
        self.index = {name: start + i for i, name in enumerate(base.TASK_FEATURES)}

    def __call__(self, obs, *names):
        vector = obs["vector"] if isinstance(obs, dict) else obs
        return np.array([vector[self.index[n]] for n in names], dtype=np.float64)


class WaypointPid:
    """PID on the target's offset in the body (yaw) frame, the derivative by finite differences over the 0.1 s
    control step; PD on the yaw error. For StationKeeping (the station) and GalleryTransit (the next route point,
    capped at `speed_limit` m of offset so the robot cruises)."""

    def __init__(
        self,
        env,
        target=("station_x", "station_y", "station_z"),
        kp=40.0,
        ki=5.0,
        kd=140.0,
        yaw_kp=10.0,
        yaw_kd=15.0,
        offset_limit=math.inf,
    ):
        self.features, self.target, self.dt = _Features(env), target, env.unwrapped.CONTROL_DT
        self.kp, self.ki, self.kd, self.yaw_kp, self.yaw_kd = kp, ki, kd, yaw_kp, yaw_kd
        self.offset_limit = offset_limit
        self.reset()

    def reset(self):
        self.integral = np.zeros(3)
        self.previous = None

    def __call__(self, obs):
        e = self.features(obs, *self.target)
        norm = np.linalg.norm(e)
        if norm > self.offset_limit:
            e = e * (self.offset_limit / norm)
        yaw_error = self.features(obs, "yaw_error")[0]
        if self.previous is None:
            self.previous = (e, yaw_error)
        de = (e - self.previous[0]) / self.dt
        dyaw = math.remainder(yaw_error - self.previous[1], 2 * math.pi) / self.dt
        self.previous = (e, yaw_error)
        self.integral = np.clip(self.integral + e * self.dt, -2.0, 2.0)
        force = self.kp * e + self.ki * self.integral + self.kd * de
        moment = self.yaw_kp * yaw_error + self.yaw_kd * dyaw
        return np.clip(np.array([*force, moment]) / WRENCH_SCALE, -1.0, 1.0).astype(np.float32)


class WallPid:
    """Wall following by sonar: a line fitted to the M3 sectors on the left (25..60 degrees; the points of a wall
    ahead left out), its distance held by PD on the lateral force, its angle by PD on the yaw moment, a constant
    surge force."""

    INLIER = 0.05  # [m] a sector's point is on the wall's line within this distance
    SMOOTHING = 0.7  # weight of the previous derivative in its low-pass filter, per 0.1 s step

    def __init__(self, env, surge=6.0, kp=30.0, kd=60.0, yaw_kp=8.0, yaw_kd=15.0):
        self.features, self.dt = _Features(env), env.unwrapped.CONTROL_DT
        angles = env.unwrapped.m3_sector_angles
        self.left = (angles > math.radians(25.0)) & (angles < math.radians(60.0))
        self.angles = angles[self.left]
        self.max_range = env.unwrapped.m3_max_range
        self.surge, self.kp, self.kd, self.yaw_kp, self.yaw_kd = surge, kp, kd, yaw_kp, yaw_kd
        self.reset()

    def reset(self):
        self.previous = None
        self.rates = np.zeros(2)

    def wall(self, obs):
        """(distance [m], angle [rad]) of the wall on the left from the M3 sectors, or None when unseen."""
        vector = obs["vector"] if isinstance(obs, dict) else obs
        r = np.asarray(vector[self.features.m3], dtype=np.float64)[self.left]  # the fan is level (m3_rpy 0 0 0)
        seen = r < self.max_range - 1e-6
        if seen.sum() < 2:
            return None
        x, y = r[seen] * np.cos(self.angles[seen]), r[seen] * np.sin(self.angles[seen])
        # the line within 45 degrees of the heading through the pair of points that most others agree with (within
        # INLIER m): a wall ahead (the end of a corridor) returns points of a line across, which are left out; then
        # least squares on the agreeing points
        best = None
        for i in range(len(x)):
            for j in range(i + 1, len(x)):
                if abs(y[j] - y[i]) > abs(x[j] - x[i]):
                    continue
                n = np.array([y[i] - y[j], x[j] - x[i]])
                n /= np.linalg.norm(n)
                inliers = np.abs((x - x[i]) * n[0] + (y - y[i]) * n[1]) < self.INLIER
                if best is None or inliers.sum() > best.sum():
                    best = inliers
        if best is None or best.sum() < 2:
            return None
        b, a = np.polyfit(x[best], y[best], 1)
        return a / math.sqrt(1.0 + b * b), math.atan(b)

    def __call__(self, obs):
        set_distance = self.features(obs, "distance_set")[0]
        wall = self.wall(obs)
        if wall is None:
            return np.array([self.surge / WRENCH_SCALE[0], 0.0, 0.0, 0.0], np.float32)
        distance, angle = wall
        error = distance - set_distance  # > 0: too far, move left (+y)
        if self.previous is None:
            self.previous = (error, angle)
        # the derivatives low-passed (a sonar estimate jumps when a sector's nearest return moves to another beam)
        f = self.SMOOTHING
        self.rates = (
            f * self.rates + (1.0 - f) * np.array([error - self.previous[0], angle - self.previous[1]]) / self.dt
        )
        self.previous = (error, angle)
        lateral = self.kp * error + self.kd * self.rates[0]
        moment = self.yaw_kp * angle + self.yaw_kd * self.rates[1]
        return np.clip(np.array([self.surge, lateral, 0.0, moment]) / WRENCH_SCALE, -1.0, 1.0).astype(np.float32)


def baseline_for(env):
    """The PID baseline of environment `env` (by its class)."""
    from unexmin.gym.tasks import GalleryTransitEnv, StationKeepingEnv, WallFollowingEnv

    base = env.unwrapped
    if isinstance(base, StationKeepingEnv):
        return WaypointPid(env)
    if isinstance(base, GalleryTransitEnv):
        return WaypointPid(env, target=("next_x", "next_y", "next_z"), kp=25.0, ki=0.0, kd=100.0, offset_limit=1.0)
    if isinstance(base, WallFollowingEnv):
        return WallPid(env)
    raise TypeError(f"no baseline for {type(base).__name__}")


def run_episode(env, policy, seed=0):
    """One episode of `policy` from reset(seed): (return, steps, the last info)."""
    obs, info = env.reset(seed=seed)
    policy.reset()
    total, steps = 0.0, 0
    while True:
        obs, reward, terminated, truncated, info = env.step(policy(obs))
        total += reward
        steps += 1
        if terminated or truncated:
            return total, steps, info

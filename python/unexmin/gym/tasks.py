"""The UX-1's jobs as Gymnasium environments (docs/gym.md has each one's features, reward and ends).

- StationKeepingEnv: hold the spawn pose in the tank against a 0.2 m/s current.
- GalleryTransitEnv: fly the mine's first-level gallery to a waypoint without touching the walls.
- WallFollowingEnv: follow the tank's long wall at a set distance, measured by the M3 sonar.
"""

import math

import numpy as np

from unexmin.gym.env import UnexminEnv, to_body_yaw, yaw_of_quaternion

TOUCH_PENALTY = 10.0  # reward lost when the hull touches the world (the episode ends)


def action_cost(action):
    """0.01 |a|^2: the effort term of every task's reward."""
    return 0.01 * float(np.dot(action, action))


class StationKeepingEnv(UnexminEnv):
    """Hold the spawn position and heading in the tank (UX_1's spawn of worlds/tank.world) against a current of
    0.2 m/s along +x (the `current_*` randomisation parameters replace it)."""

    WORLD = "tank"
    CURRENT = (0.2, 0.0, 0.0)
    MAX_SECONDS = 60.0
    LOST = 1.0  # [m] from the station: the episode ends
    TASK_FEATURES = ("station_x", "station_y", "station_z", "yaw_error")

    def _start(self, state):
        self.station = state["position"].copy()
        self.heading = yaw_of_quaternion(state["orientation"])

    def _task(self, state, action):
        yaw = yaw_of_quaternion(state["orientation"])
        error = to_body_yaw(self.station - state["position"], yaw)
        yaw_error = math.remainder(self.heading - yaw, 2 * math.pi)
        distance = float(np.linalg.norm(error))
        touching = self.touching()
        reward = -(distance + 0.1 * abs(yaw_error) + action_cost(action))
        terminated = distance > self.LOST or touching
        if touching:
            reward -= TOUCH_PENALTY
        info = {"distance": distance, "yaw_error": yaw_error, "touching": touching}
        return np.array([*error, yaw_error]), reward, terminated, info


class GalleryTransitEnv(UnexminEnv):
    """From the start of the mine's first-level gallery (4 m from the entry shaft's axis) to the waypoint `gallery`
    m from that axis along it (default 20: 16 m of route), without touching the walls. The route is the gallery's
    centreline every 4 m (the mine mission's waypoints); the features give the next route point."""

    WORLD = "mine"
    MAX_SECONDS = 120.0
    REACHED = 1.0  # [m] a route point is passed within this distance
    GOAL = 0.5  # [m] the goal is reached within this distance
    GOAL_REWARD = 10.0
    TASK_FEATURES = ("next_x", "next_y", "next_z", "yaw_error", "remaining")

    def __init__(self, gallery=20.0, **kwargs):
        from unexmin.missions.waypoints import waypoints

        if not (isinstance(gallery, (int, float)) and 8.0 <= gallery <= 60.0):
            raise ValueError(f"gallery = {gallery!r}: expected a length in [8, 60] m")
        path = np.array(waypoints(float(gallery)))[2:]  # the gallery's points (the shaft's are left out)
        if len(path) < 2:
            raise ValueError(f"gallery = {gallery}: the route has fewer than two points")
        self.route = path[1:]
        heading = math.atan2(*(path[1] - path[0])[1::-1])
        self.SPAWN = (tuple(path[0]), (0.0, 0.0, heading))
        super().__init__(**kwargs)

    def _remaining(self, position):
        target = self.route[self.next]
        rest = np.linalg.norm(np.diff(self.route[self.next :], axis=0), axis=1).sum()
        return float(np.linalg.norm(target - position) + rest)

    def _start(self, state):
        self.next = 0
        self.previous = self._remaining(state["position"])

    def _task(self, state, action):
        p = state["position"]
        while self.next < len(self.route) - 1 and np.linalg.norm(self.route[self.next] - p) < self.REACHED:
            self.next += 1
        target = self.route[self.next]
        yaw = yaw_of_quaternion(state["orientation"])
        error = to_body_yaw(target - p, yaw)
        yaw_error = math.remainder(math.atan2(error[1], error[0]), 2 * math.pi)
        remaining = self._remaining(p)
        touching = self.touching()
        reached = self.next == len(self.route) - 1 and np.linalg.norm(target - p) < self.GOAL
        reward = (self.previous - remaining) - action_cost(action)
        self.previous = remaining
        if touching:
            reward -= TOUCH_PENALTY
        if reached:
            reward += self.GOAL_REWARD
        info = {"remaining": remaining, "route_index": self.next, "touching": touching, "reached": bool(reached)}
        return np.array([*error, yaw_error, remaining]), reward, bool(touching or reached), info


class WallFollowingEnv(UnexminEnv):
    """Follow the tank's wall at y = +2 m (worlds/tank.world: interior 6 m x 4 m, centred) at `distance` m from the
    hull's centre (default 1.0, in [0.6, 1.6]), along +x from x = -2 m to x = +1.5 m (1.5 m before the end wall),
    1 m deep. The M3 sonar's level fan (120 degrees wide) sees the wall on the robot's left."""

    WORLD = "tank"
    SPAWN_X, END_X, WALL_Y, DEPTH = -2.0, 1.5, 2.0, 1.0  # [m]
    MAX_SECONDS = 60.0
    LOST = 0.6  # [m] off the set distance: the episode ends
    END_REWARD = 5.0
    TASK_FEATURES = ("distance_set",)

    def __init__(self, distance=1.0, **kwargs):
        if not (isinstance(distance, (int, float)) and 0.6 <= distance <= 1.6):
            raise ValueError(f"distance = {distance!r}: expected a distance in [0.6, 1.6] m")
        self.distance = float(distance)
        self.SPAWN = ((self.SPAWN_X, self.WALL_Y - self.distance, -self.DEPTH), (0.0, 0.0, 0.0))
        super().__init__(**kwargs)

    def _start(self, state):
        self.previous_x = float(state["position"][0])

    def _task(self, state, action):
        x, y = float(state["position"][0]), float(state["position"][1])
        off = (self.WALL_Y - y) - self.distance
        touching = self.touching()
        lost = abs(off) > self.LOST
        done = x >= self.END_X
        reward = (x - self.previous_x) - 0.1 * abs(off) - action_cost(action)
        self.previous_x = x
        if touching or lost:
            reward -= TOUCH_PENALTY
        if done:
            reward += self.END_REWARD
        info = {"distance_error": off, "touching": touching, "lost": lost, "reached": done}
        return np.array([self.distance]), reward, bool(touching or lost or done), info

"""One robot of the explorer's team: its mode, its path and the reference that runs along it, what it spent and
what it flew."""

import math
from dataclasses import dataclass, field

import numpy as np

from unexmin.missions.explore.navigation import DeadReckoning


@dataclass
class Agent:
    """One robot's state in the loop."""

    name: str
    handle: object
    imu: object  # Collector of the IMU
    nav: DeadReckoning
    home: np.ndarray
    mode: str = "explore"  # explore, return, home
    why: str = ""
    path: np.ndarray = None  # [m] points of the path followed
    s: float = 0.0  # [m] the reference's arc length along the path
    goal: np.ndarray = None
    hold: np.ndarray = None  # [m] where the robot waits without a path
    idle: int = 0  # replans in a row without a goal
    yaw_ref: float = 0.0
    energy: float = 0.0  # [J]
    flown: float = 0.0  # [m] true distance flown
    last_true: np.ndarray = None
    last_dvl: float = -1.0
    progress_mark: tuple = (0.0, 0.0)  # (sim time, arc length) of the last advance
    travelled_est: float = 0.0  # [m] estimated distance flown
    touching: bool = False
    min_clearance: float = math.inf  # [m] true clearance of the hull's centre to the rock
    home_m: float = 0.0  # [m] last path length home
    rows: list = field(default_factory=list)

    def set_path(self, points, t):
        self.hold = None
        pts = np.vstack([self.nav.p[None], np.asarray(points, float)])
        keep = np.concatenate([[True], np.linalg.norm(np.diff(pts, axis=0), axis=1) > 1e-6])
        self.path = pts[keep]
        self.s = 0.0
        self.progress_mark = (t, 0.0)

    def reference(self, speed):
        """(point [m], velocity [m/s]) of the reference at arc length s."""
        if self.path is None or len(self.path) < 2:
            return (self.nav.p.copy() if self.path is None else self.path[-1]), np.zeros(3)
        seg = np.diff(self.path, axis=0)
        lengths = np.linalg.norm(seg, axis=1)
        ends = np.cumsum(lengths)
        s = min(self.s, ends[-1])
        k = min(int(np.searchsorted(ends, s, side="right")), len(seg) - 1)
        start = ends[k] - lengths[k]
        f = (s - start) / lengths[k] if lengths[k] > 0 else 1.0
        point = self.path[k] + f * seg[k]
        left = ends[-1] - s
        velocity = seg[k] / max(lengths[k], 1e-9) * speed * min(1.0, left / 0.5)
        return point, velocity

    def path_length(self):
        return 0.0 if self.path is None else float(np.linalg.norm(np.diff(self.path, axis=0), axis=1).sum())

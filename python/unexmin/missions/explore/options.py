"""What the explorer is told (docs/explore.md): its options and the default box it explores."""

from dataclasses import dataclass

import numpy as np


@dataclass
class ExploreOptions:
    robots: int = 1  # how many of the world's robots explore (1..3)
    speed: float = 0.3  # [m/s] along the path
    yaw_rate: float = 0.2  # [rad/s] the robot turns all the time (its sensors sweep the walls, floor and roof)
    control_dt: float = 0.2  # [s] of sim time between controller updates
    map_period: float = 5.0  # [s] of sim time between map reads (and replanning)
    cell_voxels: int = 4  # grid cell edge in map voxels (0.4 m at the default resolution)
    resolution: float = 0.1  # [m] the mapper's voxel edge
    bounds: tuple = None  # ((x, y, z), (x, y, z)) [m] the box explored; None: around the start (default_bounds)
    goal_tolerance: float = 0.8  # [m] a goal is reached within this
    home_tolerance: float = 0.5  # [m] the start is reached within this (estimated position)
    hold_distance: float = 0.4  # [m] the reference waits while the robot is farther than this from it
    stuck_s: float = 20.0  # [s] a robot that has not advanced stuck_m along its path in this time is stuck
    stuck_m: float = 0.3  # [m]
    sonar_guard: float = 0.45  # [m] an M3 echo this near the hull ahead of the motion stops the robot
    robot_clearance: float = 1.2  # [m] between robots' centres in their plans
    snapshot: float = 0.0  # [s] of sim time between saved maps (snapshots/, scored at the end); 0: none
    idle_replans: int = 3  # replans in a row without a goal before the robot calls the box explored
    grace_s: float = 120.0  # [s] past the time budget before the run is stopped (a robot not home is reported)

    def check(self):
        if self.robots not in (1, 2, 3):
            raise ValueError(f"explore option robots = {self.robots}: expected 1, 2 or 3")
        for name in ("speed", "control_dt", "map_period", "resolution", "goal_tolerance", "home_tolerance"):
            if not getattr(self, name) > 0:
                raise ValueError(f"explore option {name} = {getattr(self, name)}: expected > 0")
        for name in ("yaw_rate", "snapshot", "sonar_guard", "grace_s"):
            if not getattr(self, name) >= 0:
                raise ValueError(f"explore option {name} = {getattr(self, name)}: expected >= 0")
        if self.cell_voxels not in (1, 2, 4, 8):
            raise ValueError(f"explore option cell_voxels = {self.cell_voxels}: expected 1, 2, 4 or 8")


def default_bounds(start, world_box, surface_z, reach=(40.0, 15.0, 25.0)):
    """A box around the start [m]: reach metres along x and y either way and down, clipped to the world's box
    and to the water surface."""
    start = np.asarray(start, float)
    lo = np.maximum(start - reach, world_box[0])
    hi = np.minimum(start + (reach[0], reach[1], 0.5), world_box[1])
    hi[2] = min(max(hi[2], start[2] + 0.5), surface_z)
    return lo, hi

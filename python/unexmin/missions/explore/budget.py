"""The explorer's budget (no ROS): sim time and energy, and when to turn for home.

Energy is the thrusters' mechanical work on the robot, E = ∫ (|F · v| + |N ω_z|) dt [J]: F the allocated body
force [N], v the DVL's body velocity [m/s], N the allocated yaw moment [N m], ω_z the IMU's yaw rate [rad/s] (what
the robot itself measures; hovering costs nothing in this measure).
"""

import math
from dataclasses import dataclass


@dataclass
class Budget:
    time_s: float = 600.0  # [s] of sim time from the start
    energy_j: float = math.inf  # [J]
    reserve: float = 1.5  # the way home is costed at this many times its estimate
    margin_s: float = 20.0  # [s] kept over the reserve (turning, settling at the start)

    def check(self):
        if not self.time_s > 0:
            raise ValueError(f"explore budget time_s = {self.time_s}: expected > 0 s")
        if not self.energy_j > 0:
            raise ValueError(f"explore budget energy_j = {self.energy_j}: expected > 0 J")
        if not self.reserve >= 1:
            raise ValueError(f"explore budget reserve = {self.reserve}: expected >= 1")

    def must_return(self, t, energy, home_m, speed, joules_per_m):
        """(True, why) when the way home (home_m [m] at speed [m/s], joules_per_m [J/m]) no longer fits in what
        is left of the budget at time t [s] having spent `energy` [J]."""
        need_s = self.reserve * home_m / speed + self.margin_s
        if t + need_s >= self.time_s:
            return True, f"time: {self.time_s - t:.0f} s left, {need_s:.0f} s needed to return"
        need_j = self.reserve * home_m * joules_per_m
        if math.isfinite(self.energy_j) and energy + need_j >= self.energy_j:
            return True, f"energy: {self.energy_j - energy:.0f} J left, {need_j:.0f} J needed to return"
        return False, ""


def power(force, velocity, moment_z, yaw_rate):
    """Mechanical power [W] of an allocated body force [N] and yaw moment [N m] at a body velocity [m/s] and yaw
    rate [rad/s]."""
    return abs(sum(f * v for f, v in zip(force, velocity))) + abs(moment_z * yaw_rate)

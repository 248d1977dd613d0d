"""Allocation from a vehicle's own description: body wrench -> thruster commands and fin angles. Pure maths, no ROS.

The description's actuators (unexmin.description; their inverse families in unexmin.control.actuators) give the
configuration matrix B (6 x n, rows X Y Z K M N: body force [N] and moment about the body origin [N m]; body frame
x forward, y left, z up):

- a thruster's column is its wrench per newton of thrust, [d; p x d] (d its unit axis, p its position);
- a movable fin's column is its wrench per radian of fin angle at the current surge speed u [m/s]: the
  linearised lift 1/2 rho u^2 A C_L' (d alpha / d delta) [l; p x l], l = e x s the lift direction (e the direction
  the water passes the fin, s its span), as the simulator computes it (docs/hydrodynamics.md, "Fins"). Below
  `fin_min_speed` (and going backwards) a fin has no column: the fins are left at 0. Fixed surfaces (limits 0, 0)
  are not actuators.

Only the degrees of freedom in `dofs` are allocated (an underactuated vehicle such as a torpedo AUV cannot choose its
sway and heave forces apart from its yaw and pitch moments): with S the rows of B for those degrees of freedom, the
actuator effort is the least-norm solution x = pinv(S) tau_S, so S x = tau_S exactly whenever S has full row rank
(the ROV's eight thrusters: every one of the six).

Saturation: thrusts are limited by their thrust range and by what the command range can give; when a thrust is
beyond its limit, every thrust is multiplied by the same factor (so the thrusters' wrench keeps its direction, as the
UX-1's allocator does). Fin angles are clamped each to its limits (a fin's authority changes with the speed; scaling
the propeller with it would stall the vehicle). Thrusts become commands through the inverse of each thruster's
conversion family.
"""

import math

import numpy as np

from unexmin.control.actuators import conversion_of, lift_slope_of
from unexmin.control.allocation import DOF, AllocationError
from unexmin.description import DescriptionError, parse

#: [m/s] default surge speed below which the fins are not used.
DEFAULT_FIN_MIN_SPEED = 0.2
#: [kg/m^3] default water density of the fins' lift (fresh water, as the tank and the mine).
DEFAULT_WATER_DENSITY = 1000.0


def parse_dofs(value, name="dofs"):
    """Row indices of the degrees of freedom named in `value` ("X Y Z K M N", any subset, spaces or commas)."""
    words = str(value).replace(",", " ").split() if not isinstance(value, (list, tuple)) else [str(v) for v in value]
    bad = [w for w in words if w not in DOF]
    if not words or bad or len(set(words)) != len(words):
        raise AllocationError(f"parameter {name} = {value!r}: expected distinct names among {' '.join(DOF)}")
    return sorted(DOF.index(w) for w in words)


def _fin_angle_of_attack(fin, flow, delta):
    """The simulator's angle of attack [rad] of `fin` at angle `delta` in the flow `flow` (spanwise part removed)."""
    s, c0 = fin.axis, fin.chord
    c = math.cos(delta) * c0 + math.sin(delta) * np.cross(s, c0)
    n = np.cross(s, c)
    return math.atan2(float(flow @ n), float(-(flow @ c)))


def fin_column(fin, rho):
    """Wrench [N | N m] per radian of `fin` at a surge speed of 1 m/s (scales with u^2)."""
    u = np.array([-1.0, 0.0, 0.0])  # the water passing a vehicle going forward at 1 m/s
    flow = u - (u @ fin.axis) * fin.axis
    speed = float(np.linalg.norm(flow))
    if speed < 1e-9:
        return np.zeros(6)
    h = 1e-6
    dalpha = (_fin_angle_of_attack(fin, flow, h) - _fin_angle_of_attack(fin, flow, -h)) / (2 * h)
    lift = np.cross(flow / speed, fin.axis)
    force = 0.5 * rho * speed**2 * fin.area * lift_slope_of(fin) * dalpha * lift
    return np.concatenate([force, np.cross(fin.position, force)])


class VehicleAllocator:
    """Body wrench -> (thruster commands, fin angles [rad]) for the actuators of one robot description.

    xml: the expanded description; dofs: the degrees of freedom allocated (names, default all six); rho [kg/m^3]:
    water density of the fins' lift; fin_min_speed [m/s] > 0: the fins are used above this surge speed only.
    """

    def __init__(
        self,
        xml,
        dofs="X Y Z K M N",
        rho=DEFAULT_WATER_DENSITY,
        fin_min_speed=DEFAULT_FIN_MIN_SPEED,
        source="robot_description",
    ):
        try:
            robot = parse(xml, source)
            self.thrusters, fins = robot.thrusters, robot.fins
            self.conversions = [conversion_of(t) for t in self.thrusters]
            for t, conv in zip(self.thrusters, self.conversions):
                conv[0](t, 0.0)  # the inverse's parameters are checked once, here
        except DescriptionError as e:
            raise AllocationError(str(e)) from None
        self.fins = [f for f in fins if f.movable]
        self.fin_count = len(fins)  # the simulator's fin topics count every <fin>, fixed ones too
        self.dofs = parse_dofs(dofs)
        if not (math.isfinite(rho) and rho > 0.0):
            raise AllocationError(f"parameter water_density = {rho}: expected > 0 [kg/m^3]")
        if not (math.isfinite(fin_min_speed) and fin_min_speed > 0.0):
            raise AllocationError(f"parameter fin_min_speed = {fin_min_speed}: expected > 0 [m/s]")
        self.fin_min_speed = float(fin_min_speed)
        if not self.thrusters and not self.fins:
            raise AllocationError(f"{source}: no thruster and no movable fin to allocate")
        self.thruster_matrix = np.array(
            [np.concatenate([t.axis, np.cross(t.position, t.axis)]) for t in self.thrusters]
        ).T.reshape(6, len(self.thrusters))
        try:
            self.fin_matrix = np.array([fin_column(f, rho) for f in self.fins]).T.reshape(6, len(self.fins))
        except DescriptionError as e:
            raise AllocationError(str(e)) from None
        # [N] thrust each thruster can give: its thrust range within what its command range converts to
        self.thrust_low = np.array(
            [max(t.min_thrust, conv[1](t, t.min_command)) for t, conv in zip(self.thrusters, self.conversions)]
        )
        self.thrust_high = np.array(
            [min(t.max_thrust, conv[1](t, t.max_command)) for t, conv in zip(self.thrusters, self.conversions)]
        )

    def matrix(self, surge_speed=0.0):
        """B (6 x (thrusters + movable fins)) at surge speed u [m/s]: thrust columns per newton, fin columns per
        radian (zero below fin_min_speed)."""
        u = float(surge_speed)
        scale = u * u if u >= self.fin_min_speed else 0.0
        return np.hstack([self.thruster_matrix, scale * self.fin_matrix])

    def effort(self, wrench, surge_speed=0.0):
        """(thrusts [N], fin angles [rad], scale): the saturated least-norm effort for the wrench
        [X Y Z K M N] ([N], [N m]) on the allocated degrees of freedom; scale <= 1 the thrusts' common factor."""
        tau = np.asarray(wrench, float).reshape(-1)
        if tau.size != 6 or not np.all(np.isfinite(tau)):
            raise AllocationError(f"wrench: expected 6 finite numbers [X Y Z K M N], got {tau.tolist()}")
        s = self.matrix(surge_speed)[self.dofs, :]
        x = np.linalg.pinv(s, rcond=1e-9) @ tau[self.dofs]
        n = len(self.thrusters)
        thrusts, angles = x[:n], x[n:]
        scale = 1.0
        for t, lo, hi in zip(thrusts, self.thrust_low, self.thrust_high):
            if t > hi > 0.0 or (t > 0.0 and hi <= 0.0):
                scale = min(scale, max(hi, 0.0) / t)
            elif t < lo < 0.0 or (t < 0.0 and lo >= 0.0):
                scale = min(scale, min(lo, 0.0) / t)
        lo_angles = np.array([f.min_angle for f in self.fins])
        hi_angles = np.array([f.max_angle for f in self.fins])
        return thrusts * scale, np.clip(angles, lo_angles, hi_angles), scale

    def commands(self, thrusts):
        """Each thruster's command (its own unit, within its command range) for the thrusts [N]."""
        return [
            float(min(max(conv[0](t, float(f)), t.min_command), t.max_command))
            for t, conv, f in zip(self.thrusters, self.conversions, thrusts)
        ]

    def allocate(self, wrench, surge_speed=0.0):
        """(thruster commands, fin angles [rad] by fin id (0 for the fixed ones), scale) for the body wrench."""
        thrusts, angles, scale = self.effort(wrench, surge_speed)
        by_id = dict(zip((f.id for f in self.fins), angles))
        return self.commands(thrusts), [float(by_id.get(i, 0.0)) for i in range(self.fin_count)], scale

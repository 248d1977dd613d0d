"""What the identification derives from a robot description (unexmin.description.RobotDescription): the parameters it
does not estimate (volume, inertia, thruster geometry and dynamics, pendulum, VBS) are the record's; the nominal
values of those it does (its prior and the reference for flat directions) come from the functions below.
Body frame x forward, y left, z up; origin at the hull centre."""

import numpy as np

from unexmin.description import DescriptionError


def whole_cog(robot):
    """[m] whole-vehicle centre of gravity, pendulum at 0 rad, VBS empty, body frame."""
    h, pend = robot.hydro, robot.pendulum
    return ((h.mass - pend.mass) * h.center_of_gravity + pend.mass * np.array([0.0, 0.0, -pend.arm])) / h.mass


def is_horizontal(thruster):
    """True for a thruster with no thrust along the body z axis."""
    return abs(thruster.axis[2]) < 1e-6


def thruster_groups(robot):
    """{'horizontal': [ids], 'vertical': [ids]} of the thrusters (vertical: any thrust along z)."""
    return {
        "horizontal": [t.id for t in robot.thrusters if is_horizontal(t)],
        "vertical": [t.id for t in robot.thrusters if not is_horizontal(t)],
    }


def time_constant(thruster):
    """[s] the first-order time constant of a `first_order` thruster, 0 (zero order) for any other dynamics."""
    if thruster.dynamics != "first_order":
        return 0.0
    tau = thruster.dynamics_params.get("tau", [])
    if len(tau) != 1:
        raise DescriptionError(f"<thruster id={thruster.id}>: dynamics 'first_order' needs one 'tau' [s], got {tau}")
    return float(tau[0])


def thrust_gain(thruster):
    """Slope of a `table` conversion that is one straight line through zero (how thruster_gain_* is emitted), else
    1."""
    if thruster.conversion != "table":
        return 1.0
    x = thruster.conversion_params.get("input", [])
    y = thruster.conversion_params.get("output", [])
    slopes = [b / a for a, b in zip(x, y) if a != 0.0]
    if (
        slopes
        and all(abs(k - slopes[0]) < 1e-9 * max(1.0, abs(slopes[0])) for k in slopes)
        and all(b == 0.0 for a, b in zip(x, y) if a == 0.0)
    ):
        return slopes[0]
    return 1.0


def rest_attitude(robot):
    """(roll, pitch) [rad] at which the robot rests (pendulum 0, VBS empty): centre of gravity straight below the
    centre of buoyancy. ZYX Euler, pitch positive nose down (thesis 7 convention of urdf/ux1_perturbed.xacro)."""
    g = whole_cog(robot) - robot.hydro.center_of_buoyancy
    lever = np.linalg.norm(g)
    if lever < 1e-12:
        return 0.0, 0.0
    # g = -L (-sin p, sin r cos p, cos r cos p) in the body frame
    pitch = float(np.arcsin(np.clip(g[0] / lever, -1.0, 1.0)))
    roll = float(np.arctan2(-g[1], -g[2]))
    return roll, pitch

"""The allocator's side of the actuator families of a robot description (the actuators themselves: unexmin.description).
Pure Python, no ROS.

Each thrust-conversion family the simulator knows has its inverse here (thrust [N] -> command in the thruster's own
unit), registered by the family's name in CONVERSIONS; each fin lift family its lift slope in LIFT_SLOPES. A
thruster's or fin's parameters are the description's <param>s, lists of numbers by name.
"""

import math

import numpy as np

from unexmin.description import DescriptionError


def _scalar(params, name):
    """The one number of parameter `name`, None when it is missing or has several."""
    values = params.get(name)
    return float(values[0]) if values is not None and len(values) == 1 else None


# ------------------------------------------------------------------------------------------------------------------
# Inverse thrust conversions, by family name: thrust [N] -> command (the thruster's unit)
# ------------------------------------------------------------------------------------------------------------------
def _identity(thruster, thrust):
    return thrust


def _basic(thruster, thrust):
    """thrust = gain w |w|  ->  w = sign(thrust / gain) sqrt(|thrust / gain|)."""
    gain = _scalar(thruster.conversion_params, "gain")
    if not gain:
        raise DescriptionError(f"<thruster id={thruster.id}>: conversion 'basic' needs one non-zero 'gain'")
    ratio = thrust / gain
    return math.copysign(math.sqrt(abs(ratio)), ratio)


def _table(thruster, thrust):
    """Inverse of the piecewise-linear table (input, output): the outputs must not decrease. A thrust on a flat part
    (a dead band, within 1e-9 N) maps to the middle of its inputs; beyond the ends to the end inputs."""
    x = np.atleast_1d(np.asarray(thruster.conversion_params.get("input", []), float))
    y = np.atleast_1d(np.asarray(thruster.conversion_params.get("output", []), float))
    if x.size < 2 or x.size != y.size or np.any(np.diff(y) < 0.0):
        raise DescriptionError(
            f"<thruster id={thruster.id}>: conversion 'table' cannot be inverted: expected input and output of the "
            "same length >= 2 with the output not decreasing"
        )
    if thrust <= y[0]:
        return float(x[0])
    if thrust >= y[-1]:
        return float(x[-1])
    on = np.flatnonzero(np.abs(y - thrust) <= 1e-9)  # [N] rounding of the allocation: on the plateau
    if on.size:
        return float(0.5 * (x[on[0]] + x[on[-1]]))
    k = int(np.searchsorted(y, thrust)) - 1  # y[k] < thrust < y[k + 1]
    return float(x[k] + (thrust - y[k]) * (x[k + 1] - x[k]) / (y[k + 1] - y[k]))


def _forward_table(thruster, command):
    x = np.asarray(thruster.conversion_params["input"], float)
    y = np.asarray(thruster.conversion_params["output"], float)
    return float(np.interp(command, x, y))


#: conversion family name -> (inverse: thrust [N] -> command, forward: command -> thrust [N]).
CONVERSIONS = {
    "identity": (_identity, lambda t, c: c),
    "basic": (_basic, lambda t, c: _scalar(t.conversion_params, "gain") * c * abs(c)),
    "table": (_table, _forward_table),
}

#: fin lift family name -> lift slope dC_L/d(alpha) [1/rad] at zero angle of attack, from its <param>s.
LIFT_SLOPES = {"linear_lift": lambda fin: _scalar(fin.model_params, "lift_slope") or 0.0}


def conversion_of(thruster):
    """(inverse, forward) of the thruster's conversion family; DescriptionError naming the known ones."""
    if thruster.conversion not in CONVERSIONS:
        raise DescriptionError(
            f"<thruster id={thruster.id}>: conversion '{thruster.conversion}' has no inverse in the allocator "
            f"(known: {', '.join(sorted(CONVERSIONS))})"
        )
    return CONVERSIONS[thruster.conversion]


def lift_slope_of(fin):
    """dC_L/d(alpha) [1/rad] of the fin's lift family; DescriptionError naming the known ones."""
    if fin.model not in LIFT_SLOPES:
        raise DescriptionError(
            f"<fin id={fin.id}>: lift model '{fin.model}' is unknown to the allocator (known: {', '.join(LIFT_SLOPES)})"
        )
    return LIFT_SLOPES[fin.model](fin)

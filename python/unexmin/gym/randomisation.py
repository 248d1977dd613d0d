"""Domain randomisation of the Gymnasium environments (docs/gym.md, "Domain randomisation"), in the batch spec's
vocabulary (docs/batch.md): drawn from the environment's np_random at every reset, so `reset(seed=s)` repeats an
episode exactly.

A spec maps a parameter to a fixed value, a [low, high] pair (uniform) or, for `visibility`, a list of levels
(one drawn). The sensors' noise seed is always drawn (the world's seed of the episode).
"""

import math
import xml.etree.ElementTree as ET

from unexmin.worlds.schema import visibility_levels

#: Parameter -> meaning (unit); the batch spec's names where the batch has one.
PARAMETERS = {
    "current_speed": "mean speed of the water current [m/s] (>= 0)",
    "current_angle": "horizontal angle of the current [rad, from +x towards +y]",
    "current_vertical_angle": "vertical angle of the current [rad, up positive]",
    "visibility": "water visibility level: " + " | ".join(visibility_levels()),
    "buoyancy_offset": "buoyancy minus weight of the robot [kg]: > 0 floats (its mass becomes mass - offset)",
    "damping_scale": "factor on the robot's linear and quadratic damping [-] (> 0)",
}
VISIBILITY = visibility_levels()
#: Parameters that change the world or the robot's description: the engine's World is rebuilt when they change.
REBUILD = ("visibility", "buoyancy_offset", "damping_scale")


def check(spec):
    """The spec as {name: ("fixed", value) | ("uniform", (low, high)) | ("choice", [levels])}; ValueError naming
    the parameter and what was expected otherwise."""
    if spec is None:
        return {}
    if not isinstance(spec, dict):
        raise ValueError(f"randomise = {spec!r}: expected {{parameter: value | [low, high] | [levels]}}")
    out = {}
    for name, value in spec.items():
        if name not in PARAMETERS:
            raise ValueError(f"randomise: unknown parameter {name!r}: expected one of {', '.join(PARAMETERS)}")
        if name == "visibility":
            levels = [value] if isinstance(value, str) else value
            if not isinstance(levels, (list, tuple)) or not levels or any(v not in VISIBILITY for v in levels):
                raise ValueError(f"randomise.visibility = {value!r}: expected a level or a list of {VISIBILITY}")
            out[name] = ("choice", list(levels))
            continue
        if isinstance(value, (list, tuple)):
            if len(value) != 2 or not all(_finite(v) for v in value) or value[0] > value[1]:
                raise ValueError(f"randomise.{name} = {value!r}: expected [low, high], finite, low <= high")
            low, high = float(value[0]), float(value[1])
            out[name] = ("uniform", (low, high))
        elif _finite(value):
            low = high = float(value)
            out[name] = ("fixed", low)
        else:
            raise ValueError(f"randomise.{name} = {value!r}: expected a finite number or [low, high]")
        if name == "current_speed" and low < 0:
            raise ValueError(f"randomise.current_speed = {value!r}: a speed is >= 0 m/s")
        if name == "damping_scale" and low <= 0:
            raise ValueError(f"randomise.damping_scale = {value!r}: expected a factor > 0")
    return out


def _finite(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def draw(spec, rng):
    """One episode's values {name: value} of a checked spec, from numpy Generator `rng` (in the spec's order)."""
    values = {}
    for name, (kind, arg) in spec.items():
        if kind == "fixed":
            values[name] = arg
        elif kind == "uniform":
            values[name] = float(rng.uniform(arg[0], arg[1]))
        else:
            values[name] = arg[int(rng.integers(len(arg)))]
    return values


def patched_description(urdf, buoyancy_offset=0.0, damping_scale=1.0):
    """The URDF text `urdf` with its <unexmin><hydrodynamics> mass lowered by `buoyancy_offset` [kg] and its linear
    and quadratic damping multiplied by `damping_scale` (the rest as it is)."""
    if buoyancy_offset == 0.0 and damping_scale == 1.0:
        return urdf
    root = ET.fromstring(urdf)
    hydro = root.find("unexmin/hydrodynamics")
    if hydro is None:
        raise ValueError("the robot description has no <unexmin><hydrodynamics> block to randomise")
    mass = hydro.find("mass")
    new_mass = float(mass.get("value")) - buoyancy_offset
    if not new_mass > 0:
        raise ValueError(f"buoyancy_offset = {buoyancy_offset} kg leaves a mass of {new_mass} kg: expected > 0")
    mass.set("value", repr(new_mass))
    for tag in ("linear_damping", "quadratic_damping"):
        e = hydro.find(tag)
        e.set("value", " ".join(repr(float(v) * damping_scale) for v in e.get("value").split()))
    return ET.tostring(root, encoding="unicode")

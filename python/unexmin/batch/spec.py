"""Batch specifications (docs/batch.md): read and check a SPEC.yaml, expand it into missions, and write
the world file, robot overrides and launch file of one mission. Pure Python, no ROS, no Dask.

A mission is {"index", "seed", "params"}: `params` holds one value per swept or sampled parameter (and the
spec's fixed `params`). The expansion depends only on the spec: seeds outermost, then the cartesian
product of `sweep` in the order written, and each `sample` parameter drawn from a generator seeded with
(sample_seed, index), so the same spec gives the same missions whatever runs them.
"""

import importlib
import itertools
import math
import os
from xml.etree import ElementTree

import numpy as np
import yaml

from unexmin.vehicles import parse_vehicles
from unexmin.worlds.files import PACKAGE_DIR, link_meshes, world_path
from unexmin.worlds.schema import WorldFileError, read_world, visibility_levels

#: Parameters that change the simulated world or robot rather than (only) the mission function.
WORLD_PARAMS = {
    "current_speed": "mean speed of the world's water current [m/s]",
    "current_angle": "horizontal angle of the current [rad, from +x towards +y]",
    "current_vertical_angle": "vertical angle of the current [rad, up positive]",
    "visibility": "water visibility level: none | low | medium | high",
    "buoyancy_offset": "buoyancy minus weight of every robot [kg]: > 0 floats (vehicle_mass - offset)",
    "sensor_noise_scale": "factor on every sensor noise figure of the robot description [-]",
    "overrides": "xacro overrides file for every robot (relative to the spec's folder)",
}
DISTRIBUTIONS = {"uniform": 2, "normal": 2, "loguniform": 2, "integers": 2, "choice": None}
KEYS = {
    "world",
    "robots",
    "mission",
    "duration",
    "timeout",
    "retries",
    "seeds",
    "sweep",
    "sample",
    "sample_seed",
    "params",
    "sensors",
    "mode",
    "ray_caster_threads",
    "python_path",
    "control",
    "vehicles",
    "backend",
}
VISIBILITY = visibility_levels()


class SpecError(ValueError):
    """A batch specification that cannot be run; the message names the file, the key and what was expected."""


def _number(where, value, low=-math.inf, high=math.inf, integer=False):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise SpecError(f"{where}: expected a finite number, got {value!r}")
    if integer and int(value) != value:
        raise SpecError(f"{where}: expected a whole number, got {value!r}")
    if not low <= value <= high:
        raise SpecError(f"{where}: {value!r} is outside [{low}, {high}]")
    return int(value) if integer else float(value)


def _seeds(where, value):
    if isinstance(value, int) and not isinstance(value, bool):
        return list(range(_number(where, value, 1, integer=True)))
    if isinstance(value, dict):
        unknown = set(value) - {"start", "count"}
        if unknown or "count" not in value:
            raise SpecError(f"{where}: expected {{start: S, count: N}} (start optional), got {value!r}")
        start = _number(f"{where}.start", value.get("start", 0), 0, integer=True)
        return list(range(start, start + _number(f"{where}.count", value["count"], 1, integer=True)))
    if isinstance(value, list) and value:
        return [_number(f"{where}[{i}]", s, 0, integer=True) for i, s in enumerate(value)]
    raise SpecError(f"{where}: expected a count N, a list of seeds or {{start: S, count: N}}, got {value!r}")


def _check_value(where, name, value):
    """Range checks of the world parameters' values (swept, sampled or fixed)."""
    if name == "visibility" and value not in VISIBILITY:
        raise SpecError(f"{where}: visibility {value!r}: expected one of {', '.join(VISIBILITY)}")
    if name == "current_speed":
        _number(where, value, 0.0)
    if name == "sensor_noise_scale":
        _number(where, value, 0.0)
    if name in ("current_angle", "current_vertical_angle", "buoyancy_offset"):
        _number(where, value)
    if name == "overrides" and not isinstance(value, str):
        raise SpecError(f"{where}: overrides: expected a xacro file path, got {value!r}")


def _distribution(where, value):
    if not isinstance(value, dict) or len(value) != 1 or next(iter(value)) not in DISTRIBUTIONS:
        raise SpecError(
            f"{where}: expected one of {{{', '.join(f'{d}: [...]' for d in DISTRIBUTIONS)}}}, got {value!r}"
        )
    kind, args = next(iter(value.items()))
    if not isinstance(args, list) or not args or (DISTRIBUTIONS[kind] and len(args) != DISTRIBUTIONS[kind]):
        raise SpecError(
            f"{where}.{kind}: expected a list of {DISTRIBUTIONS[kind] or 'one or more'} values, got {args!r}"
        )
    if kind != "choice":
        a, b = (_number(f"{where}.{kind}[{i}]", v) for i, v in enumerate(args))
        if kind == "normal" and b < 0 or kind != "normal" and not a <= b:
            raise SpecError(
                f"{where}.{kind}: {args!r}: expected "
                + ("a standard deviation >= 0" if kind == "normal" else "low <= high")
            )
        if kind == "loguniform" and a <= 0:
            raise SpecError(f"{where}.loguniform: {args!r}: expected 0 < low <= high")
    return kind, args


def draw(kind, args, rng):
    """One value of the distribution `kind` with arguments `args` from the numpy Generator `rng`."""
    if kind == "uniform":
        return float(rng.uniform(args[0], args[1]))
    if kind == "normal":
        return float(rng.normal(args[0], args[1]))
    if kind == "loguniform":
        return float(math.exp(rng.uniform(math.log(args[0]), math.log(args[1]))))
    if kind == "integers":
        return int(rng.integers(int(args[0]), int(args[1]), endpoint=True))
    return args[int(rng.integers(len(args)))]  # choice


def load_spec(path):
    """The checked spec of the YAML file `path` as a dict with every default filled in (docs/batch.md)."""
    path = os.path.abspath(path)
    try:
        with open(path) as f:
            raw = yaml.safe_load(f)
    except (OSError, yaml.YAMLError) as e:
        raise SpecError(f"{path}: cannot read the batch spec ({e})") from None
    return check_spec(raw, path)


def check_spec(raw, path="<spec>"):
    """Check and complete a spec given as a dict; `path` names it in errors and anchors relative paths."""
    if not isinstance(raw, dict):
        raise SpecError(f"{path}: a batch spec is a YAML map (world, mission, duration, seeds, sweep, sample...)")
    unknown = sorted(set(raw) - KEYS)
    if unknown:
        raise SpecError(f"{path}: unknown key(s) {', '.join(unknown)} (accepted: {', '.join(sorted(KEYS))})")
    base = os.path.dirname(os.path.abspath(path)) if os.path.exists(path) else os.getcwd()
    spec = {"path": path, "base": base}
    mission = raw.get("mission")
    if not isinstance(mission, str) or mission.count(":") != 1 or not all(mission.split(":")):
        raise SpecError(
            f"{path}: mission: expected 'module:function' (e.g. unexmin.missions.batch:tank_survey), "
            f"got {mission!r}"
        )
    spec["mission"] = mission
    world = raw.get("world", "tank")
    if not isinstance(world, str):
        raise SpecError(f"{path}: world: expected tank, mine, test_box or a world file, got {world!r}")
    try:
        spec["world_file"] = os.path.abspath(world_path(world, base))
    except FileNotFoundError:
        raise SpecError(
            f"{path}: world: {world!r} is neither a world of the package's worlds/ "
            "(tank, mine, test_box) nor an existing world file"
        ) from None
    try:
        read_world(spec["world_file"])  # a typo in the world stops the batch before its first mission
    except WorldFileError as e:
        raise SpecError(f"{path}: world: {e}") from None
    spec["world"] = world
    spec["robots"] = _number(f"{path}: robots", raw.get("robots", 1), 1, 3, integer=True)
    try:  # a mixed team instead of `robots` UX-1s (docs/batch.md)
        spec["vehicles"] = parse_vehicles(raw["vehicles"], f"{path}: vehicles") if raw.get("vehicles") else []
    except ValueError as e:
        raise SpecError(str(e)) from None
    spec["duration"] = _number(f"{path}: duration [s of sim time]", raw.get("duration", 30.0), 1e-3)
    spec["timeout"] = _number(
        f"{path}: timeout [s of wall time per attempt]", raw.get("timeout", 120.0 + 10.0 * spec["duration"]), 1.0
    )
    spec["retries"] = _number(f"{path}: retries", raw.get("retries", 1), 0, 5, integer=True)
    spec["sample_seed"] = _number(f"{path}: sample_seed", raw.get("sample_seed", 0), 0, integer=True)
    spec["ray_caster_threads"] = _number(
        f"{path}: ray_caster_threads", raw.get("ray_caster_threads", 1), 0, integer=True
    )
    for key, default, accepted in (("sensors", "all", None), ("mode", "operational", ("operational", "visual"))):
        value = raw.get(key, default)
        if not isinstance(value, str) or (accepted and value not in accepted):
            raise SpecError(f"{path}: {key}: expected {' | '.join(accepted) if accepted else 'a text'}, got {value!r}")
        spec[key] = value
    spec["control"] = raw.get("control", True)
    if not isinstance(spec["control"], bool):
        raise SpecError(f"{path}: control: expected true or false, got {spec['control']!r}")
    # A mixed team runs on the ROS simulator: the core spawns the world file's first robots only.
    spec["backend"] = raw.get("backend", "ros" if spec["vehicles"] else "core")
    if spec["backend"] not in ("core", "ros"):
        raise SpecError(f"{path}: backend: expected core or ros, got {spec['backend']!r}")
    if spec["backend"] == "core" and spec["vehicles"]:
        raise SpecError(f"{path}: backend: core cannot run a mixed team (vehicles): use backend: ros")
    spec["seeds"] = _seeds(f"{path}: seeds", raw.get("seeds", 1))
    python_path = raw.get("python_path", [])
    if not isinstance(python_path, list) or not all(isinstance(p, str) for p in python_path):
        raise SpecError(f"{path}: python_path: expected a list of folders, got {python_path!r}")
    spec["python_path"] = [os.path.normpath(os.path.join(base, p)) for p in python_path]

    fixed = raw.get("params", {}) or {}
    sweep = raw.get("sweep", {}) or {}
    sample = raw.get("sample", {}) or {}
    for key, value in (("params", fixed), ("sweep", sweep), ("sample", sample)):
        if not isinstance(value, dict):
            raise SpecError(f"{path}: {key}: expected a map of parameter names, got {value!r}")
    taken = {}
    for key, table in (("params", fixed), ("sweep", sweep), ("sample", sample)):
        for name in table:
            if not isinstance(name, str) or not name.isidentifier():
                raise SpecError(f"{path}: {key}.{name}: parameter names are Python identifiers")
            if name in taken:
                raise SpecError(f"{path}: parameter {name!r} is given both in {taken[name]} and in {key}")
            if name in ("seed", "index", "robots", "status", "error", "log", "wall_time_s", "attempts", "duration"):
                raise SpecError(f"{path}: {key}.{name}: this name is a column of the results table")
            taken[name] = key
    for name, value in fixed.items():
        _check_value(f"{path}: params.{name}", name, value)
    for name, values in sweep.items():
        if not isinstance(values, list) or not values:
            raise SpecError(f"{path}: sweep.{name}: expected a non-empty list of values, got {values!r}")
        for i, v in enumerate(values):
            _check_value(f"{path}: sweep.{name}[{i}]", name, v)
    spec["params"] = dict(fixed)
    spec["sweep"] = {n: list(v) for n, v in sweep.items()}
    spec["sample"] = {n: _distribution(f"{path}: sample.{n}", v) for n, v in sample.items()}
    for name, (kind, args) in spec["sample"].items():
        if kind == "choice":
            for i, v in enumerate(args):
                _check_value(f"{path}: sample.{name}.choice[{i}]", name, v)
    return spec


def expand(spec, limit=None):
    """The spec's missions, in order: [{"index", "seed", "params"}]; only the first `limit` if given."""
    missions = []
    names = list(spec["sweep"])
    for seed in spec["seeds"]:
        for combo in itertools.product(*(spec["sweep"][n] for n in names)):
            index = len(missions)
            params = dict(spec["params"])
            params.update(zip(names, combo))
            rng = np.random.default_rng([spec["sample_seed"], index])
            for name, (kind, args) in spec["sample"].items():
                params[name] = draw(kind, args, rng)
            for name in ("current_speed", "sensor_noise_scale"):  # a normal draw can go below zero
                if name in params and params[name] < 0:
                    params[name] = 0.0
            missions.append({"index": index, "seed": int(seed), "params": params})
            if limit is not None and len(missions) >= limit:
                return missions
    return missions


def load_mission_function(name):
    """The callable `module:function` (mission(sim, params) -> dict of metrics)."""
    module_name, _, attr = name.partition(":")
    try:
        module = importlib.import_module(module_name)
    except ImportError as e:
        raise SpecError(
            f"mission {name!r}: cannot import module {module_name!r} ({e}); is its folder in the spec's python_path?"
        ) from None
    fn = getattr(module, attr, None)
    if not callable(fn):
        raise SpecError(f"mission {name!r}: module {module_name!r} has no function {attr!r}")
    return fn


# -- one mission's files -----------------------------------------------------------------------------------
def write_world(spec, params, folder):
    """A copy of the spec's world file with the mission's current, its meshes linked beside it; its path."""
    world = read_world(spec["world_file"])
    link_meshes(world.get("meshes") or [], os.path.dirname(os.path.abspath(spec["world_file"])), folder)
    current = world.setdefault("current", {})
    for name, var in (
        ("current_speed", "speed"),
        ("current_angle", "horizontal_angle"),
        ("current_vertical_angle", "vertical_angle"),
    ):
        if name in params:
            value = float(params[name])
            process = current.setdefault(var, {"min": value, "max": value, "noise": 0.0, "mu": 0.0})
            process["mean"] = value
            # the process stays inside [min, max]: widen the world's bounds to hold the mission's mean
            process["min"] = min(float(process.get("min", value)), value)
            process["max"] = max(float(process.get("max", value)), value)
    if "visibility" in params:
        world.setdefault("visibility", {})["level"] = params["visibility"]
    path = os.path.join(folder, "mission.world")
    with open(path, "w") as f:
        f.write("# Written by unexmin.batch for one mission (docs/batch.md)\n")
        yaml.safe_dump(world, f, sort_keys=False)
    read_world(path)  # what the simulator will read follows the schema
    return path


def noise_properties(properties_file=None):
    """Names of the robot description's noise figures: the properties of urdf/properties.xacro whose name
    holds "noise" and whose value refers to no other noise property (a derived figure follows its source)."""
    properties_file = properties_file or str(PACKAGE_DIR / "urdf" / "properties.xacro")
    root = ElementTree.parse(properties_file).getroot()
    names = []
    for elt in root.iter("{http://www.ros.org/wiki/xacro}property"):
        name, value = elt.get("name"), elt.get("value") or ""
        if "noise" in name and "noise" not in value:
            names.append(name)
    return names


def write_overrides(spec, params, folder):
    """The mission's robot overrides xacro (the user's overrides file, then buoyancy and noise scaling), or
    "" when the mission changes none. Each redefinition is evaluated at once (scope="global") from the
    value in force, so it scales the robot description's own figure."""
    lines = []
    if "overrides" in params:
        user = os.path.normpath(os.path.join(spec["base"], params["overrides"]))
        if not os.path.exists(user):
            raise SpecError(f"overrides {params['overrides']!r}: no such file ({user})")
        lines.append(f'  <xacro:include filename="{user}"/>')
    if "buoyancy_offset" in params:
        lines.append(
            f'  <xacro:property name="vehicle_mass" value="${{vehicle_mass - ({float(params["buoyancy_offset"])!r})}}"'
            ' scope="global"/>'
        )
    if "sensor_noise_scale" in params:
        scale = float(params["sensor_noise_scale"])
        lines += [
            f'  <xacro:property name="{n}" value="${{{n} * {scale!r}}}" scope="global"/>' for n in noise_properties()
        ]
    if not lines:
        return ""
    path = os.path.join(folder, "overrides.xacro")
    with open(path, "w") as f:
        f.write(
            '<?xml version="1.0"?>\n<!-- Written by unexmin.batch for one mission (docs/batch.md) -->\n'
            '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n' + "\n".join(lines) + "\n</robot>\n"
        )
    return path


def write_launch(spec, mission, folder):
    """The mission's launch file: simulation.launch (lockstep, paused) with its world, seed and overrides."""
    os.makedirs(folder, exist_ok=True)
    world = write_world(spec, mission["params"], folder)
    overrides = write_overrides(spec, mission["params"], folder)
    args = {
        "world": world,
        "robots": spec["robots"],
        "realtime": "false",
        "paused": "true",
        "seed": mission["seed"],
        "mode": spec["mode"],
        "sensors": spec["sensors"],
        "ray_caster_threads": spec["ray_caster_threads"],
        "control": str(spec["control"]).lower(),
        "mesh_marker": "false",
    }  # no rviz in a batch
    if spec.get("vehicles"):
        args["vehicles"] = ",".join(spec["vehicles"])
    for k in range(1, spec["robots"] + 1):
        args[f"UX_{k}_overrides"] = overrides
    body = "\n".join(f'    <arg name="{k}" value="{v}"/>' for k, v in args.items())
    path = os.path.join(folder, "mission.launch")
    with open(path, "w") as f:
        f.write(
            "<!-- Written by unexmin.batch for one mission (docs/batch.md) -->\n<launch>\n"
            f'  <include file="$(find unexmin)/launch/simulation.launch">\n{body}\n  </include>\n</launch>\n'
        )
    return path

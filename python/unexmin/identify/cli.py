"""python -m unexmin.identify BAG --out DIR: the command, and the files it writes (docs/identification.md)."""

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np
import yaml

from unexmin.identify.model import DOF, INDEX, PARAMS
from unexmin.replay.bag_io import MOTORS_TOPIC, read_bag
from unexmin.replay.errors import ReplayError

DESCRIPTION = "Identify the robot's dynamics (Fossen model) from a mission bag; write identified.yaml, " \
              "an overrides file and a report."
DEFAULT_FIXED = ("added_mass",)


def _entry(fit, names, unidentifiable):
    values = [float(fit.x[INDEX[n]]) for n in names]
    sigmas = [None if n in unidentifiable or not math.isfinite(fit.sigma[INDEX[n]]) else float(fit.sigma[INDEX[n]])
              for n in names]
    return values, sigmas


def results(fit, nominal, physics, signals, bag, robot, fixed):
    """The identified.yaml dict."""
    unid = list(fit.unidentifiable)

    def one(names):
        v, s = _entry(fit, names, unid + list(fixed))
        return {"value": v[0], "sigma": s[0]} if len(names) == 1 else {"value": v, "sigma": s}

    gains = one(["thrust_gain_horizontal", "thrust_gain_vertical"])
    groups = physics.groups()
    return {
        "bag": str(Path(bag).resolve()), "robot": robot,
        "buoyancy_kg": one(["buoyancy_kg"]),
        "cog_m": one(["cog_x", "cog_y", "cog_z"]),
        "damping_linear": one([f"damping_linear_{d}" for d in DOF]),
        "damping_quadratic": one([f"damping_quadratic_{d}" for d in DOF]),
        "thrust_gain": {"value": dict(zip(("horizontal", "vertical"), gains["value"])),
                        "sigma": dict(zip(("horizontal", "vertical"), gains["sigma"])),
                        "groups": {k: [int(i) for i in v] for k, v in groups.items()}},
        "added_mass": one(["added_mass"]),
        "added_inertia": one([f"added_inertia_{d}" for d in DOF[3:]]),
        "unidentifiable": unid,
        "fixed": list(fixed),
        "nominal": {n: float(nominal[INDEX[n]]) for n in PARAMS},
        "units": {"buoyancy_kg": "kg (positive: floats)", "cog_m": "m, body frame, whole vehicle, pendulum at 0, "
                  "VBS empty, relative to the centre of buoyancy", "damping_linear": "N s/m x3, N m s/rad x3",
                  "damping_quadratic": "N s^2/m^2 x3, N m s^2/rad^2 x3", "thrust_gain": "achieved / nominal thrust",
                  "added_mass": "kg (translational, isotropic)", "added_inertia": "kg m^2 (roll, pitch, yaw)",
                  "order": list(DOF)},
        "fit": {"samples": int(signals.keep.sum()), "navigation_period_s": float(signals.t[1] - signals.t[0]),
                "window_s": float(signals.window * (signals.t[1] - signals.t[0])),
                "residual_rms": dict(zip(DOF, (float(v) for v in fit.rms))),
                "residual_rms_nominal": dict(zip(DOF, (float(v) for v in fit.rms_nominal))),
                "residual_units": "N (surge, sway, heave: world frame) and N m (roll, pitch, yaw: body frame)",
                "rms_speed": dict(zip(DOF, (float(v) for v in np.sqrt(np.mean(
                    np.hstack([signals.v, signals.w])[signals.keep] ** 2, axis=0))))),
                "rms_speed_units": "m/s (surge, sway, heave), rad/s (roll, pitch, yaw), body frame"},
    }


def overrides_xacro(fit, physics, water_density):
    """Text of a xacro overrides file (urdf/properties.xacro names) that makes the simulated robot the
    identified one; unidentifiable and fixed parameters keep the values of the description."""
    X = dict(zip(PARAMS, fit.x))
    m = water_density * physics.volume - X["buoyancy_kg"]
    c_whole = np.array([X["cog_x"], X["cog_y"], X["cog_z"]]) + physics.cob
    cog_base = (m * c_whole - physics.pendulum_mass * np.array([0.0, 0.0, -physics.pendulum_arm])) / (
        m - physics.pendulum_mass)
    ma, ia = X["added_mass"], [X[f"added_inertia_{d}"] for d in DOF[3:]]
    matrix = np.diag([ma, ma, ma, *ia])

    def fmt(values):
        return " ".join(f"{v:.9g}" for v in values)

    return f"""<?xml version="1.0"?>
<!-- Written by python -m unexmin.identify (docs/identification.md): the identified robot as overrides of
     urdf/properties.xacro. Use: roslaunch unexmin tank_world.launch UX_1_overrides:=<this file>, or
     python -m unexmin.replay BAG with its overrides option set to this file. -->
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <!-- [kg] net buoyancy {X['buoyancy_kg']:.6g} kg: vehicle mass = rho V - buoyancy -->
  <xacro:property name="vehicle_mass" value="${{water_density * hull_volume - {X['buoyancy_kg']:.9g}}}"/>
  <!-- [m] centre of gravity of the vehicle less the pendulum, body frame (whole vehicle relative to the
       centre of buoyancy: {fmt(c_whole - physics.cob)}) -->
  <xacro:property name="cog_x" value="{cog_base[0]:.9g}"/>
  <xacro:property name="cog_y" value="{cog_base[1]:.9g}"/>
  <xacro:property name="cog_z" value="{cog_base[2]:.9g}"/>
  <!-- [N s/m x3 | N m s/rad x3] surge sway heave roll pitch yaw -->
  <xacro:property name="linear_damping_diagonal" value="{fmt(X[f'damping_linear_{d}'] for d in DOF)}"/>
  <!-- [N s^2/m^2 x3 | N m s^2/rad^2 x3] -->
  <xacro:property name="quadratic_damping_diagonal" value="{fmt(X[f'damping_quadratic_{d}'] for d in DOF)}"/>
  <!-- M_A [kg | kg m^2] -->
  <xacro:property name="added_mass_matrix" value="{fmt(matrix.ravel())}"/>
  <!-- [-] thrust gains of the thruster groups -->
  <xacro:property name="thruster_gain_horizontal" value="{X['thrust_gain_horizontal']:.9g}"/>
  <xacro:property name="thruster_gain_vertical" value="{X['thrust_gain_vertical']:.9g}"/>
</robot>
"""


def identify_bag(bag, out_dir, robot="UX_1", motors_topic=MOTORS_TOPIC, pendulum_topic=None, vbs_topic=None,
                 nav_topic=None, window_s=0.7, water_density=1000.0, surface_z=0.0, fixed=DEFAULT_FIXED,
                 overrides=None, progress=True, mission=None):
    """Identify from `bag` (or an already read `mission`) and write identified.yaml,
    identified_overrides.xacro and report.md (+ plots) into out_dir. Returns the identified.yaml dict."""
    from unexmin.identify import description, fit, model, report

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    wall0 = time.monotonic()
    if mission is None:
        mission = read_bag(bag, robot, motors_topic, pendulum_topic, vbs_topic, nav_topic)
    if mission.nav is None:
        raise ReplayError(f"{bag}: no navigation in the bag (nav_msgs/Odometry or a pose topic): nothing to fit")
    for name in fixed:
        if name not in INDEX:
            raise ReplayError(f"--fix {name}: unknown parameter (one of {', '.join(PARAMS)})")
    try:
        physics = description.load(name=robot, overrides=overrides)
    except description.DescriptionError as e:
        raise ReplayError(str(e)) from None
    nominal = model.nominal_vector(physics)
    nominal[INDEX["buoyancy_kg"]] = water_density * physics.volume - physics.mass
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=len(PARAMS) + 3, desc="identify", unit="fit", leave=False)
    try:
        signals = model.prepare(mission, physics, window_s, water_density, surface_z)
    except ValueError as e:
        raise ReplayError(str(e)) from None
    if bar:
        bar.update(1)
    result = fit.identify(signals, physics, nominal, fixed, progress=bar.update if bar else None)
    if bar:
        bar.close()
    data = results(result, nominal, physics, signals, bag, robot, fixed)
    data["fit"]["wall_time_s"] = round(time.monotonic() - wall0, 2)
    with open(out_dir / "identified.yaml", "w") as f:
        yaml.safe_dump(data, f, sort_keys=False, default_flow_style=None)
    (out_dir / "identified_overrides.xacro").write_text(overrides_xacro(result, physics, water_density))
    report.write(out_dir, data, result, nominal, signals)
    return data


def summary(data):
    """Terminal lines of an identified.yaml dict."""
    def pm(e, fmt="{:.4g}"):
        if e is data["added_mass"] and "added_mass" in data["fixed"]:
            return f"{e['value']:.4g} (fixed)"
        return "flat" if e["sigma"] is None else f"{fmt.format(e['value'])} +- {fmt.format(e['sigma'])}"

    def vec(e):
        return ", ".join(("flat" if s is None else f"{v:.4g}+-{s:.2g}") for v, s in zip(e["value"], e["sigma"]))

    g = data["thrust_gain"]
    lines = [f"buoyancy: {pm(data['buoyancy_kg'])} kg",
             f"centre of gravity - centre of buoyancy: ({vec(data['cog_m'])}) m",
             f"quadratic damping (surge sway heave roll pitch yaw): {vec(data['damping_quadratic'])}",
             f"linear damping: {vec(data['damping_linear'])}",
             "thrust gain: " + ", ".join(f"{k} " + pm({"value": v, "sigma": g["sigma"][k]}) for k, v in g["value"].items()),
             f"added mass: {pm(data['added_mass'])} kg; added inertia (roll pitch yaw): {vec(data['added_inertia'])}",
             f"unidentifiable from this bag (kept at the description's value): {', '.join(data['unidentifiable']) or 'none'}"]
    if data["fixed"]:
        lines.append(f"fixed by request: {', '.join(data['fixed'])}")
    return lines


def main(argv=None):
    """Command line; exit 0 done, 2 bad bag or argument."""
    ap = argparse.ArgumentParser(prog="python -m unexmin.identify", description=DESCRIPTION)
    ap.add_argument("bag", help="ROS 1 bag: motor commands (ux1_msgs/MotorCommand), pendulum, VBS, navigation")
    ap.add_argument("--out", default="identify_out", help="output folder (default identify_out)")
    ap.add_argument("--robot", default="UX_1", help="robot name: topics /<robot>/... (default UX_1)")
    ap.add_argument("--motors-topic", default=MOTORS_TOPIC, help=f"MotorCommand topic (default {MOTORS_TOPIC})")
    ap.add_argument("--pendulum-topic", help="Float64 pendulum command topic (default /<robot>/pendulum if present)")
    ap.add_argument("--vbs-topic", help="Float64 VBS command topic (default /<robot>/vbs if present)")
    ap.add_argument("--nav-topic", help="navigation topic (default /<robot>/odom, else the only Odometry/Pose one)")
    ap.add_argument("--window", type=float, default=0.7, help="[s] Savitzky-Golay window of the derivatives "
                    "(default 0.7 for ground truth; 5 for a navigation filter's noisy output)")
    ap.add_argument("--water-density", type=float, default=1000.0, help="[kg/m^3] (default 1000, fresh water)")
    ap.add_argument("--surface-z", type=float, default=0.0, help="[m] world z of the free surface (default 0)")
    ap.add_argument("--overrides", help="xacro overrides of the description the fit starts from (its prior)")
    ap.add_argument("--fix", action="append", default=None, metavar="NAME",
                    help=f"keep a parameter at the description's value (repeatable; default: {', '.join(DEFAULT_FIXED)})")
    ap.add_argument("--free-all", action="store_true", help="fix nothing (added mass too)")
    ap.add_argument("--quiet", action="store_true", help="no progress bar")
    args = ap.parse_args(argv)
    fixed = () if args.free_all else tuple(args.fix if args.fix is not None else DEFAULT_FIXED)
    try:
        if not (args.window > 0 and math.isfinite(args.window)):
            raise ReplayError(f"--window {args.window}: expected a positive number of seconds")
        if not (args.water_density > 0 and math.isfinite(args.water_density)):
            raise ReplayError(f"--water-density {args.water_density}: expected a positive density [kg/m^3]")
        data = identify_bag(args.bag, args.out, args.robot, args.motors_topic, args.pendulum_topic, args.vbs_topic,
                            args.nav_topic, args.window, args.water_density, args.surface_z, fixed, args.overrides,
                            not args.quiet)
    except ReplayError as e:
        print(f"identify: error: {e}", file=sys.stderr)
        return 2
    for line in summary(data):
        print(line)
    print(f"written: {Path(args.out).resolve()}/identified.yaml, identified_overrides.xacro, report.md")
    return 0

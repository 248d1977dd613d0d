"""python -m unexmin.identify BAG --out DIR: the command, and the files it writes (docs/identification.md)."""

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np
import yaml

from unexmin.identify.model import DOF, INDEX, PARAMS
from unexmin.identify.vehicle import thruster_groups
from unexmin.replay.bag_io import MOTORS_TOPIC, read_bag
from unexmin.replay.errors import ReplayError, print_summary

DESCRIPTION = (
    "Identify the robot's dynamics (Fossen model) from a mission bag; write identified.yaml, "
    "an overrides file and a report."
)
DEFAULT_FIXED = ("added_mass",)


def _entry(fit, names, unidentifiable):
    values = [float(fit.x[INDEX[n]]) for n in names]
    sigmas = [
        None if n in unidentifiable or not math.isfinite(fit.sigma[INDEX[n]]) else float(fit.sigma[INDEX[n]])
        for n in names
    ]
    return values, sigmas


def results(fit, nominal, physics, signals, bag, robot, fixed):
    """The identified.yaml dict."""
    unid = list(fit.unidentifiable)

    def one(names):
        v, s = _entry(fit, names, unid + list(fixed))
        return {"value": v[0], "sigma": s[0]} if len(names) == 1 else {"value": v, "sigma": s}

    gains = one(["thrust_gain_horizontal", "thrust_gain_vertical"])
    groups = thruster_groups(physics)
    return {
        "bag": str(Path(bag).resolve()),
        "robot": robot,
        "buoyancy_kg": one(["buoyancy_kg"]),
        "cog_m": one(["cog_x", "cog_y", "cog_z"]),
        "damping_linear": one([f"damping_linear_{d}" for d in DOF]),
        "damping_quadratic": one([f"damping_quadratic_{d}" for d in DOF]),
        "thrust_gain": {
            "value": dict(zip(("horizontal", "vertical"), gains["value"])),
            "sigma": dict(zip(("horizontal", "vertical"), gains["sigma"])),
            "groups": {k: [int(i) for i in v] for k, v in groups.items()},
        },
        "added_mass": one(["added_mass"]),
        "added_inertia": one([f"added_inertia_{d}" for d in DOF[3:]]),
        "unidentifiable": unid,
        "fixed": list(fixed),
        "nominal": {n: float(nominal[INDEX[n]]) for n in PARAMS},
        "units": {
            "buoyancy_kg": "kg (positive: floats)",
            "cog_m": "m, body frame, whole vehicle, pendulum at 0, VBS empty, relative to the centre of buoyancy",
            "damping_linear": "N s/m x3, N m s/rad x3",
            "damping_quadratic": "N s^2/m^2 x3, N m s^2/rad^2 x3",
            "thrust_gain": "achieved / nominal thrust",
            "added_mass": "kg (translational, isotropic)",
            "added_inertia": "kg m^2 (roll, pitch, yaw)",
            "order": list(DOF),
        },
        "fit": {
            "samples": int(signals.keep.sum()),
            "navigation_period_s": float(signals.t[1] - signals.t[0]),
            "window_s": float(signals.window * (signals.t[1] - signals.t[0])),
            "residual_rms": dict(zip(DOF, (float(v) for v in fit.rms))),
            "residual_rms_nominal": dict(zip(DOF, (float(v) for v in fit.rms_nominal))),
            "residual_units": "N (surge, sway, heave: world frame) and N m (roll, pitch, yaw: body frame)",
            "rms_speed": dict(
                zip(
                    DOF,
                    (float(v) for v in np.sqrt(np.mean(np.hstack([signals.v, signals.w])[signals.keep] ** 2, axis=0))),
                )
            ),
            "rms_speed_units": "m/s (surge, sway, heave), rad/s (roll, pitch, yaw), body frame",
        },
    }


def overrides_xacro(fit, physics, water_density):
    """Text of a xacro overrides file (urdf/properties.xacro names) that makes the simulated robot the
    identified one; unidentifiable and fixed parameters keep the values of the description."""
    X = dict(zip(PARAMS, fit.x))
    m = water_density * physics.hydro.volume - X["buoyancy_kg"]
    c_whole = np.array([X["cog_x"], X["cog_y"], X["cog_z"]]) + physics.hydro.center_of_buoyancy
    cog_base = (m * c_whole - physics.pendulum.mass * np.array([0.0, 0.0, -physics.pendulum.arm])) / (
        m - physics.pendulum.mass
    )
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
       centre of buoyancy: {fmt(c_whole - physics.hydro.center_of_buoyancy)}) -->
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


NAV_SOURCES = ("odometry", "dead-reckoning")
DR_DEFAULTS = {
    "imu_topic": None,
    "dvl_topic": None,
    "pressure_topic": None,
    "gravity": 9.81,
    "atmospheric_pressure": 101325.0,
    "depth_time_constant": 10.0,
    "level_time": 1.0,
    "period": 0.1,
}


def dead_reckoning_nav(bag, mission, robot, overrides, water_density, surface_z, options=None):
    """Navigation rows (t, x, y, z, roll, pitch, yaw) of the bag's IMU, DVL and pressure messages by dead
    reckoning (unexmin.identify.dead_reckoning) on a uniform grid of options['period'] [s]."""
    from unexmin import description
    from unexmin.bag import BagError, read_messages, topic_types
    from unexmin.identify import dead_reckoning as dr
    from unexmin.replay.bag_io import pick_topic

    o = dict(DR_DEFAULTS, **(options or {}))
    try:
        types = topic_types(bag)
        topics = {}
        for role, default, kind in (
            ("imu", "imu", dr.IMU_TYPE),
            ("dvl", "dvl_twist", dr.DVL_TYPE),
            ("pressure", "pressure", dr.PRESSURE_TYPE),
        ):
            # the given topic, else /<robot>/<default>, else the bag's only topic of that type
            wanted = o[f"{role}_topic"] or (f"/{robot}/{default}" if f"/{robot}/{default}" in types else None)
            topics[role] = pick_topic(types, wanted, (kind,), f"{role} topic", True)
        messages = read_messages(bag, set(topics.values()))
    except BagError as e:
        raise ReplayError(str(e)) from None
    imu, dvl, prs = dr.sensor_arrays(messages, topics["imu"], topics["dvl"], topics["pressure"], mission.t0)
    try:
        mounts = dr.mounts_from_urdf(description.expand(name=robot, overrides=overrides), robot)
        t_end = min(imu[-1, 0], mission.duration) if len(imu) else 0.0
        grid = np.arange(max(0.0, imu[0, 0] if len(imu) else 0.0), t_end + 1e-9, o["period"])
        nav = dr.dead_reckon(
            imu,
            dvl,
            prs,
            mounts,
            grid,
            water_density,
            o["gravity"],
            o["atmospheric_pressure"],
            surface_z,
            o["level_time"],
            depth_time_constant=o["depth_time_constant"],
        )
    except (ValueError, description.DescriptionError) as e:
        raise ReplayError(f"{bag}: {e}") from None
    mission.topics.update({f"dead_reckoning_{k}": v for k, v in topics.items()})
    return nav


def identify_bag(
    bag,
    out_dir,
    robot="UX_1",
    motors_topic=MOTORS_TOPIC,
    pendulum_topic=None,
    vbs_topic=None,
    nav_topic=None,
    window_s=0.7,
    water_density=1000.0,
    surface_z=0.0,
    fixed=DEFAULT_FIXED,
    overrides=None,
    progress=True,
    mission=None,
    nav_source="odometry",
    dead_reckoning=None,
):
    """Identify from `bag` (or an already read `mission`) and write identified.yaml,
    identified_overrides.xacro and report.md (+ plots) into out_dir. Returns the identified.yaml dict.
    nav_source: "odometry" (the bag's navigation topic) or "dead-reckoning" (its IMU, DVL and pressure
    messages; `dead_reckoning`: options of DR_DEFAULTS)."""
    from unexmin import description
    from unexmin.identify import fit, model, report

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    wall0 = time.monotonic()
    if mission is None:
        mission = read_bag(bag, robot, motors_topic, pendulum_topic, vbs_topic, nav_topic)
    if nav_source not in NAV_SOURCES:
        raise ReplayError(f"--nav {nav_source}: expected one of {', '.join(NAV_SOURCES)}")
    if nav_source == "dead-reckoning":
        mission.nav = dead_reckoning_nav(bag, mission, robot, overrides, water_density, surface_z, dead_reckoning)
    if mission.nav is None:
        raise ReplayError(f"{bag}: no navigation in the bag (nav_msgs/Odometry or a pose topic): nothing to fit")
    for name in fixed:
        if name not in INDEX:
            raise ReplayError(f"--fix {name}: unknown parameter (one of {', '.join(PARAMS)})")
    try:
        physics = description.load(description.ROBOT_FILE, robot, overrides)
    except description.DescriptionError as e:
        raise ReplayError(str(e)) from None
    nominal = model.nominal_vector(physics)
    nominal[INDEX["buoyancy_kg"]] = water_density * physics.hydro.volume - physics.hydro.mass
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
    data["fit"]["navigation"] = {
        "source": nav_source,
        "topics": {k: v for k, v in mission.topics.items() if k == "nav" or k.startswith("dead_reckoning")},
    }
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
    lines = [
        f"buoyancy: {pm(data['buoyancy_kg'])} kg",
        f"centre of gravity - centre of buoyancy: ({vec(data['cog_m'])}) m",
        f"quadratic damping (surge sway heave roll pitch yaw): {vec(data['damping_quadratic'])}",
        f"linear damping: {vec(data['damping_linear'])}",
        "thrust gain: " + ", ".join(f"{k} " + pm({"value": v, "sigma": g["sigma"][k]}) for k, v in g["value"].items()),
        f"added mass: {pm(data['added_mass'])} kg; added inertia (roll pitch yaw): {vec(data['added_inertia'])}",
        "unidentifiable from this bag (kept at the description's value): "
        + (", ".join(data["unidentifiable"]) or "none"),
    ]
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
    ap.add_argument(
        "--nav",
        choices=NAV_SOURCES,
        default="odometry",
        help="navigation: the bag's odometry/pose "
        "topic (default), or dead reckoning from its IMU, DVL and pressure messages",
    )
    ap.add_argument("--imu-topic", help="sensor_msgs/Imu topic for --nav dead-reckoning (default /<robot>/imu)")
    ap.add_argument(
        "--dvl-topic",
        help="geometry_msgs/TwistWithCovarianceStamped DVL topic, DVL frame (default /<robot>/dvl_twist)",
    )
    ap.add_argument("--pressure-topic", help="sensor_msgs/FluidPressure topic (default /<robot>/pressure)")
    ap.add_argument("--gravity", type=float, default=9.81, help="[m/s^2] for the depth from pressure (default 9.81)")
    ap.add_argument(
        "--atmospheric-pressure",
        type=float,
        default=101325.0,
        help="[Pa] at the free surface, for the depth from pressure (default 101325)",
    )
    ap.add_argument(
        "--depth-time-constant",
        type=float,
        default=10.0,
        help="[s] of the complementary filter of pressure depth and DVL heave (default 10)",
    )
    ap.add_argument(
        "--level-time",
        type=float,
        default=1.0,
        help="[s] at the start of the bag the robot is at rest: "
        "the initial roll and pitch come from the accelerometer over it (default 1)",
    )
    ap.add_argument(
        "--window",
        type=float,
        default=0.7,
        help="[s] Savitzky-Golay window of the derivatives "
        "(default 0.7 for ground truth; 5 for a navigation filter's noisy output)",
    )
    ap.add_argument("--water-density", type=float, default=1000.0, help="[kg/m^3] (default 1000, fresh water)")
    ap.add_argument("--surface-z", type=float, default=0.0, help="[m] world z of the free surface (default 0)")
    ap.add_argument("--overrides", help="xacro overrides of the description the fit starts from (its prior)")
    ap.add_argument(
        "--fix",
        action="append",
        default=None,
        metavar="NAME",
        help=f"keep a parameter at the description's value (repeatable; default: {', '.join(DEFAULT_FIXED)})",
    )
    ap.add_argument("--free-all", action="store_true", help="fix nothing (added mass too)")
    ap.add_argument("--quiet", action="store_true", help="no progress bar")
    args = ap.parse_args(argv)
    fixed = () if args.free_all else tuple(args.fix if args.fix is not None else DEFAULT_FIXED)
    try:
        if not (args.window > 0 and math.isfinite(args.window)):
            raise ReplayError(f"--window {args.window}: expected a positive number of seconds")
        if not (args.water_density > 0 and math.isfinite(args.water_density)):
            raise ReplayError(f"--water-density {args.water_density}: expected a positive density [kg/m^3]")
        for flag, value in (
            ("--gravity", args.gravity),
            ("--depth-time-constant", args.depth_time_constant),
            ("--level-time", args.level_time),
        ):
            if not (value > 0 and math.isfinite(value)):
                raise ReplayError(f"{flag} {value}: expected a positive number")
        if not (args.atmospheric_pressure >= 0 and math.isfinite(args.atmospheric_pressure)):
            raise ReplayError(f"--atmospheric-pressure {args.atmospheric_pressure}: expected a pressure >= 0 [Pa]")
        dr_options = {
            "imu_topic": args.imu_topic,
            "dvl_topic": args.dvl_topic,
            "pressure_topic": args.pressure_topic,
            "gravity": args.gravity,
            "atmospheric_pressure": args.atmospheric_pressure,
            "depth_time_constant": args.depth_time_constant,
            "level_time": args.level_time,
        }
        data = identify_bag(
            args.bag,
            args.out,
            args.robot,
            args.motors_topic,
            args.pendulum_topic,
            args.vbs_topic,
            args.nav_topic,
            args.window,
            args.water_density,
            args.surface_z,
            fixed,
            args.overrides,
            not args.quiet,
            nav_source=args.nav,
            dead_reckoning=dr_options,
        )
    except ReplayError as e:
        print(f"identify: error: {e}", file=sys.stderr)
        return 2
    return print_summary(
        summary(data), f"written: {Path(args.out).resolve()}/identified.yaml, identified_overrides.xacro, report.md"
    )

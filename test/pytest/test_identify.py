"""Dynamics identification from a bag (python/unexmin/identify/, docs/identification.md).

- Pure parts: the thrust and pendulum histories against their closed forms (first-order step
  T (1 - exp(-t / tau)), the watchdog, the pendulum's constant speed), the rest attitude of the
  thesis prototype (8 deg roll, 14 deg pitch), and the overrides file round trip (parameters ->
  xacro -> expanded description -> the same parameters).
- Known robots: bags recorded with worlds/tools/make_sample_bag.py --overrides from robots whose
  buoyancy, centre of gravity, damping and thrust gains are set here (different seeds); every
  identified parameter must be within 10 % of the truth (or 0.02 kg / 2 mm where the truth is near
  zero), and the parameters the mission does not excite (roll damping) must be reported, at the
  nominal value.
- The shipped sample bag: identify, then replay with the result: final position error < 0.15 m
  (1.42 m with the nominal robot), yaw RMS < 1 deg.
- Sensor-grade navigation: seeded noise on the pose; the estimates stay within the bounds
  documented in docs/identification.md.

Bags are made once per session in a temporary folder (each launches its own world on a private
master, in a subprocess). Run: python -m pytest test/pytest/test_identify.py (after source scripts/env.sh)
"""

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml

from unexmin import description
from unexmin.control.esc import MODE_RPM, EscConverter
from unexmin.identify import model, vehicle
from unexmin.identify.cli import identify_bag, overrides_xacro
from unexmin.identify.model import DOF, INDEX, PARAMS
from unexmin.replay import read_bag

REPO = Path(__file__).resolve().parents[2]
SAMPLE_BAG = REPO / "worlds" / "bags" / "ux1_tank_perturbed.bag"
MAKER = REPO / "worlds" / "tools" / "make_sample_bag.py"


def ux1(overrides=None):
    """The UX-1's robot description (urdf/ux1.urdf.xacro with `overrides`)."""
    return description.load(description.ROBOT_FILE, overrides=overrides)


RHO_V = 1000.0 * 4.0 / 3.0 * math.pi * 0.3**3


def run(args, cwd, timeout=300):
    env = dict(os.environ, ROS_HOME=str(cwd / "ros_home"), ROS_LOG_DIR=str(cwd / "ros_log"), PYTHONWARNINGS="ignore")
    return subprocess.run(
        [sys.executable, *map(str, args)], capture_output=True, text=True, timeout=timeout, env=env, cwd=cwd
    )


# ---------------------------------------------------------------------------------------------
# pure
# ---------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def nominal_physics():
    return ux1()


def test_thrust_history_is_the_first_order_step_and_the_watchdog_stops_it(nominal_physics):
    p = nominal_physics
    tau = vehicle.time_constant(p.thrusters[0])
    rpm = EscConverter().to_command(MODE_RPM, [10.0] * 8)
    thrust_10 = EscConverter().to_thrust(MODE_RPM, rpm)[0][0]
    times = np.array([tau, 2 * tau, 0.5, 0.9, 1.0 + 0.002 + 3 * tau])
    th = model.thrust_history(p, [(0.0, MODE_RPM, tuple(rpm))], times)
    expected = thrust_10 * (1.0 - np.exp(-times[:4] / tau))
    assert th[:4, 0] == pytest.approx(expected, rel=1e-9)
    assert thrust_10 == pytest.approx(10.0, rel=0.02)
    # no command for 1 s (the watchdog): the thrust decays from its value at 1 s with the same tau
    at_timeout = thrust_10 * (1.0 - math.exp(-1.0 / tau))
    assert th[4, 0] == pytest.approx(at_timeout * math.exp(-(times[4] - 1.0) / tau), rel=1e-6)


def test_pendulum_turns_at_its_speed_and_locks_on_target(nominal_physics):
    p = nominal_physics
    target = math.radians(10.0)
    times = np.array([1.0, 1.25, 1.5, 3.0])
    a = model.pendulum_history(p, [(1.0, target)], times)
    assert a[0] == 0.0
    assert a[1] == pytest.approx(p.pendulum.speed * 0.25, abs=p.pendulum.speed * 0.002 + 1e-12)
    assert a[2] == pytest.approx(min(target, p.pendulum.speed * 0.5), abs=p.pendulum.speed * 0.002 + 1e-12)
    assert a[3] == pytest.approx(target, abs=1e-12)


def test_rest_attitude_of_the_thesis_prototype():
    roll, pitch = vehicle.rest_attitude(ux1(overrides=REPO / "urdf" / "ux1_perturbed.xacro"))
    assert math.degrees(roll) == pytest.approx(8.0, abs=1e-6)
    assert math.degrees(pitch) == pytest.approx(14.0, abs=1e-6)


def test_overrides_round_trip(tmp_path, nominal_physics):
    """Parameters -> overrides xacro -> expanded description -> the same parameters."""
    x = model.nominal_vector(nominal_physics)
    x[INDEX["buoyancy_kg"]] = -0.137
    x[INDEX["cog_x"] : INDEX["cog_z"] + 1] = [0.011, -0.017, -0.035]
    x[INDEX["thrust_gain_horizontal"]], x[INDEX["thrust_gain_vertical"]] = 0.83, 1.17
    for k, d in enumerate(DOF):
        x[INDEX[f"damping_linear_{d}"]] = 0.5 + k
        x[INDEX[f"damping_quadratic_{d}"]] = 10.0 * (k + 1)
    x[INDEX["added_mass"]] = 50.0
    x[INDEX["added_inertia_yaw"]] = 0.3

    class Result:
        pass

    fit = Result()
    fit.x = x
    path = tmp_path / "ov.xacro"
    path.write_text(overrides_xacro(fit, nominal_physics, 1000.0))
    back = model.nominal_vector(ux1(overrides=path))
    assert back == pytest.approx(x, rel=1e-7, abs=1e-9)


# ---------------------------------------------------------------------------------------------
# bags of known robots
# ---------------------------------------------------------------------------------------------
# The corners of the ranges (buoyancy -0.2 .. +0.2 kg, centre of gravity up to 2 cm off,
# damping x0.5 .. x2, thrust gains x0.8 .. x1.2 per group, different seeds), each robot trimmed to
# neutral with the VBS by its operator (--vbs-trim) so that it stays in mid-water:
# name: (buoyancy [kg], hull-less-pendulum CG offset from the nominal (0, 0, -0.02) x, y, z [m],
#        damping factor, thrust gains h, v, seed, spawn xyz [m])
# (spawn positions keep each robot's runs clear of the walls, the floor, the anchor and the surface)
ROBOTS = {
    "heavy_stiff": (-0.2, (0.015, -0.010, 0.0), 2.0, 0.8, 1.2, 1, (-1.7, -0.85, -1.0)),
    "light_soft": (0.2, (-0.004, 0.006, 0.0), 0.5, 1.2, 0.8, 2, (-1.7, -1.35, -0.9)),
    "cog_xy_2cm": (0.1, (0.01414, 0.01414, 0.0), 1.0, 1.2, 1.2, 3, (-1.7, -0.85, -1.0)),
    "cog_up_2cm": (-0.1, (0.0, 0.0, 0.02), 2.0, 0.8, 0.8, 4, (-1.7, -0.85, -1.0)),
    "cog_down_2cm": (0.05, (0.0, -0.02, -0.02), 0.5, 1.0, 1.2, 5, (-1.7, -1.35, -1.3)),
    "cog_forward_2cm": (-0.05, (0.02, 0.0, 0.0), 1.5, 0.9, 1.0, 6, (-1.7, -1.35, -1.0)),
}
NOMINAL_COG_BASE = (0.0, 0.0, -0.02)  # urdf/properties.xacro cog_x, cog_y, cog_z


def robot_overrides(buoyancy, cog_offset, damping, gain_h, gain_v):
    q = model.nominal_vector(ux1())
    lin = [q[INDEX[f"damping_linear_{d}"]] * damping for d in DOF]
    quad = [q[INDEX[f"damping_quadratic_{d}"]] * damping for d in DOF]
    cog = [c + o for c, o in zip(NOMINAL_COG_BASE, cog_offset)]
    return f"""<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="vehicle_mass" value="${{water_density * hull_volume - {buoyancy}}}"/>
  <xacro:property name="cog_x" value="{cog[0]}"/>
  <xacro:property name="cog_y" value="{cog[1]}"/>
  <xacro:property name="cog_z" value="{cog[2]}"/>
  <xacro:property name="linear_damping_diagonal" value="{' '.join(map(str, lin))}"/>
  <xacro:property name="quadratic_damping_diagonal" value="{' '.join(map(str, quad))}"/>
  <xacro:property name="thruster_gain_horizontal" value="{gain_h}"/>
  <xacro:property name="thruster_gain_vertical" value="{gain_v}"/>
</robot>
"""


@pytest.fixture(scope="session")
def bag_dir(tmp_path_factory):
    return tmp_path_factory.mktemp("identify_bags")


def make_bag(bag_dir, name):
    buoyancy, cog_offset, damping, gain_h, gain_v, seed, spawn_xyz = ROBOTS[name]
    overrides = bag_dir / f"{name}.xacro"
    bag = bag_dir / f"{name}.bag"
    if not bag.exists():
        overrides.write_text(robot_overrides(buoyancy, cog_offset, damping, gain_h, gain_v))
        # the operator trims the robot to neutral with the VBS, so it stays in mid-water, and commands
        # the runs in the level frame (--level), so a robot trimmed 20 deg nose down does not dive onto
        # the anchor or the floor along its tilted x axis
        out = run(
            [
                MAKER,
                "--overrides",
                overrides,
                "--out",
                bag,
                "--seed",
                seed,
                "--vbs-trim",
                buoyancy,
                "--spawn-xyz",
                *spawn_xyz,
                "--level",
            ],
            bag_dir,
        )
        assert out.returncode == 0, out.stderr[-3000:]
    return bag, overrides


def got_values(data):
    """{parameter name: identified value} of an identified.yaml dict."""
    got = {
        "buoyancy_kg": data["buoyancy_kg"]["value"],
        "added_mass": data["added_mass"]["value"],
        "thrust_gain_horizontal": data["thrust_gain"]["value"]["horizontal"],
        "thrust_gain_vertical": data["thrust_gain"]["value"]["vertical"],
    }
    for i, a in enumerate("xyz"):
        got[f"cog_{a}"] = data["cog_m"]["value"][i]
    for i, d in enumerate(DOF):
        got[f"damping_linear_{d}"] = data["damping_linear"]["value"][i]
        got[f"damping_quadratic_{d}"] = data["damping_quadratic"]["value"][i]
    for i, d in enumerate(DOF[3:]):
        got[f"added_inertia_{d}"] = data["added_inertia"]["value"][i]
    return got


def bound_of(name, truth, truth_physics, data):
    """Accepted error of a parameter: 10 % of the truth, or the issue's near-zero bounds."""
    want = truth[INDEX[name]]
    if name == "buoyancy_kg":
        return max(0.1 * abs(want), 0.02)
    if name.startswith("cog_"):
        return max(0.1 * abs(want), 0.002)
    if name.startswith("added_inertia"):
        return 0.1 * (truth_physics.hydro.inertia[DOF.index(name.split("_")[-1]) - 3] + want)
    if name.startswith("damping_linear"):
        # near zero (Stokes drag): 10 % of the damping force at the mission's RMS speed
        d = name.split("_")[-1]
        return max(0.1 * want, 0.1 * truth[INDEX[f"damping_quadratic_{d}"]] * data["fit"]["rms_speed"][d])
    return 0.1 * abs(want)


def check_identified(data, truth_physics):
    """Every identified parameter within 10 % of the truth, or the near-zero bounds of the issue."""
    truth = model.nominal_vector(truth_physics)
    skip = set(data["unidentifiable"]) | set(data["fixed"])
    got = got_values(data)
    errors = []
    for name in PARAMS:
        want, have = truth[INDEX[name]], got[name]
        if name in skip:
            assert have == pytest.approx(data["nominal"][name]), f"{name} is reported flat but not nominal"
            continue
        bound = bound_of(name, truth, truth_physics, data)
        if not abs(have - want) <= bound:
            errors.append(f"{name}: identified {have:.6g}, truth {want:.6g}, bound {bound:.3g}")
    assert not errors, "\n".join(errors)
    return got


@pytest.mark.long
@pytest.mark.parametrize("name", sorted(ROBOTS))
def test_identifies_robots_of_known_parameters(bag_dir, tmp_path, name):
    bag, overrides = make_bag(bag_dir, name)
    # the robot stayed in open water (the model has no contacts): 5 cm between the hull and the tank's
    # walls (x +-3 m, y +-2 m), floor (z = -3 m) and the free surface
    nav = read_bag(bag).nav
    clear = 0.3 + 0.05
    assert np.all(np.abs(nav[:, 1]) <= 3.0 - clear) and np.all(np.abs(nav[:, 2]) <= 2.0 - clear)
    assert np.all(nav[:, 3] >= -3.0 + clear) and np.all(nav[:, 3] <= -clear)
    data = identify_bag(bag, tmp_path / "out", progress=False)
    check_identified(data, ux1(overrides=overrides))
    # what the mission cannot excite is reported, not guessed: the rotational linear damping (no slow
    # turns), and a robot with its centre of gravity on the z axis never rolls (no roll moment from
    # any thruster, the weight or the pendulum): its roll damping has no support at all. (A tilted
    # robot's yaw turn rolls it a little: there roll damping may be identified, within 10 %.)
    assert "damping_linear_roll" in data["unidentifiable"]
    if ROBOTS[name][1][:2] == (0.0, 0.0):
        assert "damping_quadratic_roll" in data["unidentifiable"]
    # what the mission does excite is identified: the runs forward, sideways and down, the turn and the
    # pendulum's pitch swing, the buoyancy, the centre of gravity and both gains
    for d in ("surge", "sway", "heave", "pitch", "yaw"):
        assert f"damping_quadratic_{d}" not in data["unidentifiable"]
    assert not {"buoyancy_kg", "cog_x", "cog_y", "cog_z", "thrust_gain_horizontal", "thrust_gain_vertical"} & set(
        data["unidentifiable"]
    )
    written = yaml.safe_load((tmp_path / "out" / "identified.yaml").read_text())
    assert written["buoyancy_kg"]["value"] == pytest.approx(data["buoyancy_kg"]["value"])
    assert {"value", "sigma"} <= set(written["cog_m"]) and len(written["damping_quadratic"]["value"]) == 6
    assert (tmp_path / "out" / "report.md").read_text().count("![fit_") == 6


def test_sample_bag_identify_then_replay(tmp_path):
    data = identify_bag(SAMPLE_BAG, tmp_path / "id", progress=False)
    check_identified(data, ux1(overrides=REPO / "urdf" / "ux1_perturbed.xacro"))
    for d in ("surge", "sway", "heave", "yaw"):
        assert f"damping_quadratic_{d}" not in data["unidentifiable"]
    out = run(
        [
            "-m",
            "unexmin.replay",
            SAMPLE_BAG,
            "--out",
            tmp_path / "replay",
            "--quiet",
            "--overrides",
            tmp_path / "id" / "identified_overrides.xacro",
        ],
        tmp_path,
    )
    assert out.returncode == 0, out.stderr[-3000:]
    report = json.loads((tmp_path / "replay" / "report.json").read_text())
    assert report["errors_before"]["position_error_m"]["final"] > 1.3
    assert report["errors"]["position_error_m"]["final"] < 0.15
    assert report["errors"]["yaw_error_deg"]["rms"] < 1.0
    assert "before (nominal robot)" in out.stdout


def noisy(mission, sigma_pos, sigma_ang, seed):
    rng = np.random.default_rng(seed)
    nav = mission.nav.copy()
    nav[:, 1:4] += rng.normal(0.0, sigma_pos, (len(nav), 3))
    nav[:, 4:7] += rng.normal(0.0, sigma_ang, (len(nav), 3))
    mission.nav = nav
    return mission


def test_noisy_navigation_degrades_gracefully(tmp_path):
    """Odometry with 5 mm and 0.1 deg of white noise at 10 Hz, window 5 s: the bounds of
    docs/identification.md ("Sensor-grade navigation")."""
    mission = noisy(read_bag(SAMPLE_BAG), 0.005, math.radians(0.1), seed=7)
    data = identify_bag(SAMPLE_BAG, tmp_path, window_s=5.0, progress=False, mission=mission)
    assert not {"buoyancy_kg", "cog_x", "cog_y", "thrust_gain_horizontal", "thrust_gain_vertical"} & set(
        data["unidentifiable"]
    )
    truth = model.nominal_vector(ux1(overrides=REPO / "urdf" / "ux1_perturbed.xacro"))
    assert data["buoyancy_kg"]["value"] == pytest.approx(truth[INDEX["buoyancy_kg"]], abs=0.02)
    assert data["cog_m"]["value"] == pytest.approx(list(truth[INDEX["cog_x"] : INDEX["cog_z"] + 1]), abs=0.002)
    for g in ("horizontal", "vertical"):
        assert data["thrust_gain"]["value"][g] == pytest.approx(1.0, rel=0.15)
    for i, d in enumerate(DOF[:3]):
        if f"damping_quadratic_{d}" not in data["unidentifiable"]:
            assert data["damping_quadratic"]["value"][i] == pytest.approx(
                truth[INDEX[f"damping_quadratic_{d}"]], rel=0.25
            )


# ---------------------------------------------------------------------------------------------
# navigation by dead reckoning (IMU + DVL + pressure)
# ---------------------------------------------------------------------------------------------
def test_dead_reckoning_of_a_steady_turn_is_the_closed_form_circle(nominal_physics):
    """A level robot turning at a constant yaw rate r with a constant body velocity (u forward, h up):
    the DVL (below the centre, turned over) sees v_b + w x r_DVL in its own axes, the IMU the rate and
    (0, 0, g), the pressure sensor its own depth. Dead reckoning gives the circle x = (u/r) sin(r t),
    y = (u/r) (1 - cos(r t)), z = z0 + h t, yaw = r t -- also with the robot starting pitched, where
    the levelling must find the pitch from the accelerometer."""
    from unexmin.geometry import rpy_matrix
    from unexmin.identify import dead_reckoning as dr

    mounts = dr.mounts_from_urdf(description.expand())
    assert mounts.dvl_r == pytest.approx([0.0, 0.0, -0.3]) and mounts.pressure_r[2] == pytest.approx(-0.212132)
    u, h, r, z0, g, rho, p_atm = 0.2, 0.01, math.radians(10.0), -1.2, 9.81, 1000.0, 101325.0
    t = np.arange(0.0, 30.0 + 1e-9, 0.002)
    w_b = np.array([0.0, 0.0, r])
    imu = np.column_stack([t, np.tile(w_b, (len(t), 1)), np.tile([0.0, 0.0, g], (len(t), 1))])
    td = np.arange(0.0, 30.0 + 1e-9, 0.125)
    v_b = np.array([u, 0.0, h])  # level: body z is world z
    v_dvl = mounts.dvl_R.T @ (v_b + np.cross(w_b, mounts.dvl_r))
    dvl = np.column_stack([td, np.tile(v_dvl, (len(td), 1))])
    tp = np.arange(0.0, 30.0 + 1e-9, 0.1)
    z_sensor = z0 + h * tp + mounts.pressure_r[2]  # level: the mount's z offset is its world offset
    pressure = np.column_stack([tp, p_atm + rho * g * (0.0 - z_sensor)])
    t_out = np.arange(0.0, 30.0, 0.5)
    nav = dr.dead_reckon(imu, dvl, pressure, mounts, t_out, rho, g, p_atm, 0.0)
    R = u / r
    assert nav[:, 1] == pytest.approx(R * np.sin(r * t_out), abs=1e-4)
    assert nav[:, 2] == pytest.approx(R * (1.0 - np.cos(r * t_out)), abs=1e-4)
    assert nav[:, 3] == pytest.approx(z0 + h * t_out, abs=1e-4)
    assert nav[:, 6] == pytest.approx(r * t_out, abs=1e-6)
    assert nav[:, 4:6] == pytest.approx(0.0, abs=1e-9)
    # at rest, pitched 10 deg nose down and rolled 5 deg: the levelling finds both from the specific force
    rest = rpy_matrix((math.radians(5.0), math.radians(10.0), 0.0))
    f_rest = rest.T @ np.array([0.0, 0.0, g])
    imu_rest = np.column_stack([t[:500], np.zeros((500, 3)), np.tile(f_rest, (500, 1))])
    dvl_rest = np.column_stack([td[:8], np.zeros((8, 3))])
    p_rest = np.column_stack([tp[:10], np.full(10, p_atm + rho * g * 1.0)])
    nav = dr.dead_reckon(imu_rest, dvl_rest, p_rest, mounts, [0.5], rho, g, p_atm, 0.0)
    assert np.degrees(nav[0, 4:6]) == pytest.approx([5.0, 10.0], abs=1e-9)
    assert nav[0, 3] == pytest.approx(-1.0 - (rest @ mounts.pressure_r)[2], abs=1e-6)
    # pitching in place at q about the centre: the DVL 0.3 m below sees only the lever arm's w x r,
    # which dead reckoning must take out (the centre stays put)
    q = 0.1
    w_q = np.array([0.0, q, 0.0])
    t1 = t[t <= 2.0]
    imu_q = np.column_stack([t1, np.tile(w_q, (len(t1), 1)), np.tile([0.0, 0.0, g], (len(t1), 1))])
    td1 = td[td <= 2.0]
    rows = []
    for _ in td1:  # the DVL's axes turn with the body; its velocity in them is constant
        rows.append(mounts.dvl_R.T @ np.cross(w_q, mounts.dvl_r))
    dvl_q = np.column_stack([td1, np.array(rows)])
    p_q = np.column_stack([tp[tp <= 2.0], np.full(len(tp[tp <= 2.0]), p_atm + rho * g * 1.0)])
    nav = dr.dead_reckon(imu_q, dvl_q, p_q, mounts, [1.9], rho, g, p_atm, 0.0, level_time=0.002)
    assert nav[0, 1:3] == pytest.approx([0.0, 0.0], abs=1e-6)
    assert nav[0, 5] == pytest.approx(q * 1.9, abs=1e-6)
    with pytest.raises(ValueError, match="DVL"):
        dr.dead_reckon(imu, dvl[:1], pressure, mounts, t_out)


def test_dead_reckoning_navigation_degrades_gracefully(tmp_path):
    """The sample bag's own IMU, DVL and pressure messages (the simulator's noise, docs/sensors.md)
    instead of ground truth, window 5 s: the bounds of docs/identification.md ("Navigation by dead
    reckoning"), against the known truth; the damping the 42 s mission cannot pin with this
    navigation is reported flat, at the nominal value, never guessed."""
    from unexmin.identify.cli import main

    out = tmp_path / "dr"
    assert main([str(SAMPLE_BAG), "--out", str(out), "--nav", "dead-reckoning", "--window", "5", "--quiet"]) == 0
    data = yaml.safe_load((out / "identified.yaml").read_text())
    assert data["fit"]["navigation"]["source"] == "dead-reckoning"
    assert data["fit"]["navigation"]["topics"]["dead_reckoning_dvl"] == "/UX_1/dvl_twist"
    got = check_identified(data, ux1(overrides=REPO / "urdf" / "ux1_perturbed.xacro"))
    truth = model.nominal_vector(ux1(overrides=REPO / "urdf" / "ux1_perturbed.xacro"))
    kept = {"buoyancy_kg", "cog_x", "cog_y", "thrust_gain_horizontal"}
    assert not kept & set(data["unidentifiable"])
    assert abs(got["buoyancy_kg"] - truth[INDEX["buoyancy_kg"]]) < 0.002
    for a in "xy":
        assert abs(got[f"cog_{a}"] - truth[INDEX[f"cog_{a}"]]) < 0.001
    assert got["thrust_gain_horizontal"] == pytest.approx(1.0, abs=0.03)


def test_bad_input_is_one_error_line(tmp_path, bag_dir):
    out = run(["-m", "unexmin.identify", tmp_path / "missing.bag", "--out", tmp_path / "o", "--quiet"], tmp_path)
    assert out.returncode == 2
    assert out.stderr.strip().startswith("identify: error:") and len(out.stderr.strip().splitlines()) == 1
    out = run(["-m", "unexmin.identify", SAMPLE_BAG, "--out", tmp_path / "o", "--fix", "nonsense", "--quiet"], tmp_path)
    assert out.returncode == 2 and "--fix nonsense" in out.stderr
    out = run(
        [
            "-m",
            "unexmin.identify",
            SAMPLE_BAG,
            "--out",
            tmp_path / "o",
            "--nav",
            "dead-reckoning",
            "--depth-time-constant",
            "0",
            "--quiet",
        ],
        tmp_path,
    )
    assert out.returncode == 2 and "--depth-time-constant 0" in out.stderr
    # dead reckoning from a bag without the navigation sensors (recorded without --sensors)
    bag, _ = make_bag(bag_dir, "cog_up_2cm")
    out = run(["-m", "unexmin.identify", bag, "--out", tmp_path / "o", "--nav", "dead-reckoning", "--quiet"], tmp_path)
    assert out.returncode == 2 and len(out.stderr.strip().splitlines()) == 1
    assert "no imu topic (sensor_msgs/msg/Imu) in the bag" in out.stderr

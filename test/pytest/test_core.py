"""unexmin.core, the engine in-process (docs/python_api.md, "unexmin.core"), without ROS: the sensor schedule and
the physics step against closed forms, reset and seeds, numpy outputs, and every bad input as a Python exception
that names the argument (the interpreter survives each).

A sensor at rate f samples at the first physics step at or after k / f (docs/sensors.md): after n steps of
dt, its newest sample is stamped t_k = ceil(k / (f dt)) dt for the largest k with t_k <= n dt.
"""

import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from unexmin.core import World
from unexmin.description import ROBOT_FILE, expand


@pytest.fixture(scope="module")
def urdf():
    return expand(ROBOT_FILE, "UX_1")


@pytest.fixture(scope="module")
def rates(urdf):
    return {s.get("name"): float(s.get("rate")) for s in ET.fromstring(urdf).iter("sensor")}


@pytest.fixture(scope="module")
def world(urdf):
    return World("tank", seed=3, sensors="imu,dvl,pressure,m3,msis", descriptions={"UX_1": urdf})


def newest_stamp(rate, steps, dt):
    """t_k of the newest sample after `steps` physics steps of `dt` (see the module's documentation)."""
    k = math.floor(steps * dt * rate + 1e-9)
    while k > 0 and math.ceil(k / (rate * dt) - 1e-9) > steps:
        k -= 1
    return math.ceil(k / (rate * dt) - 1e-9) * dt


def test_time_and_sensor_schedules_follow_the_step(world, rates):
    world.reset(3)
    assert world.time == 0.0 and world.step_count == 0
    assert world.step(1183) == pytest.approx(1183 * world.dt, abs=1e-12)
    ux = world.robot("UX_1")
    assert set(ux.sensors) == {"imu", "dvl", "pressure", "m3", "msis"}
    for name in ux.sensors:
        assert ux.sample(name)["time"] == pytest.approx(newest_stamp(rates[name], 1183, world.dt), abs=1e-9), name


def test_samples_are_numpy_arrays_of_the_documented_shapes(world):
    world.reset(3)
    world.run_for(1.0)
    ux = world.robot("UX_1")
    imu = ux.sample("imu")
    assert imu["specific_force"].shape == (3,) and imu["angular_velocity"].shape == (3,)
    # at rest, level, in the tank: the accelerometer reads about +g along the body's up axis
    assert np.linalg.norm(imu["specific_force"]) == pytest.approx(9.81, abs=0.3)
    dvl = ux.sample("dvl")
    assert dvl["beam_range"].shape == (4,) and dvl["velocity"].shape == (3,)
    m3 = ux.sample("m3")
    assert m3["ranges"].dtype == np.float32 and m3["ranges"].shape == m3["intensities"].shape == m3["beam_angles"].shape
    assert np.isfinite(m3["ranges"]).any(), "the M3 sees the tank's walls"
    assert ux.sample("msis")["intensity"].ndim == 1
    # hydrostatics at the port: p_atm + rho g depth, the port 0.3 sin(45 deg) m below the hull centre (urdf:
    # hull_radius, pressure_elevation_deg; the robot level), within 4 sigma of the sensor's 100 Pa noise
    depth = -ux.state()["position"][2] + 0.3 * math.sin(math.radians(45.0))
    assert ux.sample("pressure")["pressure"] == pytest.approx(101325.0 + 1000.0 * 9.81 * depth, abs=400.0)


def test_thrust_moves_the_robot_and_reset_repeats_it_exactly(world):
    ux = world.robot("UX_1")
    runs = []
    for _ in range(2):
        world.reset(7)
        ux.thrusts([5, 0, -5, 0, 5, 0, -5, 0])
        world.step(1000)
        runs.append((ux.state()["position"], ux.sample("m3")["ranges"]))
    assert np.linalg.norm(runs[0][0] - World("tank", seed=7, sensors="none").robot("UX_1").state()["position"]) > 0.05
    np.testing.assert_array_equal(runs[0][0], runs[1][0])
    np.testing.assert_array_equal(runs[0][1], runs[1][1])
    world.reset(8)
    ux.thrusts([5, 0, -5, 0, 5, 0, -5, 0])
    world.step(1000)
    assert not np.array_equal(ux.sample("m3")["ranges"], runs[0][1]), "another seed, other M3 noise"


def test_commands_hold_without_a_watchdog_only_with_hold(urdf):
    w = World("tank", sensors="none", descriptions={"UX_1": urdf})
    ux = w.robot("UX_1")
    ux.thrusts([10.0] * 8)
    w.step(5 * 500, hold=False)  # 5 s: past the thruster watchdog, which zeroes the commands
    assert np.all(np.abs(ux.achieved_thrusts()) < 1e-9)  # the thrust decays to zero after the timeout
    w.reset()
    ux.thrusts([10.0] * 8)
    w.step(5 * 500)
    assert np.all(ux.achieved_thrusts() > 5.0)


def test_sensor_selection_and_visibility_of_the_world_file(urdf):
    w = World("tank", sensors="imu,m3", visibility="low", descriptions={"UX_1": urdf})
    assert set(w.robot("UX_1").sensors) == {"imu", "m3"} and w.sensors == "imu,m3" and w.visibility == "low"
    with pytest.raises(KeyError, match=r"sensor = 'dvl'.*imu, m3.*off by sensors='imu,m3'"):
        w.robot("UX_1").sample("dvl")
    assert World("tank", sensors="none", descriptions={"UX_1": urdf}).visibility == "none"  # tank.world's


@pytest.mark.parametrize(
    "call, error, words",
    [
        (lambda w: w.robot("UX_1").thrusts([1.0] * 7), ValueError, r"thrusts = 7 values.*expected 8 values"),
        (lambda w: w.robot("UX_1").thrusts([[1.0] * 8]), ValueError, r"thrusts = 8 values in 2 dimension"),
        (lambda w: w.robot("UX_1").thrusts([1.0] * 7 + [math.nan]), ValueError, r"thrusts\[7\] = nan"),
        (lambda w: w.robot("UX_1").thrusts([1e9] * 8), ValueError, r"thrusts\[0\] = 1000000000: expected \[-40, 40\]"),
        (lambda w: w.robot("UX_1").thrusts(["a"] * 8), (ValueError, TypeError), r""),
        (lambda w: w.robot("UX_1").pendulum(math.inf), ValueError, r"angle = inf: expected a finite number"),
        (lambda w: w.robot("UX_1").pendulum(3.0), ValueError, r"angle = 3: expected \[.*\] rad"),
        (lambda w: w.robot("UX_1").vbs(math.nan), ValueError, r"mass = nan"),
        (lambda w: w.robot("UX_1").vbs(-5.0), ValueError, r"mass = -5: expected \[.*\] kg"),
        (lambda w: w.robot("UX_9"), KeyError, r"robot = 'UX_9'.*UX_1"),
        (lambda w: w._core.state("UX_9"), KeyError, r"robot = 'UX_9'"),
        (lambda w: w.robot("UX_1").sample("sonar"), KeyError, r"sensor = 'sonar'.*imu"),
        (lambda w: w.step(-1), ValueError, r"n = -1"),
        (lambda w: w.step(1.5), ValueError, r"n = 1.5"),
        (lambda w: w.run_for(math.nan), ValueError, r"seconds = nan"),
        (lambda w: w.reset(-2), ValueError, r"seed = -2"),
        (lambda w: w.robot("UX_1").set_pose([0, 0]), ValueError, r"position = 2 values.*expected 3 numbers"),
        (lambda w: w.robot("UX_1").set_pose([0, math.nan, 0]), ValueError, r"position\[1\] = nan: expected a finite"),
        (lambda w: w.robot("UX_1").set_pose([0, 0, -1], [0, 0, 0]), ValueError, r"orientation = 3 values.*4 numbers"),
        (
            lambda w: w.robot("UX_1").set_pose([0, 0, -1], [0, 0, 0, 2]),
            ValueError,
            r"orientation = a quaternion of norm 2",
        ),
        (lambda w: w.robot("UX_1").set_pose([0, 0, -1], [0, math.inf, 0, 1]), ValueError, r"orientation\[1\] = inf"),
        (
            lambda w: w.robot("UX_1").set_rendering("dvl", False),
            ValueError,
            r"UX_1/dvl \(family dvl\) renders no images: expected .*a camera",
        ),
        (lambda w: w.robot("UX_1").set_rendering("camera_9", False), KeyError, r"sensor = 'camera_9'"),
        (lambda w: w.set_current(math.nan, steady=True), ValueError, r"speed = nan"),
    ],
)
def test_bad_commands_raise_naming_the_argument(world, call, error, words):
    before = world.robot("UX_1").state()["position"]
    with pytest.raises(error, match=words):
        call(world)
    np.testing.assert_array_equal(world.robot("UX_1").state()["position"], before)
    world.step(1)  # still alive


@pytest.mark.parametrize(
    "kwargs, error, words",
    [
        (dict(world="no_such_world"), FileNotFoundError, r"no_such_world"),
        (dict(robots=4), ValueError, r"robots = 4: expected 1, 2 or 3"),
        (dict(seed=-1), ValueError, r"seed = -1"),
        (dict(sensors="imu,sonar"), ValueError, r"sensors.*sonar"),
        (dict(visibility="murky"), ValueError, r"visibility = 'murky': expected none\|low\|medium\|high"),
        (dict(mode="fast"), ValueError, r"mode = 'fast': expected operational\|visual"),
        (dict(physics_rate=50.0), ValueError, r"physics_rate = 50: expected \[100, 20000\] Hz"),
        (dict(physics_rate=math.nan), ValueError, r"physics_rate = nan"),
        (dict(descriptions={"UX_2": "<robot/>"}), ValueError, r"descriptions.*no 'UX_1'"),
        (dict(descriptions={"UX_1": "<robot name='x'"}), ValueError, r"UX_1 description"),
        (dict(overrides={"UX_1": "/no/such/overrides.xacro"}), FileNotFoundError, r"overrides\['UX_1'\]"),
        (dict(overrides={"UX_2": ""}), KeyError, r"overrides: robot 'UX_2' is not spawned"),
    ],
)
def test_bad_worlds_raise_naming_the_argument(kwargs, error, words):
    with pytest.raises(error, match=words):
        World(**{"sensors": "none", **kwargs})


def test_a_world_file_that_is_not_one_raises(tmp_path):
    bad = tmp_path / "bad.world"
    bad.write_text("name: [unclosed\n")
    with pytest.raises(ValueError, match="bad.world"):
        World(str(bad), sensors="none")


def test_camera_images_are_views_without_a_copy(urdf):
    w = World("tank", sensors="camera", mode="visual", descriptions={"UX_1": urdf})
    ux = w.robot("UX_1")
    assert ux.sample("camera_0")["time"] < 0 and "image" not in ux.sample("camera_0")
    w.run_for(0.1)  # the cameras' first frame (10 fps)
    first, again = ux.sample("camera_0"), ux.sample("camera_0")
    image = first["image"]
    assert first["rendered"] and image.dtype == np.uint8 and image.ndim == 3 and image.shape[2] == 3
    assert not image.flags.owndata and np.shares_memory(image, again["image"]), "a view of the camera's frame"
    assert image.max() > image.min(), "the tank is in sight: the image is not uniform"
    operational = World("tank", sensors="camera", descriptions={"UX_1": urdf})
    operational.run_for(0.1)
    assert operational.robot("UX_1").sample("camera_0")["rendered"] is False


def test_step_releases_the_gil(urdf):
    import threading
    import time

    w = World("tank", sensors="all", descriptions={"UX_1": urdf})
    span = []

    def stepping():
        span.append(time.perf_counter())
        w.step(10000)  # 20 s of sim time with every sensor: 0.1 s or more of wall time
        span.append(time.perf_counter())

    thread = threading.Thread(target=stepping)
    turns = []
    thread.start()
    while thread.is_alive():  # this thread's Python runs while the other is inside step(), or it waits
        turns.append(time.perf_counter())
    thread.join()
    assert w.step_count == 10000
    inside = [t for t in turns if span[0] <= t <= span[1]]
    gaps = np.diff([span[0], *inside, span[1]])
    assert gaps.max() < 0.5 * (
        span[1] - span[0]
    ), f"this thread stood still for {gaps.max():.3f} s of the {span[1] - span[0]:.3f} s step(): it held the GIL"


def test_the_world_files_current_and_visibility_are_honoured(tmp_path, urdf):
    import yaml

    from unexmin.worlds.files import PACKAGE_DIR, link_meshes

    source = PACKAGE_DIR / "worlds" / "tank.world"
    world = yaml.safe_load(source.read_text())
    link_meshes(world["meshes"], str(source.parent), str(tmp_path))
    # a steady 0.2 m/s current towards +y (horizontal angle pi/2, no noise), murky water
    world["current"]["speed"].update(mean=0.2, noise=0.0)
    world["current"]["horizontal_angle"].update(mean=math.pi / 2, noise=0.0)
    world["visibility"]["level"] = "medium"
    path = tmp_path / "drift.world"
    path.write_text(yaml.safe_dump(world))
    w = World(str(path), sensors="none", descriptions={"UX_1": urdf})
    assert w.visibility == "medium"
    np.testing.assert_allclose(w.current, [0.2 * math.cos(math.pi / 2), 0.2, 0.0], atol=1e-12)
    start = w.robot("UX_1").state()["position"]
    w.run_for(10.0)
    moved = w.robot("UX_1").state()["position"] - start
    assert moved[1] > 0.3 and abs(moved[0]) < 0.2 * moved[1], f"the robot drifts with the current: {moved}"


def test_set_pose_teleports_at_rest_and_the_robot_falls_from_there(urdf):
    # Tank, still water: 1 kg of ballast makes the robot sink. Teleported at rest, it starts again from rest: the
    # same fall from the same pose, to the bit, whatever it did before.
    w = World("tank", sensors="none", descriptions={"UX_1": urdf})
    w.set_current(0.0, steady=True)
    ux = w.robot("UX_1")
    ux.vbs(1.0)
    w.run_for(1.0)
    assert np.linalg.norm(ux.state()["linear_velocity"]) > 0.01
    q = np.array([0.0, 0.0, math.sin(0.3), math.cos(0.3)])  # yaw 0.6 rad
    ux.set_pose([0.5, -0.25, -1.0], q)
    s = ux.state()
    np.testing.assert_allclose(s["position"], [0.5, -0.25, -1.0], atol=1e-12)
    np.testing.assert_allclose(s["orientation"], q, atol=1e-12)
    np.testing.assert_array_equal(s["linear_velocity"], np.zeros(3))
    np.testing.assert_array_equal(s["angular_velocity"], np.zeros(3))
    w.run_for(0.2)
    fall = -1.0 - ux.state()["position"][2]
    assert 0.0 < fall < 0.01 and abs(ux.state()["position"][0] - 0.5) < 1e-3
    ux.set_pose([0.5, -0.25, -1.0], q)
    w.run_for(0.2)
    assert -1.0 - ux.state()["position"][2] == fall, "the same fall from the same rest"


def test_set_pose_reads_strided_arrays_by_their_strides(urdf):
    # A column of a table and a reversed view: numpy hands them over without copying, with strides.
    w = World("tank", sensors="none", descriptions={"UX_1": urdf})
    table = np.array([[0.5, 9.0], [-0.25, 9.0], [-1.0, 9.0]])
    q = np.array([0.0, 0.0, math.sin(0.3), math.cos(0.3)])
    w.robot("UX_1").set_pose(table[:, 0], np.array([q[3], q[2], q[1], q[0]])[::-1])
    s = w.robot("UX_1").state()
    np.testing.assert_allclose(s["position"], [0.5, -0.25, -1.0], atol=1e-12)
    np.testing.assert_allclose(s["orientation"], q, atol=1e-12)


def test_set_rendering_renders_only_the_frames_asked_for(urdf):
    w = World("tank", sensors="camera", mode="visual", descriptions={"UX_1": urdf})
    ux = w.robot("UX_1")
    ux.set_rendering("camera_0", False)
    w.run_for(0.3)
    s = ux.sample("camera_0")
    assert s["count"] == 3 and s["rendered"] is False and "image" not in s
    assert ux.sample("camera_1")["rendered"] is True
    ux.set_rendering("camera_0", True)
    w.run_for(0.1)
    assert ux.sample("camera_0")["count"] == 4 and ux.sample("camera_0")["rendered"] is True
    ux.set_rendering("camera_0", False)
    w.reset()
    w.run_for(0.1)
    assert ux.sample("camera_0")["count"] == 1 and ux.sample("camera_0")["rendered"] is False, "kept across reset()"


def test_steady_current_and_no_sediment_in_the_tank(urdf):
    w = World("tank", sensors="none", descriptions={"UX_1": urdf})
    assert w.sediment_params["enabled"] is False  # off by default (tank.world has no sediment block)
    w.set_current(0.1, math.pi / 2, 0.0, steady=True)
    w.robot("UX_1").thrusts([0, 20, 0, 20, 0, -20, 0, -20])
    w.run_for(2.0)
    np.testing.assert_allclose(w.current, [0.0, 0.1, 0.0], atol=1e-12)  # no noise: the mean, exactly
    puffs = w.sediment()
    assert puffs["centre"].shape == (0, 3) and len(puffs["sigma"]) == 0


def test_set_current_without_steady_restores_the_world_files_noise(tmp_path, urdf):
    import yaml

    from unexmin.worlds.files import PACKAGE_DIR, link_meshes

    source = PACKAGE_DIR / "worlds" / "tank.world"
    world = yaml.safe_load(source.read_text())
    link_meshes(world["meshes"], str(source.parent), str(tmp_path))
    world["current"]["speed"].update(mean=0.2, min=0.0, max=0.5, noise=0.05, mu=0.1)  # a noisy speed
    path = tmp_path / "noisy.world"
    path.write_text(yaml.safe_dump(world))
    w = World(str(path), sensors="none", descriptions={"UX_1": urdf})
    w.set_current(0.2, steady=True)
    w.run_for(1.0)
    assert np.linalg.norm(w.current) == pytest.approx(0.2, abs=1e-12), "steady: the mean, exactly"
    w.set_current(0.2)  # the world file's noise again
    speeds = []
    for _ in range(20):
        w.run_for(0.1)
        speeds.append(np.linalg.norm(w.current))
    # 0.05 m/s/sqrt(s) over 2 s: the speed wanders by about 0.07 m/s; steady it would not move at all
    assert np.ptp(speeds) > 0.005, f"the speed stayed at the mean: {speeds}"


def test_contacts_of_a_robot_pressed_on_a_wall(urdf):
    w = World("tank", sensors="none", descriptions={"UX_1": urdf})
    ux = w.robot("UX_1")
    assert ux.contacts()["depth"].shape == (0,), "at its spawn pose the robot touches nothing"
    ux.thrusts([-20.0, 0, 20.0, 0, -20.0, 0, 20.0, 0])  # backwards, into the wall x = -3 (tank.world)
    w.run_for(4.0)
    c = ux.contacts()
    assert len(c["depth"]) > 0 and c["position"].shape == c["normal"].shape == (len(c["depth"]), 3)
    np.testing.assert_allclose(c["position"][:, 0], -3.0, atol=0.02)  # on the wall
    np.testing.assert_allclose(c["normal"], np.tile([1.0, 0.0, 0.0], (len(c["depth"]), 1)), atol=0.05)
    assert np.all(c["depth"] >= 0.0) and c["impulse"].sum() > 0.0


def test_a_world_stepping_in_another_thread_refuses_other_calls(urdf):
    import threading
    import time

    w = World("tank", sensors="all", descriptions={"UX_1": urdf})
    thread = threading.Thread(target=w.step, args=(20000,))
    thread.start()
    deadline = time.monotonic() + 30.0
    while not w._core.busy and thread.is_alive() and time.monotonic() < deadline:
        pass
    assert w._core.busy, "the step() call in the other thread never started"
    for call in (
        lambda: w.step(1),
        lambda: w.reset(),
        lambda: w.time,
        lambda: w.robot("UX_1").state(),
        lambda: w.robot("UX_1").sample("m3"),
        lambda: w.robot("UX_1").thrusts([0.0] * 8),
    ):
        with pytest.raises(RuntimeError, match="stepping .* in another thread"):
            call()
    thread.join()
    assert w.step_count == 20000 and not w._core.busy

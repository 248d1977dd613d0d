"""The scripting API's two back ends (docs/python_api.md, "Back ends"): the same script through the ROS simulator and
through the engine in-process gives the same odometry bit for bit; the core back end's collectors get every sample
(round(T f) samples over T s of a sensor at f Hz, stamped at the first physics step at or after k / f); latest()
follows sim.time and resets; bad launch arguments raise errors naming them.
"""

import math
import os
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from unexmin.description import ROBOT_FILE, expand

ENV_KEYS = ("ROS_MASTER_URI", "ROS_IP", "ROS_LOG_DIR")
pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")  # rospy's own
SEED = 4


def script(sim):
    """A short script of the public calls: thrusts, a wrench (the ROS side's allocator answers asynchronously, so
    it is not used here), pendulum, steps of several sizes, run_for, a reset with another seed. Returns the
    odometry rows [t, x y z, qx qy qz qw, u v w, p q r] after each step call."""

    def row(o):
        p, q, v, w = o.pose.pose.position, o.pose.pose.orientation, o.twist.twist.linear, o.twist.twist.angular
        return [o.header.stamp.to_sec(), p.x, p.y, p.z, q.x, q.y, q.z, q.w, v.x, v.y, v.z, w.x, w.y, w.z]

    ux = sim.robot("UX_1", streams="none")
    rows = []
    ux.thrusts([6.0, 2.0, -6.0, -2.0, 6.0, 2.0, -6.0, -2.0])
    ux.pendulum(0.1)
    for n in (1, 7, 250, 500):
        sim.step(n)
        rows.append(row(ux.odom()))
    ux.thrusts([0.0, 5.0, 0.0, 5.0, 0.0, -5.0, 0.0, -5.0])
    ux.vbs(0.05)
    sim.run_for(1.5)
    rows.append(row(ux.odom()))
    sim.reset(seed=SEED + 1)
    ux.thrusts([-3.0, 0.0, 3.0, 0.0, -3.0, 0.0, 3.0, 0.0])
    sim.run_for(0.5)
    rows.append(row(ux.odom()))
    return np.array(rows)


@pytest.fixture(scope="module")
def rates():
    urdf = expand(ROBOT_FILE, "UX_1")
    return {s.get("name"): float(s.get("rate")) for s in ET.fromstring(urdf).iter("sensor")}


def test_same_script_same_odometry_on_both_back_ends(tmp_path, monkeypatch):
    from unexmin import Simulation

    for k in ENV_KEYS:  # the launch sets them in this process: restored at the end
        monkeypatch.setenv(k, os.environ[k]) if k in os.environ else monkeypatch.delenv(k, raising=False)
    with Simulation.launch("tank", seed=SEED, log_dir=str(tmp_path), sensors="imu,dvl") as sim:
        assert sim.backend == "ros"
        ros = script(sim)
    with Simulation.launch("tank", seed=SEED, sensors="imu,dvl", backend="core") as sim:
        assert sim.backend == "core"
        core = script(sim)
    assert np.linalg.norm(core[4, 1:4] - core[0, 1:4]) > 0.01, "the thrusts did not move the robot"
    assert core[-1, 0] == pytest.approx(0.5)
    np.testing.assert_allclose(ros[:, 0], core[:, 0], rtol=0, atol=2e-9)  # stamps: whole nanoseconds both ways
    differ = np.argwhere(ros[:, 1:] != core[:, 1:])
    assert differ.size == 0, f"{len(differ)} values differ, first at row {differ[0][0]}, column {differ[0][1]}"


def test_core_collectors_get_every_sample(rates):
    from unexmin import Simulation

    sim = Simulation.launch("tank", seed=2, sensors="imu,dvl,pressure,m3", backend="core")
    ux = sim.robot("UX_1")
    dt = 1.0 / sim.physics_rate
    sim.run_for(0.3)  # collecting from t0 = 0.3 s on
    t0 = sim.time
    collectors = {name: ux.collect(name) for name in ("imu", "dvl", "pressure", "m3/scan")}
    sim.step(3)  # step calls of several sizes: the count must not depend on them
    sim.run_for(1.994)  # 997 steps
    sim.step(1000)
    T = sim.time - t0
    assert T == pytest.approx(4.0)
    for topic, c in collectors.items():
        rate = rates[topic.split("/")[0]]
        # samples k with t0 < ceil(k / (f dt)) dt <= t0 + T: closed form of the schedule
        stamps = [math.ceil(k / (rate * dt) - 1e-9) * dt for k in range(1, int(rate * (t0 + T)) + 3)]
        due = [s for s in stamps if t0 + 1e-9 < s <= t0 + T + 1e-9]
        assert len(c) == len(due) == round(T * rate), topic
        np.testing.assert_allclose(c.stamps(), due, atol=1e-9, err_msg=topic)
        counts = [m["count"] for m in c.messages]
        assert counts == list(range(counts[0], counts[0] + len(counts))), f"{topic}: a sample was skipped"
    c = collectors["dvl"]
    c.stop()
    sim.run_for(1.0)
    assert len(c) == round(T * rates["dvl"]), "a stopped collector went on collecting"
    sim.close()


def test_core_latest_follows_sim_time_and_reset(rates):
    from unexmin import Simulation

    with Simulation.launch("tank", sensors="imu,dvl", backend="core") as sim:
        ux = sim.robot("UX_1")
        with pytest.raises(LookupError, match="dvl"):
            ux.latest("dvl")
        sim.run_for(2.366)
        assert ux.latest("dvl")["time"] == pytest.approx(math.floor(2.366 * rates["dvl"]) / rates["dvl"])
        assert ux.latest("kvh/imu_raw")["time"] == pytest.approx(sim.time)
        with pytest.raises(LookupError, match="min|stamped"):
            ux.latest("dvl", min_stamp=2.3)
        with pytest.raises(LookupError, match="m3"):
            ux.latest("m3")  # not among the sensors that run
        sim.reset()
        with pytest.raises(LookupError):
            ux.latest("imu")


def test_core_wrench_is_the_thesis_allocation():
    from unexmin import Simulation
    from unexmin.control.allocation import ThrusterAllocator

    with Simulation.launch("tank", sensors="none", backend="core") as sim:
        ux = sim.robot("UX_1")
        ux.wrench(X=10.0, N=2.0)
        sim.run_for(2.0)  # thrusters settle to their commands (first order, tau << 2 s)
        expected = ThrusterAllocator().allocate([10.0, 0, 0, 0, 0, 2.0])[0]
        np.testing.assert_allclose(sim.world.robot("UX_1").achieved_thrusts(), expected, atol=1e-3)
        with pytest.raises(ValueError, match="N must be a finite"):
            ux.wrench(N=float("nan"))


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"backend": "gazebo"}, "backend = 'gazebo'"),
        ({"backend": "core", "mapping": "yes"}, "mapping = 'yes'"),
        ({"backend": "core", "record": "/tmp/x.bag"}, "record = '/tmp/x.bag': the core back end cannot"),
        ({"backend": "core", "map_file": "m.bt"}, "map_file = 'm.bt': the map is only made with mapping=True"),
        ({"backend": "core", "launch_file": "x.launch"}, "launch_file = 'x.launch'"),
        ({"backend": "core", "log_dir": "/tmp"}, "log_dir = '/tmp'"),
        ({"backend": "core", "mode": "sonar"}, "mode = 'sonar'"),
        ({"backend": "core", "visibility": "murky"}, "visibility = 'murky'"),
        ({"backend": "core", "sensors": ""}, "sensors = ''"),
        ({"backend": "core", "sensors": "imu,gps"}, "sensors"),
        ({"backend": "ros", "mode": "sonar"}, "mode = 'sonar'"),
        ({"backend": "ros", "mapping": "yes"}, "mapping = 'yes'"),
        ({"backend": "ros", "launch_file": "x.launch", "mode": "visual"}, "launch_file = x.launch: .* mode"),
    ],
)
def test_bad_launch_arguments_are_named(kwargs, match):
    from unexmin import Simulation

    with pytest.raises(ValueError, match=match):
        Simulation.launch("tank", **kwargs)


def test_missing_overrides_file_is_named():
    from unexmin import Simulation

    for backend in ("ros", "core"):
        with pytest.raises(FileNotFoundError, match="no-such.xacro"):
            Simulation.launch("tank", backend=backend, overrides={"UX_1": "/nonexistent/no-such.xacro"})

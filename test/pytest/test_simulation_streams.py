"""Sensor data as a script expects it (python/unexmin/scripting/ros_backend.py, python/unexmin/scripting/streams.py).

One lockstep tank world in this process. Expected values are closed forms of the sensor rates
written in the robot description (`<sensor rate=...>` of /UX_1/robot_description): sample k of a
sensor at rate f is taken at the first physics step at or after k / f, so at
t_k = ceil(k / (f dt)) dt, dt = 1 / physics rate.

- latest(topic), asked for the first time after any steps, is the newest sample at or before
  sim.time: stamp t_k for the largest k with t_k <= sim.time (500 Hz KVH after run_for(3.0): 3.0);
  its class comes from the topic's type; a wrong class, an unknown topic, or a sensor that has not
  sampled yet give one clear error at once.
- collect(topic) over steps of T s gets exactly floor(T f) messages stamped t_k, none lost: several
  step calls of odd lengths, and one call far longer than the simulator's per-topic queue holds.
  The robot streams (odometry, thrust) also publish at the end of each step call.
"""

import math
import os
import xml.etree.ElementTree as ET

import pytest

ENV_KEYS = ("ROS_MASTER_URI", "ROS_IP", "ROS_LOG_DIR")
pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")  # rospy's own (notifyAll, warn)
# topic of UX_1 -> the <sensor> whose samples it carries
SENSOR_OF = {
    "imu": "imu",
    "imu/mag": "imu",
    "kvh/imu_raw": "imu",
    "dvl": "dvl",
    "dvl_sonar0": "dvl",
    "pressure": "pressure",
    "m3/scan": "m3",
    "tritech_micron/scan": "msis",
}


@pytest.fixture(scope="module")
def sim(tmp_path_factory):
    from unexmin import Simulation

    saved = {k: os.environ.get(k) for k in ENV_KEYS}
    with Simulation.launch("tank", robots=1, seed=3, log_dir=str(tmp_path_factory.mktemp("world"))) as s:
        yield s
    for k, v in saved.items():
        if v is None:
            os.environ.pop(k, None)
        else:
            os.environ[k] = v


@pytest.fixture(scope="module")
def rates(sim):
    """{sensor name: rate [Hz]} from UX_1's robot description, as the simulator reads it."""
    import rospy

    root = ET.fromstring(rospy.get_param("/UX_1/robot_description"))
    return {s.get("name"): float(s.get("rate")) for s in root.iter("sensor") if s.get("rate")}


def sample_time(k, rate, dt):
    """[s] of sample k of a sensor at `rate`: the first physics step at or after k / rate."""
    return math.ceil(k / (rate * dt) - 1e-9) * dt


def newest_sample(t, rate, dt):
    """[s] of the newest sample at or before t (t on the physics grid)."""
    return sample_time(math.floor(t * rate + 1e-9), rate, dt)


def test_latest_after_run_for_is_the_sample_at_sim_time(sim):
    from kvh_1775.msg import ImuRawKvh

    sim.reset(seed=3)
    ux = sim.robot("UX_1")
    sim.run_for(3.0)
    msg = ux.latest("kvh/imu_raw", ImuRawKvh)
    assert isinstance(msg, ImuRawKvh)
    assert msg.header.stamp.to_sec() == pytest.approx(3.0, abs=1e-9)
    assert ux.latest("kvh/imu_raw") is msg  # the class is found from the topic's type


def test_latest_of_every_sensor_topic_first_asked_after_steps_of_odd_lengths(sim, rates):
    sim.reset(seed=3)
    ux = sim.robot("UX_1")
    dt = 1.0 / sim.physics_rate
    sim.run_for(1.1)
    sim.step(383)  # t = 1.866 s: between samples of every slow sensor
    sim.run_for(0.5)  # t = 2.366 s
    t = sim.time
    assert t == pytest.approx(1.1 + 383 * dt + 0.5, abs=1e-9)
    for topic, sensor in SENSOR_OF.items():
        expected = newest_sample(t, rates[sensor], dt)
        assert ux.latest(topic).header.stamp.to_sec() == pytest.approx(expected, abs=1e-9), topic
    # e.g. the DVL at 8 Hz: sample 18 at 2.25 s; the pressure sensor at 10 Hz: 2.3 s
    assert ux.latest("dvl").header.stamp.to_sec() == pytest.approx(2.25, abs=1e-9)


def test_latest_errors_are_immediate_and_say_why(sim):
    from sensor_msgs.msg import Imu

    sim.reset(seed=3)
    ux = sim.robot("UX_1")
    with pytest.raises(TypeError, match="kvh_1775/ImuRawKvh"):
        ux.latest("kvh/imu_raw", Imu)
    with pytest.raises(LookupError, match="nobody publishes /UX_1/no_such_sensor"):
        ux.latest("no_such_sensor")
    sim.step(1)  # t = 2 ms: the IMU has sampled, the DVL (8 Hz) not
    assert ux.latest("imu").header.stamp.to_sec() == pytest.approx(0.002, abs=1e-9)
    with pytest.raises(LookupError, match="no message on /UX_1/dvl up to sim time 0.002000 s"):
        ux.latest("dvl")


def test_collect_gets_every_message_of_the_following_steps(sim, rates):
    sim.reset(seed=3)
    ux = sim.robot("UX_1")
    dt = 1.0 / sim.physics_rate
    sim.run_for(0.25)  # collectors start at t0, mid-run
    t0 = sim.time
    topics = ("imu", "kvh/imu_raw", "dvl", "pressure", "m3/scan")
    cols = {t: ux.collect(t) for t in topics}
    thrust = ux.collect("thrusters/0/thrust")  # a robot stream without header
    ends = []  # physics step count after each call
    for seconds in (0.7, 0.036, 1.014):  # three step calls, 1.75 s in all
        sim.run_for(seconds)
        ends.append(round(sim.time / dt))
    for c in cols.values():
        c.stop()
    thrust.stop()
    T = sim.time - t0
    assert T == pytest.approx(1.75, abs=1e-9)
    for topic, c in cols.items():
        rate = rates[SENSOR_OF[topic]]
        k0, k1 = math.floor(t0 * rate + 1e-9), math.floor(sim.time * rate + 1e-9)
        expected = [sample_time(k, rate, dt) for k in range(k0 + 1, k1 + 1)]
        assert len(c) == len(expected), topic
        assert c.stamps() == pytest.approx(expected, abs=1e-9), topic
    assert len(cols["imu"]) == round(T * 500)  # every physics step at 500 Hz
    # The thrust stream: every `every` physics steps, and at the end of a step call that is not on that grid.
    import rospy

    every = round(sim.physics_rate / rospy.get_param("/simulator/thrust_rate", 50.0))
    on_grid = sum(1 for s in range(round(t0 / dt) + 1, ends[-1] + 1) if s % every == 0)
    assert len(thrust) == on_grid + sum(1 for e in ends if e % every) == 88 + 2
    sim.run_for(0.1)
    assert len(cols["imu"]) == round(T * 500)  # stopped: nothing more


def test_collect_over_a_step_longer_than_the_simulators_queues_loses_nothing(sim, rates):
    sim.reset(seed=3)
    ux = sim.robot("UX_1")
    dt = 1.0 / sim.physics_rate
    with ux.collect("imu") as imu, ux.collect("dvl") as dvl:
        sim.run_for(24.0)  # the simulator queues 20 s of samples per topic
    assert len(imu) == round(24.0 * rates["imu"])  # 12000
    assert imu.stamps() == pytest.approx([k * dt for k in range(1, 12001)], abs=1e-9)
    assert len(dvl) == round(24.0 * rates["dvl"])  # 192
    assert dvl.stamps()[-1] == pytest.approx(24.0, abs=1e-9)
    assert ux.latest("imu").header.stamp.to_sec() == pytest.approx(24.0, abs=1e-9)


def test_reset_forgets_the_newest_messages(sim):
    ux = sim.robot("UX_1")
    sim.run_for(0.2)
    sim.reset(seed=3)
    assert ux.latest("odom").header.stamp.to_sec() == pytest.approx(0.0, abs=1e-9)  # published by the reset
    with pytest.raises(LookupError, match="since the start or the last reset"):
        ux.latest("imu")

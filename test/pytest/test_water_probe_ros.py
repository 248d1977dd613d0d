"""The water probe over ROS against unexmin.core (docs/water_probe.md, "Topics"): the tank with the UX-1's probe
alone, seed 5, 3 s of lockstep; every sample on probe/temperature (sensor_msgs/Temperature), probe/pressure
(sensor_msgs/FluidPressure) and probe/water_quality (unexmin/WaterQuality), stamped k / 1 Hz in the probe's frame,
and each number equal, bit for bit, to the in-process engine's sample of the same seed."""

import pytest
from lockstep_pairs import ros_environment_kept

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")  # rospy's own
SEED = 5
SECONDS = 3
CHANNELS = ("temperature", "conductivity", "conductivity_25", "ph", "redox", "oxygen", "pressure")


def run_ros(log_dir):
    from sensor_msgs.msg import FluidPressure, Temperature

    from unexmin import Simulation
    from unexmin.msg import WaterQuality

    with ros_environment_kept():
        with Simulation.launch("tank", seed=SEED, sensors="water_probe", log_dir=log_dir) as sim:
            ux = sim.robot("UX_1", streams=[])
            with (
                ux.collect("probe/temperature", Temperature) as t,
                ux.collect("probe/pressure", FluidPressure) as p,
                ux.collect("probe/water_quality", WaterQuality) as q,
            ):
                sim.step(round(sim.physics_rate) * SECONDS)
            return list(t.messages), list(p.messages), list(q.messages)


def run_core():
    from unexmin.core import World

    w = World("tank", sensors="water_probe", seed=SEED)
    ux = w.robot("UX_1")
    samples = []
    for _ in range(round(1.0 / w.dt) * SECONDS):
        w.step(1)
        s = ux.sample("water_probe")
        if s["count"] > len(samples):
            samples.append(s)
    return samples


@pytest.fixture(scope="module")
def both(tmp_path_factory):
    return run_ros(str(tmp_path_factory.mktemp("probe"))), run_core()


def test_every_sample_is_sent_on_each_topic_in_the_probe_frame(both):
    (temperature, pressure, quality), core = both
    assert len(core) == SECONDS
    for messages in (temperature, pressure, quality):
        assert [m.header.stamp.to_sec() for m in messages] == pytest.approx([1.0, 2.0, 3.0], abs=1e-9)
        assert {m.header.frame_id for m in messages} == {"UX_1/water_probe_link"}


def test_the_messages_hold_the_in_process_samples_bit_for_bit(both):
    (temperature, pressure, quality), core = both
    for t, p, q, s in zip(temperature, pressure, quality, core):
        assert t.temperature == s["temperature"] and p.fluid_pressure == s["pressure"]
        assert [getattr(q, c) for c in CHANNELS] == [s[c] for c in CHANNELS]
        assert t.variance == q.temperature_variance == pytest.approx(0.01**2 + 0.001**2 / 12)
        assert p.variance == q.pressure_variance == pytest.approx(100.0**2 + 10.0**2 / 12)
    # fresh water at 10 degC in the tank (no water column), the robot 1 m down
    assert core[-1]["temperature"] == pytest.approx(10.0, abs=0.06)
    assert 101325.0 + 1000.0 * 9.81 * 0.5 < core[-1]["pressure"] < 101325.0 + 1000.0 * 9.81 * 2.0

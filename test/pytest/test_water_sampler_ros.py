"""The water sampler over ROS against unexmin.core, bit for bit (docs/water_sampler.md).

The tank with one UX-1, seed 3, lockstep: 0.1 s of steps, /UX_1/sampler/fire (std_srvs/Trigger), 2.2 s of steps, a
second fire while nothing fills and one while a bottle fills; the simulator launched and stepped through
`unexmin.Simulation`, every /UX_1/sampler/result collected. The same in-process (`unexmin.core.World`, Robot.fire).
The one WaterSample and the core's result must be equal, not close: the two front ends run one engine.
"""

import math

import pytest
from lockstep_pairs import ros_environment_kept

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")  # rospy's own
SEED = 3


def run_ros(log_dir):
    import rospy
    from std_srvs.srv import Trigger

    from unexmin import Simulation

    with ros_environment_kept():
        with Simulation.launch("tank", robots=1, seed=SEED, sensors="water_sampler", log_dir=log_dir) as sim:
            ux = sim.robot("UX_1", streams=["sampler/result"])
            rospy.wait_for_service("/UX_1/sampler/fire", timeout=30.0)
            fire = rospy.ServiceProxy("/UX_1/sampler/fire", Trigger)
            with ux.collect("sampler/result") as results:
                sim.step(50)
                first = fire()
                sim.step(1100)
                second = fire()
                busy = fire()
                sim.step(10)
            return first, second, busy, list(results.messages)


def run_core():
    from unexmin.core import World

    w = World("tank", seed=SEED, sensors="water_sampler")
    ux = w.robot("UX_1")
    w.step(50)
    ux.fire("water_sampler")
    w.step(1100)
    return ux.sample("water_sampler")


def test_the_fire_service_and_the_result_topic_match_the_core(tmp_path):
    first, second, busy, messages = run_ros(str(tmp_path))
    assert first.success and first.message == "filling bottle 1 of 4"
    assert second.success and second.message == "filling bottle 2 of 4"
    assert not busy.success and "UX_1/water_sampler: bottle 2 of 4 is filling" in busy.message
    assert len(messages) == 1, [m.bottle for m in messages]
    m = messages[0]
    core = run_core()
    assert m.header.stamp.to_sec() == pytest.approx(0.1 + 2.0, abs=1e-9)
    assert m.header.frame_id == "world" and m.sensor == "water_sampler" and m.trigger == "manual" and m.bottle == 0
    assert m.start_time == core["result_start_time"][0] and m.end_time == core["result_end_time"][0]
    assert [m.position.x, m.position.y, m.position.z] == list(core["result_position"][0])
    for key in ("depth", "density", "volume", "mass"):
        assert getattr(m, key) == core["result_" + key][0], key
    for key in ("temperature", "conductivity", "salinity", "ph", "redox", "oxygen", "turbidity"):
        assert math.isnan(getattr(m, key)) and math.isnan(core["result_" + key][0]), key  # the tank has no column
    assert m.density == 1000.0 and m.mass == 0.5  # uniform water: its value, exactly
    assert m.bottles_left == 3

"""A mixed team in-process and over ROS: the same samples, bit for bit (docs/python_api.md, "unexmin.core").

The mine with a UX-1, a BlueROV2 Heavy and a REMUS 100 (vehicles ux1, bluerov2_heavy, remus100: UX_1, ROV_1, AUV_1),
seed 6, 2 s of lockstep with the ROV and the AUV driven by constant thrusts: the ROS simulator launched and stepped
through `unexmin.Simulation` (every /ROV_1/imaging_sonar/polar and /AUV_1/side_scan/waterfall image collected, the
odometry of each robot after each step call), and the engine in-process (`unexmin.core.World(vehicles=...)`, the
same commands, the samples read through the families' descriptions). The polar images, the waterfalls and every
odometry value must be equal, not close: the two front ends run one engine.
"""

import numpy as np
import pytest
from lockstep_pairs import odometry_row, ros_environment_kept, state_row

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")  # rospy's own
TEAM = ["ux1", "bluerov2_heavy", "remus100"]
SEED = 6
CHUNK = 10  # physics steps per step call
SECONDS = 2
SENSORS = "imaging_sonar,side_scan"


def thrusts(count, sign):
    """A forward-ish push: alternate thrusters at +-3 N."""
    return [sign * (3.0 if k % 2 == 0 else -3.0) for k in range(count)]


def run_ros(log_dir):
    from unexmin import Simulation

    with ros_environment_kept():
        with Simulation.launch("mine", vehicles=TEAM, seed=SEED, sensors=SENSORS, log_dir=log_dir) as sim:
            steps = round(sim.physics_rate) * SECONDS
            streams = {"UX_1": [], "ROV_1": ["imaging_sonar/polar"], "AUV_1": ["side_scan/waterfall"]}
            robots = {n: sim.robot(n, streams=topics) for n, topics in streams.items()}
            rov, auv = robots["ROV_1"], robots["AUV_1"]
            rov.thrusts(thrusts(rov.thruster_count, 1.0))
            auv.thrusts(thrusts(auv.thruster_count, 1.0))
            rows = []
            with rov.collect("imaging_sonar/polar") as polar, auv.collect("side_scan/waterfall") as fall:
                for _ in range(steps // CHUNK):
                    sim.step(CHUNK)
                    rows.append([sim.time] + [v for n in robots for v in odometry_row(robots[n].odom())])
            images = {
                "polar": [(m.header.stamp.to_sec(), image(m)) for m in polar.messages],
                "waterfall": [(m.header.stamp.to_sec(), image(m)) for m in fall.messages],
            }
    return np.array(rows), images


def image(m):
    assert m.encoding == "mono8", m.encoding
    return np.frombuffer(bytes(m.data), np.uint8).reshape(m.height, m.width)


def run_core():
    from unexmin.core import World

    w = World("mine", vehicles=TEAM, seed=SEED, sensors=SENSORS)
    robots = {n: w.robot(n) for n in ("UX_1", "ROV_1", "AUV_1")}
    rov, auv = robots["ROV_1"], robots["AUV_1"]
    rov.thrusts(thrusts(rov.thruster_count, 1.0))
    auv.thrusts(thrusts(auv.thruster_count, 1.0))
    rows, images = [], {"polar": [], "waterfall": []}
    steps = round(1.0 / w.dt) * SECONDS
    for _ in range(steps // CHUNK):
        for _ in range(CHUNK):  # one step at a time, to see every ping
            w.step(1)
            for key, robot, sensor in (("polar", rov, "imaging_sonar"), ("waterfall", auv, "side_scan")):
                s = robot.sample(sensor)
                if s["count"] > len(images[key]):
                    images[key].append((s["time"], s[key].copy()))
        row = [w.time]
        for n in robots:
            st = robots[n].state()
            row += state_row(st)
        rows.append(row)
    return np.array(rows), images


@pytest.fixture(scope="module")
def both(tmp_path_factory):
    return run_ros(str(tmp_path_factory.mktemp("team"))), run_core()


def test_a_mixed_team_moves_the_same_bit_for_bit(both):
    (ros_rows, _), (core_rows, _) = both
    assert ros_rows.shape == core_rows.shape == (SECONDS * 50, 1 + 3 * 13)
    moved = np.linalg.norm(core_rows[-1, 14:17] - core_rows[0, 14:17])
    assert moved > 0.005, f"ROV_1 moved {moved} m: the commands did not drive it"
    differ = np.argwhere(ros_rows != core_rows)
    assert differ.size == 0, f"{len(differ)} odometry values differ; first at row {differ[0][0]}, column {differ[0][1]}"


@pytest.mark.parametrize("key, rate", [("polar", 10), ("waterfall", 10)])
def test_sonar_images_are_the_same_bit_for_bit(both, key, rate):
    (_, ros_images), (_, core_images) = both
    assert len(ros_images[key]) == len(core_images[key]) == SECONDS * rate
    for (t_ros, a), (t_core, b) in zip(ros_images[key], core_images[key]):
        assert t_ros == pytest.approx(t_core, abs=1e-9)
        assert a.shape == b.shape, f"{key} at t = {t_core} s: {a.shape} against {b.shape}"
        np.testing.assert_array_equal(a, b, err_msg=f"{key} at t = {t_core} s")
    assert core_images[key][-1][1].max() > 0, f"the last {key} is blank: the comparison would hold for nothing"

"""unexmin.core against the ROS simulator (docs/python_api.md, "unexmin.core"): the same world, seed and commands
give the same trajectory and sensor samples in lockstep, bit for bit.

10 s of the tank with seed 5, every sensor on, both ways: the ROS simulator launched and stepped through
`unexmin.Simulation` (step calls of 10 physics steps, the odometry each answers, every /UX_1/m3/scan message
collected), and the engine in-process (`unexmin.core.World`). The commands change every second (thrusts that
drive the robot forward, turn it, dive, and a pendulum angle). Every odometry field and every M3 range and
intensity must be equal, not close: the two run the same C++ code in the same order.
"""

import numpy as np
import pytest
from lockstep_pairs import odometry_row, ros_environment_kept, state_row

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")  # rospy's own
SEED = 5
CHUNK = 10  # physics steps per step call (50 Hz of odometry at 500 Hz)
SECONDS = 10


def commands(second):
    """(thrusts [N] for M0..M7, pendulum angle [rad]) during second `second` of the run."""
    forward = [4.0, 0.0, -4.0, 0.0, 4.0, 0.0, -4.0, 0.0]
    schedule = [
        (forward, 0.0),
        ([6.0, 2.0, -6.0, -2.0, 6.0, 2.0, -6.0, -2.0], 0.1),
        ([0.0, 5.0, 0.0, 5.0, 0.0, -5.0, 0.0, -5.0], 0.1),
        ([-3.0, 0.0, 3.0, 0.0, -3.0, 0.0, 3.0, 0.0], -0.1),
        ([0.0] * 8, 0.0),
    ]
    return schedule[second % len(schedule)]


def run_ros(log_dir):
    from unexmin import Simulation

    with ros_environment_kept():
        with Simulation.launch("tank", robots=1, seed=SEED, log_dir=log_dir) as sim:
            steps_per_second = round(sim.physics_rate)
            ux = sim.robot("UX_1", streams=["m3/scan"])
            rows = []
            with ux.collect("m3/scan") as scans:
                for second in range(SECONDS):
                    thrusts, angle = commands(second)
                    ux.thrusts(thrusts)
                    ux.pendulum(angle)
                    for _ in range(steps_per_second // CHUNK):
                        sim.step(CHUNK)
                        rows.append([sim.time] + odometry_row(ux.odom()))
            m3 = [
                (s.header.stamp.to_sec(), np.array(s.ranges, np.float32), np.array(s.intensities, np.float32))
                for s in scans.messages
            ]
    return np.array(rows), m3


def run_core():
    from unexmin.core import World

    w = World("tank", robots=1, seed=SEED)
    ux = w.robot("UX_1")
    steps_per_second = round(1.0 / w.dt)
    rows, m3 = [], []
    for second in range(SECONDS):
        thrusts, angle = commands(second)
        ux.thrusts(thrusts)
        ux.pendulum(angle)
        for _ in range(steps_per_second // CHUNK):
            for _ in range(CHUNK):  # one step at a time, to see every M3 ping
                w.step(1)
                s = ux.sample("m3")
                if s["count"] > len(m3):
                    m3.append((s["time"], s["ranges"], s["intensities"]))
            st = ux.state()
            rows.append([w.time, *state_row(st)])
    return np.array(rows), m3


@pytest.fixture(scope="module")
def both(tmp_path_factory):
    return run_ros(str(tmp_path_factory.mktemp("world"))), run_core()


def test_odometry_is_the_same_bit_for_bit(both):
    (ros_rows, _), (core_rows, _) = both
    assert ros_rows.shape == (SECONDS * 50, 14) == core_rows.shape
    travelled = np.linalg.norm(core_rows[-1, 1:4] - core_rows[0, 1:4])
    assert travelled > 0.1, f"the robot moved {travelled} m: the commands did not drive it"
    differ = np.argwhere(ros_rows != core_rows)
    assert differ.size == 0, (
        f"{len(differ)} odometry values differ; first at t = {ros_rows[differ[0][0], 0]} s, column "
        f"{differ[0][1]}: ROS {ros_rows[tuple(differ[0])]!r}, core {core_rows[tuple(differ[0])]!r}"
    )


def test_m3_ranges_and_intensities_are_the_same_bit_for_bit(both):
    (_, ros_m3), (_, core_m3) = both
    assert len(ros_m3) == len(core_m3) > 0
    for (t_ros, r_ros, i_ros), (t_core, r_core, i_core) in zip(ros_m3, core_m3):
        assert t_ros == pytest.approx(t_core, abs=1e-9)  # the ROS stamp is whole nanoseconds
        np.testing.assert_array_equal(r_ros, r_core, err_msg=f"M3 ranges at t = {t_core} s")
        np.testing.assert_array_equal(i_ros, i_core, err_msg=f"M3 intensities at t = {t_core} s")
    hits = np.isfinite(core_m3[-1][1]).sum()
    assert hits > 0, "the last M3 scan saw nothing: the comparison would hold for an empty tank too"

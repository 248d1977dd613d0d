"""The hull's contacts on ROS (/<robot>/contacts, unexmin/Contacts, docs/simulator_node.md) against a closed form and
against unexmin.core.

UX_1 is driven backwards into the tank's wall x = -3 m (worlds/meshes/tank.stl: the inner box 6 x 4 m) for 4 s in
lockstep, both over ROS (`Simulation.launch`, step calls of 10 physics steps) and in-process. The hull is a sphere
of radius R = 0.3 m (urdf/properties.xacro), so each contact must lie on the wall (x = -3) at the centre's height
and side position, its normal +x, its depth R - (x_centre + 3); and the message of the last step must hold the
numbers unexmin.core's Robot.contacts() gives after the same steps, bit for bit. Before the robot reaches the wall,
the messages carry no contact.
"""

import numpy as np
import pytest
from lockstep_pairs import ros_environment_kept

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")  # rospy's own
SEED = 2
CHUNK = 10
SECONDS = 4.0
BACKWARDS = [-20.0, 0.0, 20.0, 0.0, -20.0, 0.0, 20.0, 0.0]  # [N] M0..M7: straight back (as test/pytest/test_core.py)
WALL_X = -3.0  # [m]
RADIUS = 0.3  # [m] hull sphere


def rows(msg):
    """(position N x 3, normal N x 3, depth N, impulse N) of an unexmin/Contacts message."""
    position = np.array([[p.x, p.y, p.z] for p in msg.position]).reshape(-1, 3)
    normal = np.array([[n.x, n.y, n.z] for n in msg.normal]).reshape(-1, 3)
    return position, normal, np.array(msg.depth), np.array(msg.impulse)


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from unexmin import Simulation
    from unexmin.core import World

    steps = round(SECONDS * 500)
    with ros_environment_kept():
        log_dir = str(tmp_path_factory.mktemp("contacts_logs"))
        with Simulation.launch("tank", robots=1, seed=SEED, sensors="none", log_dir=log_dir) as sim:
            ux = sim.robot("UX_1", streams=["contacts"])
            first = None
            with ux.collect("contacts") as messages:
                sim.step(CHUNK)
                first = ux.latest("contacts")
                ux.thrusts(BACKWARDS)
                for _ in range(steps // CHUNK):
                    sim.step(CHUNK)
                last = ux.latest("contacts")
                odom = ux.odom().pose.pose.position
            collected = list(messages.messages)
    w = World("tank", robots=1, seed=SEED, sensors="none")
    r = w.robot("UX_1")
    w.step(CHUNK)
    r.thrusts(BACKWARDS)
    for _ in range(steps // CHUNK):
        w.step(CHUNK)
    return first, last, np.array([odom.x, odom.y, odom.z]), collected, r.contacts(), r.state()["position"]


def test_contacts_lie_where_the_hull_meets_the_wall(runs):
    first, last, centre, collected, _, _ = runs
    assert rows(first)[2].shape == (0,), "at its spawn pose the robot touches nothing"
    assert last.header.frame_id == "world" and last.header.stamp.to_sec() == pytest.approx(SECONDS + CHUNK / 500)
    position, normal, depth, impulse = rows(last)
    assert len(depth) > 0 and len(impulse) == len(depth)
    np.testing.assert_allclose(position[:, 0], WALL_X, atol=0.005)  # on the wall
    np.testing.assert_allclose(position[:, 1:], np.tile(centre[1:], (len(depth), 1)), atol=0.01)  # facing the centre
    np.testing.assert_allclose(normal, np.tile([1.0, 0.0, 0.0], (len(depth), 1)), atol=0.02)
    np.testing.assert_allclose(depth, RADIUS - (centre[0] - WALL_X), atol=0.005)
    assert np.all(depth >= 0.0) and impulse.sum() > 0.0
    # at the 50 Hz contacts rate, every 10 physics steps (the end of each 10-step call falls on one): 4.02 s of steps
    stamps = [m.header.stamp.to_sec() for m in collected]
    np.testing.assert_allclose(stamps, 0.02 * np.arange(1, round((SECONDS + CHUNK / 500) * 50) + 1), atol=1e-9)


def test_ros_contacts_are_the_cores(runs):
    _, last, centre, _, core, core_centre = runs
    np.testing.assert_array_equal(centre, core_centre)
    position, normal, depth, impulse = rows(last)
    np.testing.assert_array_equal(position, core["position"])
    np.testing.assert_array_equal(normal, core["normal"])
    np.testing.assert_array_equal(depth, core["depth"])
    np.testing.assert_array_equal(impulse, core["impulse"])

"""The mapper in-process (unexmin.core.World(mapping=...), docs/mapping.md "In-process") against the mapper node.

The same tank, seed and commands run two ways: over ROS in lockstep (the simulator, robot_state_publisher and the
mapper node, which places each cloud through /tf and /tf_static), and in-process. UX_1 yaws both ways and drives for
8 s, each step call 10 physics steps (one /tf sample at the 50 Hz odometry rate per call, so that the sample the
simulator adds at the end of each call is one of the regular ones). Twice: with its M3 alone (a fixed mount: the M3
link 0.27 m ahead of and 0.13 m below the body origin), and with the M3, the DVL's four beam ranges and the four SLS
units' clouds (rotated mounts: the DVL link upside down, each beam 65 deg off its axis, the cameras' optical frames;
nine topics, whose clouds of one step reach the node in any order); and, in the team tank, a BlueROV2 Heavy yawing
with its imaging sonar (pitched 10 deg down). Each time both saved .bt files must be the same
bytes: the same occupied and free leaves, the same tree (a .bt holds no log-odds: each leaf is free or occupied).

Also, in-process only: every occupied voxel lies on the tank's walls or its anchor (closed form: the tank's inner
box, 6 x 4 m, floor at -3 m); parameter errors name the parameter; the core back end of Simulation saves the map at
close.
"""

import os
from pathlib import Path

import numpy as np
import pytest
from lockstep_pairs import ros_environment_kept

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")  # rospy's own
SEED = 3
CHUNK = 10  # physics steps per step call: 500 Hz / 50 Hz (the simulator's odom_rate, the mapper's tf_rate)
SECONDS = 8
ROBOT = "UX_1"
HERE = Path(__file__).resolve().parent


def commands(second):
    """Thrusts [N] for M0..M7 during second `second`: yaw one way (the horizontal thrusters M0, M2, M4, M6 in a pure
    moment), drive forward, yaw the other way."""
    turn = [-4.0, 0.0, 4.0, 0.0, 4.0, 0.0, -4.0, 0.0]
    schedule = [turn, turn, [4.0, 0.0, -4.0, 0.0, 4.0, 0.0, -4.0, 0.0], [-t for t in turn]]
    return schedule[second % len(schedule)]


def rov_commands(second):
    """Thrusts [N] for the BlueROV2 Heavy's T0..T7 during second `second`: yaw one way (the four horizontal
    thrusters), then the other."""
    turn = [-4.0, 4.0, 4.0, -4.0, 0.0, 0.0, 0.0, 0.0]
    return turn if second % 4 < 2 else [-t for t in turn]


def drive(step, robot_thrusts, physics_rate, schedule=commands):
    """The command schedule through `step(n)` in calls of CHUNK steps."""
    for second in range(SECONDS):
        robot_thrusts(schedule(second))
        for _ in range(round(physics_rate) // CHUNK):
            step(CHUNK)


def run_core(path, sensors="m3", mapping=True, rov=False):
    from unexmin.core import World

    if rov:
        w = World(
            str(HERE.parents[1] / "worlds" / "tank_team.world"),
            vehicles=["bluerov2_heavy"],
            seed=SEED,
            sensors=sensors,
            mapping=mapping,
        )
        drive(w.step, w.robot("ROV_1").thrusts, 1.0 / w.dt, rov_commands)
    else:
        w = World("tank", robots=1, seed=SEED, sensors=sensors, mapping=mapping)
        drive(w.step, w.robot(ROBOT).thrusts, 1.0 / w.dt)
    w.save_map(path)
    return w


def mapper_connected(master, topics):
    """True once the simulator has live connections to the mapper on `topics` (a publisher drops messages for a
    subscriber that is registered but not yet connected)."""
    from xmlrpc.client import ServerProxy

    bus = ServerProxy(master.lookupNode("/simulator")).getBusInfo(master.caller_id)[2]
    connected = {c[4] for c in bus if c[1].startswith("/mapper") and c[2] == "o" and c[5]}
    return set(topics) <= connected


def run_ros(path, log_dir, core_stats, sources=False, rov=False):
    """The node's map of the same run, saved to `path` once it holds every cloud the core inserted; its stats."""
    from unexmin import Simulation
    from unexmin.scripting.launcher import wait_for

    robot, schedule = ROBOT, commands
    topics = [f"/{ROBOT}/m3/scan", "/tf"]
    if sources:
        arguments = {"launch_file": str(HERE / "clients" / "tank_mapper_sources.launch")}
        topics += [f"/{ROBOT}/dvl_sonar{i}" for i in range(4)] + [f"/{ROBOT}/sls_{i}/points" for i in range(4)]
    elif rov:
        arguments = {"launch_file": str(HERE / "clients" / "tank_team_rov_mapper.launch")}
        robot, schedule = "ROV_1", rov_commands
        topics = ["/ROV_1/imaging_sonar/points", "/tf"]
    else:
        arguments = {"robots": 1, "seed": SEED, "sensors": "m3", "mapping": True}
    with ros_environment_kept():
        with Simulation.launch("tank", log_dir=log_dir, **arguments) as sim:
            import rosgraph
            import rospy

            from unexmin.msg import MapperStats
            from unexmin.srv import SaveMap

            stats = {}
            sub = rospy.Subscriber("/mapper/stats", MapperStats, lambda m: stats.update(last=m), queue_size=10)
            master = rosgraph.Master(rospy.get_name())
            wait_for(lambda: mapper_connected(master, topics), 60.0, "the mapper to connect to the simulator")
            r = sim.robot(robot, streams="none")
            drive(sim.step, r.thrusts, sim.physics_rate, schedule)
            expected = (core_stats["clouds_received"], core_stats["clouds_inserted"])

            def caught_up():
                last = stats.get("last")
                return last is not None and (last.clouds_received, last.clouds_inserted) == expected

            wait_for(caught_up, 120.0, f"the mapper to receive and insert {expected} clouds")
            rospy.wait_for_service("/mapper/save_map", 30.0)
            answer = rospy.ServiceProxy("/mapper/save_map", SaveMap)(path=str(path), robot="")
            assert answer.success, answer.message
            sub.unregister()
            return stats["last"], answer.occupied_leaves


@pytest.fixture(scope="module")
def maps(tmp_path_factory):
    folder = tmp_path_factory.mktemp("maps")
    paths = {k: folder / f"{k}.bt" for k in ("core", "ros")}
    core = run_core(paths["core"])
    ros_stats, ros_leaves = run_ros(paths["ros"], str(folder / "logs"), core.map_stats())
    return paths, core, ros_stats, ros_leaves


def test_the_in_process_map_is_the_mapper_nodes(maps):
    from unexmin.map_quality.io import read_bt

    paths, core, ros_stats, ros_leaves = maps
    stats = core.map_stats()
    assert stats["sources"] == [f"{ROBOT}/m3"]
    # 40 Hz M3 over 8 s: 320 scans, every one placed (none waits past the last tf sample, at 8 s)
    assert stats["clouds_received"] == 320 and stats["clouds_inserted"] == 320 and stats["clouds_dropped"] == 0
    assert ros_stats.clouds_dropped == 0 and ros_stats.points_inserted == stats["points_inserted"]
    assert ros_leaves == stats["occupied_leaves"] > 300
    core_centres, core_sizes = read_bt(paths["core"])
    ros_centres, ros_sizes = read_bt(paths["ros"])
    assert len(core_centres) == len(ros_centres) == stats["occupied_leaves"]
    np.testing.assert_array_equal(core_centres, ros_centres)
    np.testing.assert_array_equal(core_sizes, ros_sizes)
    assert paths["core"].read_bytes() == paths["ros"].read_bytes(), "the two trees differ in their free leaves"


@pytest.fixture(scope="module")
def source_maps(tmp_path_factory):
    folder = tmp_path_factory.mktemp("source_maps")
    paths = {k: folder / f"{k}.bt" for k in ("core", "ros")}
    core = run_core(paths["core"], sensors="m3,dvl,sls", mapping={"dvl": True, "sonar_max_range": 8.0})
    ros_stats, ros_leaves = run_ros(paths["ros"], str(folder / "logs"), core.map_stats(), sources=True)
    return paths, core, ros_stats, ros_leaves


def test_the_in_process_map_of_every_source_on_rotated_mounts_is_the_nodes(source_maps):
    """The DVL's four beams (dvl_link upside down, each beam 65 deg off its axis) and the four SLS units' clouds (in
    their cameras' optical frames, turned 90 deg twice) beside the M3: rotated mounts, nine topics."""
    from unexmin.map_quality.io import read_bt

    paths, core, ros_stats, ros_leaves = source_maps
    stats = core.map_stats()
    sls = [f"{ROBOT}/sls_{i}" for i in range(4)]
    assert stats["sources"] == [f"{ROBOT}/dvl", f"{ROBOT}/m3", *sls]  # in the description's order
    assert stats["clouds_received"] == 320 + 4 * 64 + 4 * 80 and stats["clouds_dropped"] == 0
    assert ros_stats.points_inserted == stats["points_inserted"] and ros_leaves == stats["occupied_leaves"]
    core_centres, _ = read_bt(paths["core"])
    ros_centres, _ = read_bt(paths["ros"])
    np.testing.assert_array_equal(core_centres, ros_centres)
    assert paths["core"].read_bytes() == paths["ros"].read_bytes()


@pytest.fixture(scope="module")
def sonar_maps(tmp_path_factory):
    folder = tmp_path_factory.mktemp("sonar_maps")
    paths = {k: folder / f"{k}.bt" for k in ("core", "ros")}
    core = run_core(paths["core"], sensors="imaging_sonar", mapping={"sonar_max_range": 8.0}, rov=True)
    ros_stats, ros_leaves = run_ros(paths["ros"], str(folder / "logs"), core.map_stats(), rov=True)
    return paths, core, ros_stats, ros_leaves


def test_the_in_process_map_of_an_imaging_sonar_is_the_nodes(sonar_maps):
    """A BlueROV2 Heavy's imaging sonar (its link pitched 10 deg down) yawing in the team tank: the sonar's detections
    as the simulator's points topic makes them (cloud threshold 15 dB), within the launch files' 8 m."""
    from unexmin.map_quality.io import read_bt

    paths, core, ros_stats, ros_leaves = sonar_maps
    stats = core.map_stats()
    assert stats["sources"] == ["ROV_1/imaging_sonar"]
    assert stats["clouds_received"] == 10 * SECONDS and stats["clouds_dropped"] == 0
    assert ros_stats.points_inserted == stats["points_inserted"] and ros_leaves == stats["occupied_leaves"] > 100
    core_centres, _ = read_bt(paths["core"])
    ros_centres, _ = read_bt(paths["ros"])
    np.testing.assert_array_equal(core_centres, ros_centres)
    assert paths["core"].read_bytes() == paths["ros"].read_bytes()


def test_every_occupied_voxel_is_on_the_tank(maps):
    core = maps[1]
    v = core.occupied_voxels()
    assert v.shape[1] == 4 and len(v) == core.map_stats()["occupied_leaves"]
    centre, half = v[:, :3], v[:, 3] / 2
    # the tank's inner box: walls at x = +-3, y = +-2, the floor at z = -3 (worlds/meshes/tank.stl, 0.05 m thick)
    wall = np.min(
        np.stack(
            [
                np.abs(np.abs(centre[:, 0]) - 3.0),
                np.abs(np.abs(centre[:, 1]) - 2.0),
                np.abs(centre[:, 2] + 3.0),
            ]
        ),
        axis=0,
    )
    # the anchor lies on the floor at the centre (worlds/tank.world), below 1.5 m
    anchor = (np.abs(centre[:, 0]) < 1.0) & (np.abs(centre[:, 1]) < 1.0) & (centre[:, 2] < -1.5)
    on_rock = (wall <= half + 0.1) | anchor  # within a voxel of the surface (the M3's 3 deg beam, range noise)
    assert on_rock.mean() > 0.97, f"{(~on_rock).sum()} of {len(v)} voxels off the tank"


def test_mapper_parameters_are_checked_by_name():
    from unexmin.core import ConfigError, World

    with pytest.raises(ConfigError, match="parameter 'resolution' = 0: expected \\[0.001, 10\\] m"):
        World("tank", sensors="m3", mapping={"resolution": 0.0})
    with pytest.raises(ConfigError, match="m3_max_range' = 20: expected \\(0, max_range = 10\\] m"):
        World("tank", sensors="m3", mapping={"m3_max_range": 20.0})
    with pytest.raises(ConfigError, match="unknown parameter 'per_robot': expected one of .*resolution"):
        World("tank", sensors="m3", mapping={"per_robot": True})
    with pytest.raises(ConfigError, match="parameter 'm3' = 1: expected true or false"):
        World("tank", sensors="m3", mapping={"m3": 1})
    with pytest.raises(RuntimeError, match="maps nothing"):
        World("tank", sensors="m3").map_stats()


def test_simulation_core_backend_saves_the_map_at_close(tmp_path):
    from unexmin import Simulation
    from unexmin.map_quality.io import read_bt

    path = tmp_path / "map.bt"
    with Simulation.launch("tank", seed=SEED, sensors="m3", backend="core", mapping=True, map_file=str(path)) as sim:
        sim.robot(ROBOT).thrusts(commands(0))
        sim.run_for(2.0)
        leaves = sim.world.map_stats()["occupied_leaves"]
        settings = sim.world.map_settings()
        assert not path.exists()
    assert settings["sonar_max_range"] == 8.0 and settings["dvl"] is False  # as launch/simulation.launch
    centres, _ = read_bt(str(path))
    assert len(centres) == leaves > 100
    with pytest.raises(ValueError, match="map_file .* only made with mapping=True"):
        Simulation.launch("tank", sensors="m3", backend="core", map_file=os.fspath(tmp_path / "x.bt"))

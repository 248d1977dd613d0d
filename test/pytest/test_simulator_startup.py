"""Start-up errors of the simulator process (docs/simulator_node.md): a robot description with a <sensor> of
an unknown type, an unknown family in ~sensors, an unknown ~visibility level, a negative ~ray_caster_threads and
an unknown ray-casting back end in the world file each stop simulator_node with exit code 1 and one FATAL line
that names the input and what was expected."""

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from unexmin.scripting.launcher import free_port, start_private_master, stop_process_group, wait_for

REPO = Path(__file__).resolve().parents[2]
TANK = REPO / "worlds" / "tank.world"
BUILTIN = {
    "camera",
    "dvl",
    "gamma_counter",
    "imu",
    "m3",
    "magnetometer",
    "msis",
    "pressure",
    "sls",
    "water_probe",
    "water_sampler",
}  # families every simulator knows


@pytest.fixture(scope="module")
def description():
    xacro = shutil.which("xacro")
    assert xacro, "xacro is not on PATH (source scripts/env.sh)"
    return subprocess.run(
        [xacro, str(REPO / "urdf" / "ux1.urdf.xacro"), "name:=UX_1"], capture_output=True, text=True, check=True
    ).stdout


@pytest.fixture(scope="module")
def master(tmp_path_factory):
    """A private rosmaster; yields its URI."""
    proc, env = start_private_master(free_port(), tmp_path_factory.mktemp("ros"))
    yield env["ROS_MASTER_URI"]
    stop_process_group(proc)


def start(master, urdf, world=TANK, sensors="all", extra=()):
    """Runs simulator_node against `master` with UX_1 described by `urdf`; returns (exit code, output)."""
    import rosgraph

    params = rosgraph.Master("/startup_test", master_uri=master)
    params.setParam("/UX_1/robot_description", urdf)
    env = dict(os.environ, ROS_MASTER_URI=master)
    out = subprocess.run(
        [
            "rosrun",
            "unexmin",
            "simulator_node",
            f"_world_file:={world}",
            f"_sensors:={sensors}",
            "_paused:=true",
            "__name:=simulator",
            *extra,
        ],
        env=env,
        capture_output=True,
        text=True,
        timeout=60,
    )
    return out.returncode, out.stdout + out.stderr


def fatal_lines(output):
    return [line for line in output.splitlines() if "FATAL" in line]


def test_an_unknown_sensor_type_stops_start_up_with_one_line(master, description):
    urdf = description.replace(
        "</unexmin>", "<sensor name='echo' type='echosounder' link='UX_1/base_link' rate='10'/></unexmin>"
    )
    code, output = start(master, urdf)
    assert code == 1, output
    lines = fatal_lines(output)
    assert len(lines) == 1, output
    m = re.search(r"UX_1: sensor 'echo': unknown type 'echosounder' \(known: ([a-z0-9_, ]+)\)", lines[0])
    assert m, lines[0]
    known = m.group(1).split(", ")
    assert known == sorted(known) and BUILTIN <= set(known), known


def test_an_unknown_sensor_family_in_the_selection_stops_start_up(master, description):
    code, output = start(master, description, sensors="imu,sonar")
    assert code == 1, output
    lines = fatal_lines(output)
    assert len(lines) == 1 and "parameter ~sensors = 'imu,sonar': unknown family 'sonar'" in lines[0], output
    assert all(name in lines[0] for name in BUILTIN), lines[0]


def test_an_unknown_ray_caster_back_end_in_the_world_file_stops_start_up(master, description, tmp_path):
    world = tmp_path / "tank.world"
    (tmp_path / "meshes").symlink_to(TANK.parent / "meshes")  # mesh paths stay inside the world's folder
    text = TANK.read_text()
    assert "ray_caster: embree" in text
    world.write_text(text.replace("ray_caster: embree", "ray_caster: optix"))
    code, output = start(master, description, world=world)
    assert code == 1, output
    lines = fatal_lines(output)
    assert len(lines) == 1 and f"{world}: 'ray_caster'" in lines[0] and "optix" in lines[0], output
    assert "embree" in lines[0] and "bullet" in lines[0], lines[0]


def test_an_unknown_visibility_level_stops_start_up(master, description):
    import rosgraph

    try:
        code, output = start(master, description, sensors="imu", extra=["_visibility:=murky"])
    finally:  # rosrun left ~visibility on the master: the next start must not inherit it
        rosgraph.Master("/startup_test", master_uri=master).deleteParam("/simulator/visibility")
    assert code == 1, output
    lines = fatal_lines(output)
    assert len(lines) == 1, output
    assert (
        "parameter ~visibility = 'murky': expected none|low|medium|high|water (or empty: the world file's level)"
        in lines[0]
    ), lines[0]


def test_a_negative_ray_caster_thread_count_stops_start_up(master, description):
    import rosgraph

    try:
        code, output = start(master, description, sensors="imu", extra=["_ray_caster_threads:=-1"])
    finally:  # as above: the next start must not inherit ~ray_caster_threads
        rosgraph.Master("/startup_test", master_uri=master).deleteParam("/simulator/ray_caster_threads")
    assert code == 1, output
    lines = fatal_lines(output)
    assert len(lines) == 1, output
    assert "parameter ~ray_caster_threads = -1: expected >= 0 (0 = every hardware thread)" in lines[0], lines[0]


def test_a_valid_selection_starts(master, description):
    """The same set-up with known names starts (so the failures above are about the names): the node is
    alive until stopped."""
    import rosgraph

    rosgraph.Master("/startup_test", master_uri=master).setParam("/UX_1/robot_description", description)
    env = dict(os.environ, ROS_MASTER_URI=master)
    proc = subprocess.Popen(
        [
            "rosrun",
            "unexmin",
            "simulator_node",
            f"_world_file:={TANK}",
            "_sensors:=imu,dvl",
            "_paused:=true",
            "__name:=simulator",
        ],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        start_new_session=True,
    )
    try:
        master_api = rosgraph.Master("/startup_test", master_uri=master)
        wait_for(lambda: "/sim/step" in [s for s, _ in master_api.getSystemState()[2]], 60, "/sim/step")
        topics = {t for t, _ in master_api.getPublishedTopics("")}
        assert "/UX_1/imu" in topics and "/UX_1/dvl" in topics, sorted(topics)
        assert "/UX_1/m3/scan" not in topics and "/UX_1/tritech_micron/scan" not in topics, sorted(topics)
    finally:
        stop_process_group(proc)

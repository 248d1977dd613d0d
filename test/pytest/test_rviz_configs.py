"""The shipped rviz configurations name exactly the robots that run.

launch/unexmin.rviz names UX_1..UX_3; launch/unexmin_1.rviz and launch/unexmin_2.rviz are written from it by
scripts/rviz_configs.py; simulation.launch opens the one that matches `robots`. A display of a robot that does not
exist is a red error row in rviz (test_rviz_screenshot.py checks that on screen).
"""

import importlib.util
import re
import subprocess
from pathlib import Path

import pytest
import yaml

from unexmin.rviz_config import team_config

REPO = Path(__file__).resolve().parents[2]
spec = importlib.util.spec_from_file_location("rviz_configs", REPO / "scripts" / "rviz_configs.py")
rviz_configs = importlib.util.module_from_spec(spec)
spec.loader.exec_module(rviz_configs)

ROBOT = re.compile(r"\bUX_(\d+)\b")


def robots_named(config):
    """Every robot index a configuration names anywhere (display names, topics, robot descriptions, visibility)."""
    found = set()

    def walk(node):
        if isinstance(node, dict):
            for key, value in node.items():
                walk(key)
                walk(value)
        elif isinstance(node, list):
            for value in node:
                walk(value)
        elif isinstance(node, str):
            found.update(int(k) for k in ROBOT.findall(node))

    walk(config)
    return found


def display_names(config):
    names = []

    def walk(displays):
        for d in displays:
            names.append(d["Name"])
            walk(d.get("Displays", []))

    walk(config["Visualization Manager"]["Displays"])
    return names


def launched_config(robots, launch="tank_world.launch", arg="robots"):
    """The configuration file `<launch> rviz:=true <arg>:=<robots>` passes to rviz (roslaunch --args)."""
    out = subprocess.run(
        ["roslaunch", "--args", "rviz", "unexmin", launch, "rviz:=true", f"{arg}:={robots}"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert out.returncode == 0, out.stderr
    args = out.stdout.split()
    return Path(args[args.index("-d") + 1])


def test_shipped_configs_are_what_the_script_writes():
    assert rviz_configs.main(["--check"]) == 0


@pytest.mark.parametrize("robots", [1, 2, 3])
def test_each_config_names_exactly_its_robots(robots):
    path = rviz_configs.path_for(robots)
    config = yaml.safe_load(path.read_text())
    assert robots_named(config) == set(range(1, robots + 1)), path
    names = display_names(config)
    for k in range(1, robots + 1):
        for display in ("model", "odom", "sensors", "MSIS", "M3 fan", "SLS 0", "SLS 3"):
            assert f"UX_{k} {display}" in names, f"{path.name} lacks UX_{k} {display}"
    # everything that names no robot is kept: the world meshes, the map, the grid, tf
    template = yaml.safe_load(rviz_configs.TEMPLATE.read_text())
    shared = [n for n in display_names(template) if not ROBOT.search(n)]
    assert shared and all(n in names for n in shared)
    assert config["Visualization Manager"]["Views"] == template["Visualization Manager"]["Views"]


@pytest.mark.parametrize("robots", [1, 2, 3])
def test_the_launch_files_open_the_config_for_their_robot_count(robots):
    assert launched_config(robots).resolve() == rviz_configs.path_for(robots).resolve()


def test_config_for_refuses_a_robot_count_it_has_no_robots_for():
    text = rviz_configs.TEMPLATE.read_text()
    assert rviz_configs.config_for(text, 3) == text
    for bad in (0, 4):
        with pytest.raises(ValueError, match=f"robots = {bad}: expected 1 to 3"):
            rviz_configs.config_for(text, bad)


def test_team_config_shows_every_vehicle_and_the_mine_team_opens_it():
    config = yaml.safe_load(rviz_configs.TEAM_PATH.read_text())
    assert robots_named(config) == {1}
    names = display_names(config)
    for robot in ("UX_1", "ROV_1", "AUV_1"):
        assert f"{robot} model" in names and f"{robot} odom" in names
    displays = {d["Name"]: d for d in config["Visualization Manager"]["Displays"]}
    assert displays["ROV_1 model"]["Robot Description"] == "/ROV_1/robot_description"
    assert displays["AUV_1 odom"]["Topic"] == "/AUV_1/odom"
    assert displays["ROV_1 imaging sonar"]["Image Topic"] == "/ROV_1/imaging_sonar/fan"
    assert displays["AUV_1 side scan"]["Image Topic"] == "/AUV_1/side_scan/waterfall"
    assert displays["ROV_1 sonar cloud"]["Topic"] == "/ROV_1/imaging_sonar/points"


def test_a_team_launch_writes_the_config_of_its_own_list():
    """mine_world.launch vehicles:=<list> rviz:=true runs nodes/team_rviz on the team's robot names; its
    configuration shows each robot once, and no robot outside the team."""
    out = subprocess.run(
        [
            "roslaunch",
            "--args",
            "rviz",
            "unexmin",
            "mine_world.launch",
            "rviz:=true",
            "vehicles:=bluerov2_heavy,ux1,bluerov2_heavy",
        ],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert out.returncode == 0, out.stderr
    args = out.stdout.split()
    assert Path(args[0]).name == "team_rviz"
    team = args[args.index("--team") + 1].split(",")
    assert team == ["ROV_1", "UX_1", "ROV_2"]
    config = yaml.safe_load(team_config(Path(args[args.index("--template") + 1]).read_text(), team))
    names = display_names(config)
    for robot in team:
        assert names.count(f"{robot} model") == 1 and names.count(f"{robot} odom") == 1
    for robot in ("ROV_1", "ROV_2"):
        assert f"{robot} imaging sonar" in names and f"{robot} sonar cloud" in names
    assert robots_named(config) == {1} and not any(n.startswith("AUV_") for n in names)
    with pytest.raises(ValueError, match="rviz team: robot 'GLIDER_1'"):
        team_config(rviz_configs.TEMPLATE.read_text(), ["GLIDER_1"])

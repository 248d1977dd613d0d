"""Mixed teams outside the launch files (docs/adding_a_vehicle.md, "A mixed team"): the robot names of a team list,
the batch runner's `vehicles` key and the Python API's `vehicles` argument. No roscore.

Run: /work/main_ws/venv/bin/python -m pytest test/pytest/test_vehicle_teams.py
"""

import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import yaml

from unexmin.batch.spec import SpecError, check_spec, expand, write_launch
from unexmin.vehicles import VEHICLE_TYPES, parse_vehicles, team_names

REPO = Path(__file__).resolve().parents[2]


def test_team_names_count_each_type_on_its_own():
    assert team_names("ux1,bluerov2_heavy,remus100") == ["UX_1", "ROV_1", "AUV_1"]
    assert team_names(["ux1", "remus100", "ux1", "ux1"]) == ["UX_1", "AUV_1", "UX_2", "UX_3"]


@pytest.mark.parametrize("bad", ["", "ux1,,remus100", "ux1,torpedo", 3])
def test_unknown_vehicle_types_are_refused_naming_the_known_ones(bad):
    with pytest.raises(ValueError, match="vehicles: .*(expected: ux1, bluerov2_heavy, remus100|vehicle types)"):
        parse_vehicles(bad)


def test_the_mine_world_lists_each_type_with_its_description():
    robots = {
        r["name"]: r["description"] for r in yaml.safe_load((REPO / "worlds" / "mine.world").read_text())["robots"]
    }
    for vehicle, (prefix, description) in VEHICLE_TYPES.items():
        assert robots[f"{prefix}_1"] == description, vehicle
        assert (REPO / "urdf" / description).exists()


def test_the_launch_names_the_team_as_the_python_helper(tmp_path):
    """simulation.launch computes the names in roslaunch's eval: the same rule as unexmin.vehicles."""
    text = (REPO / "launch" / "simulation.launch").read_text()
    team = ET.fromstring(text).find("arg[@name='team']").get("value")
    prefixes = ET.fromstring(text).find("arg[@name='prefixes']").get("default")
    assert eval(prefixes) == {v: p for v, (p, _) in VEHICLE_TYPES.items()}
    for vehicles in ("ux1,bluerov2_heavy,remus100", "remus100,ux1,ux1", ""):
        expression = team[len("$(eval ") : -1]
        names = eval(expression, {}, {"vehicles": vehicles, "robots": 2, "prefixes": prefixes})
        assert names == ",".join(team_names(vehicles) if vehicles else ["UX_1", "UX_2"])


def spec_file(tmp_path, extra):
    path = tmp_path / "spec.yaml"
    path.write_text("mission: unexmin.missions.batch:tank_survey\nworld: mine\n" + extra)
    return check_spec(yaml.safe_load(path.read_text()), str(path))


def launch_args(spec, folder):
    """{name: value} of the arguments of the mission launch file the batch writes for the spec's first mission."""
    return {a.get("name"): a.get("value") for a in ET.parse(write_launch(spec, expand(spec)[0], folder)).iter("arg")}


def test_batch_spec_runs_a_team(tmp_path):
    spec = spec_file(tmp_path, "vehicles: [ux1, bluerov2_heavy, remus100]\n")
    assert spec["vehicles"] == ["ux1", "bluerov2_heavy", "remus100"]
    assert launch_args(spec, str(tmp_path / "m"))["vehicles"] == "ux1,bluerov2_heavy,remus100"
    assert "vehicles" not in launch_args(spec_file(tmp_path, ""), str(tmp_path / "n")), "no team: the robots count"
    repeats = spec_file(tmp_path, "vehicles: [bluerov2_heavy, ux1, bluerov2_heavy, remus100]\n")
    assert launch_args(repeats, str(tmp_path / "r"))["vehicles"] == "bluerov2_heavy,ux1,bluerov2_heavy,remus100"
    with pytest.raises(SpecError, match="spec.yaml: vehicles: unknown vehicle type"):
        spec_file(tmp_path, "vehicles: [ux1, glider]\n")


def test_simulation_launch_refuses_an_unknown_vehicle_before_starting_anything():
    from unexmin.scripting.simulation import Simulation

    with pytest.raises(ValueError, match="vehicles: unknown vehicle type"):
        Simulation.launch("mine", vehicles="ux1,submarine", timeout=1.0)


def roslaunch(*args):
    return subprocess.run(["roslaunch", *args], capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("launch", ["mine_world.launch", "tank_team.launch"])
def test_the_launch_runs_any_list_with_repeats_in_its_order(launch):
    vehicles = "ux1,bluerov2_heavy,bluerov2_heavy,remus100,ux1"
    names = team_names(vehicles)
    assert names == ["UX_1", "ROV_1", "ROV_2", "AUV_1", "UX_2"]
    out = roslaunch("--dump-params", "unexmin", launch, f"vehicles:={vehicles}")
    assert out.returncode == 0, out.stderr
    params = yaml.safe_load(out.stdout)
    assert params["/simulator/spawns"] == ",".join(names)
    for name, vehicle in zip(names, vehicles.split(",")):
        assert f"urdf/{VEHICLE_TYPES[vehicle][1]}" in params[f"/{name}/robot_description"]  # xacro's header
        assert params[f"/{name}/thruster_allocator/robot"] == name
        # the others' allocation comes from their own description; the UX-1's is its own allocator's
        assert params.get(f"/{name}/thruster_allocator/from_description", False) == (vehicle != "ux1")
    for name in ("UX_1", "UX_2"):
        assert params[f"/{name}/dvl_from_simulator"] is True


def test_an_unknown_vehicle_type_stops_the_launch_with_one_line_naming_it():
    out = roslaunch("--nodes", "unexmin", "mine_world.launch", "vehicles:=ux1,bluerov2_heavy,glider")
    assert out.returncode != 0
    assert (
        "vehicles: unknown vehicle type 'glider' (expected: ux1, bluerov2_heavy, remus100)" in out.stderr + out.stdout
    )

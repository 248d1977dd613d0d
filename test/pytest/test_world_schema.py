"""The world-file schema (config/world_schema.yaml, docs/worlds.md "Every key"): a typo at each level is refused
with its path and the nearest key, as the simulator refuses it (test/gtest/test_world_schema.cpp holds the same
cases); every shipped world and every world file the package's tools write pass; world.launch stops on a typo with
one line; docs/worlds.md's table is the schema's."""

import glob
import re
import subprocess
from pathlib import Path

import pytest
import yaml

from unexmin.worlds import schema
from unexmin.worlds.schema import WorldFileError, check_world, read_world

REPO = Path(__file__).resolve().parents[2]
TOP = (
    "name, gravity, water, atmospheric_pressure, visibility, sediment, ray_caster, "
    "magnetic_field, current, meshes, geology, robots"
)


def world(top="", water="", speed="", mesh="", material="", robot=""):
    """The world of the C++ test: every level present, each argument appended to its level."""
    return (
        f"name: w\ngravity: 9.81\n{top}water: {{density: 1000.0, surface_z: 0.0{water}}}\n"
        "visibility: {level: low, colour: [0.25, 0.3, 0.2]}\n"
        f"current:\n  speed: {{mean: 0.1, min: 0.0, max: 0.5, noise: 0.0, mu: 0.0{speed}}}\n"
        "meshes:\n  - {name: a, file: nowhere.stl}\n"
        f"  - {{name: b, file: nowhere.stl, albedo: [0.1, 0.1, 0.1]{mesh}, "
        f"material: {{kind: rock, seed: 7{material}}}}}\n"
        f"robots:\n  - {{name: UX_1, xyz: [0, 0, -1]{robot}}}\n"
    )


TYPOS = [
    (world(top="gravty: 9.81\n"), "gravty", TOP, "gravity"),
    (world(top="visiblity: {level: high}\n"), "visiblity", TOP, "visibility"),
    (
        world(water=", densty: 1025"),
        "water.densty",
        "density, surface_z, profile, interpolation, boundary, regions",
        "density",
    ),
    (world(speed=", meen: 0.2"), "current.speed.meen", "mean, min, max, noise, mu", "mean"),
    (
        world(mesh=", albdo: [0.1, 0.1, 0.1]"),
        "meshes[1].albdo",
        "name, file, scale, xyz, rpy, collision, visual, seen_by, albedo, material",
        "albedo",
    ),
    (
        world(material=", grian: 0.02"),
        "meshes[1].material.grian",
        "kind, albedo, seed, contrast, relief, grain, cracks, strata, stains, region, tint, square, rows, columns, "
        "dark, border, image",
        "grain",
    ),
    (world(robot=", descripton: ux1.urdf.xacro"), "robots[0].descripton", "name, description, xyz, rpy", "description"),
]


@pytest.mark.parametrize("text,path,accepted,nearest", TYPOS, ids=[t[1] for t in TYPOS])
def test_a_typo_at_each_level_is_refused_with_its_path_and_the_nearest_key(tmp_path, text, path, accepted, nearest):
    file = tmp_path / "typo.world"
    file.write_text(text)
    with pytest.raises(WorldFileError) as e:
        read_world(file)
    assert str(e.value) == f"{file}: unknown key '{path}' (accepted: {accepted}); did you mean '{nearest}'?"


def test_the_typo_free_world_passes_and_a_far_key_gets_no_suggestion(tmp_path):
    check_world(yaml.safe_load(world()), "w.world")
    with pytest.raises(WorldFileError) as e:
        check_world(yaml.safe_load(world(top="zzz: 1\n")), "w.world")
    assert str(e.value) == f"w.world: unknown key 'zzz' (accepted: {TOP})"


BAD_VALUES = [  # (text of the good world, its replacement, the message)
    ("gravity: 9.81", "gravity: -1", "'gravity' = -1: expected a finite number, > 0 [m/s^2]"),
    ("level: low", "level: murky", "'visibility.level' = 'murky': expected a string among none|low|medium|high"),
    ("mu: 0.0", "mu: -1", "'current.speed.mu' = -1: expected a finite number, >= 0 [1/s]"),
    ("albedo: [0.1, 0.1, 0.1]", "albedo: [0.1, 2]", "'meshes[1].albedo' = [0.1, 2]: expected a list of 3 finite"),
    ("seed: 7", "seed: x", "'meshes[1].material.seed' = 'x': expected an integer, >= 0"),
    ("name: UX_1, ", "", "missing 'robots[0].name' (a string)"),
    (
        "gravity: 9.81",
        "gravity: 9.81\nmagnetic_field: {intensity: 50000, inclination: 95, declination: 0}",
        "'magnetic_field.inclination' = 95: expected a finite number, >= -90 and <= 90 [deg]",
    ),
    ("gravity: 9.81", "gravity: 9.81\nmagnetic_field: [24, 134]", "'magnetic_field' = [24, 134]: expected a list of 3"),
]


def test_the_magnetic_field_takes_either_form():
    for form in ("[24.0, 134.0, -508.0]", "{intensity: 52750, inclination: 75, declination: 10}"):
        check_world(yaml.safe_load(world().replace("gravity: 9.81", f"gravity: 9.81\nmagnetic_field: {form}", 1)), "w")


@pytest.mark.parametrize("good,bad,message", BAD_VALUES, ids=[b[0] for b in BAD_VALUES])
def test_a_value_of_the_wrong_type_or_range_names_its_key(good, bad, message):
    with pytest.raises(WorldFileError) as e:
        check_world(yaml.safe_load(world().replace(good, bad, 1)), "w.world")
    assert str(e.value).startswith(f"w.world: {message}"), str(e.value)


def test_every_shipped_world_passes():
    files = sorted(glob.glob(str(REPO / "worlds" / "*.world"))) + sorted(
        glob.glob(str(REPO / "examples" / "**" / "*.world"), recursive=True)
    )
    assert {Path(f).name for f in files} >= {"mine.world", "tank.world", "test_box.world"}
    for f in files:
        read_world(f)


def test_every_world_of_the_example_batch_specs_passes(tmp_path):
    from unexmin.batch.spec import check_spec

    specs = sorted(glob.glob(str(REPO / "examples" / "**" / "*.yaml"), recursive=True))
    assert specs
    for path in specs:
        spec = check_spec(yaml.safe_load(Path(path).read_text()), path)  # reads its world through read_world
        read_world(spec["world_file"])


def test_a_typo_in_a_batch_world_stops_the_batch_before_its_missions(tmp_path):
    from unexmin.batch.spec import SpecError, check_spec

    (tmp_path / "meshes").symlink_to(REPO / "worlds" / "meshes")
    typo = tmp_path / "tank.world"
    typo.write_text((REPO / "worlds" / "tank.world").read_text().replace("gravity:", "gravty:"))
    spec_file = tmp_path / "spec.yaml"
    spec_file.write_text(f"world: {typo}\nmission: unexmin.missions.batch:tank_survey\n")
    with pytest.raises(SpecError, match=re.escape(f"world: {typo}: unknown key 'gravty'")):
        check_spec(yaml.safe_load(spec_file.read_text()), str(spec_file))


def test_the_batch_runners_mission_world_passes(tmp_path):
    from unexmin.batch.spec import check_spec, expand, write_world

    spec_file = tmp_path / "spec.yaml"
    spec_file.write_text(
        "world: mine\nmission: unexmin.missions.batch:tank_survey\n"
        "params: {current_speed: 0.7, current_angle: 1.2, current_vertical_angle: 0.1, visibility: high}\n"
    )
    spec = check_spec(yaml.safe_load(spec_file.read_text()), str(spec_file))
    path = write_world(spec, expand(spec)[0]["params"], str(tmp_path / "m"))
    data = read_world(path)
    assert data["current"]["speed"]["mean"] == 0.7 and data["visibility"]["level"] == "high"


@pytest.mark.parametrize("world_name", ["tank", "test_box", "mine"])
def test_the_replays_spawn_world_passes(tmp_path, world_name):
    """The world the replay writes (--overrides: the file `python -m unexmin.identify` writes) and
    worlds/tools/make_sample_bag.py writes: a shipped world with one robot's spawn attitude changed."""
    from unexmin.worlds.spawn import world_launch_file

    overrides = tmp_path / "identified_overrides.xacro"
    overrides.write_text('<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>\n')
    launch = world_launch_file(tmp_path, world_name, "UX_1", roll_pitch=(0.1, -0.2), overrides=overrides)
    data = read_world(tmp_path / f"{world_name}_spawn.world")
    assert data["robots"][0]["rpy"][:2] == [0.1, -0.2] and launch.is_file()


def test_the_world_written_by_world_from_scan_passes(tmp_path):
    """python -m unexmin.worlds.from_scan on a scan of the tank's inside, then its text for other options."""
    import numpy as np
    import trimesh

    from unexmin.worlds import from_scan as wfs
    from unexmin.worlds.from_scan.stages.files import world_yaml

    mesh = trimesh.load(str(REPO / "worlds" / "meshes" / "tank.stl"), force="mesh")
    c = mesh.triangles_center  # the floor and the inner walls below the rim (docs/worlds.md: 6 x 4 m, 3 m deep)
    inner = (np.abs(c[:, 0]) <= 3.0 + 1e-6) & (np.abs(c[:, 1]) <= 2.0 + 1e-6) & (c[:, 2] >= -3.0 - 1e-6)
    scan = tmp_path / "tank_scan.xyz"
    wfs.write_xyz(scan, wfs.sample_scan(mesh.triangles[inner & (c[:, 2] < 0.3 - 1e-6)], 0.05, 0.02, seed=1))
    rep = wfs.build_world(scan, tmp_path / "world", name="tank_scan", water_level=0.0, quiet=True)
    assert read_world(tmp_path / "world" / rep["world"])["robots"]
    for visibility, speed in (("none", 0.0), ("high", 0.25)):
        spawns = [((0, 1, -2), 0.8), ((1, 1, -2), 0.9)]
        meshes = [("cave", "c.ply", True, False, ""), ("cave_visual", "v.ply", False, True, ", seen_by: []")]
        text = world_yaml("cave", -1.5, visibility, speed, meshes, spawns, "scan.xyz")
        data = check_world(yaml.safe_load(text), "cave.world")
        assert [r["name"] for r in data["robots"]] == ["UX_1", "UX_2"]


def test_the_world_reading_tools_refuse_a_typo(tmp_path):
    """The mesh marker and map quality read world files through unexmin.worlds.files.load_world."""
    from unexmin.worlds.files import load_world, world_triangles

    (tmp_path / "meshes").symlink_to(REPO / "worlds" / "meshes")
    file = tmp_path / "tank.world"
    file.write_text((REPO / "worlds" / "tank.world").read_text().replace("collision: true", "colision: true", 1))
    for read in (load_world, world_triangles):
        with pytest.raises(WorldFileError, match=re.escape("unknown key 'meshes[0].colision'")):
            read(str(file))


def test_docs_table_is_the_schemas():
    doc = (REPO / "docs" / "worlds.md").read_text()
    m = re.search(r"<!-- world-schema-table: begin -->\n(.*?)<!-- world-schema-table: end -->", doc, re.S)
    assert m, "docs/worlds.md has no world-schema table"
    assert m.group(1) == schema.markdown_table(), "regenerate it: python -m unexmin.worlds.schema"
    listed = re.findall(r"^\| `([^`]+)` \|", m.group(1), re.M)
    assert listed == schema.key_paths()


def test_a_missing_schema_is_named(monkeypatch, tmp_path):
    monkeypatch.setenv(schema.SCHEMA_ENV, str(tmp_path / "none.yaml"))
    with pytest.raises(FileNotFoundError, match=re.escape(f"world-file schema {tmp_path / 'none.yaml'} not found")):
        read_world(REPO / "worlds" / "tank.world")


def test_world_launch_stops_on_a_typo_with_one_line(tmp_path):
    """`roslaunch unexmin world.launch world_file:=<a world with a typo>`: the simulator (a required node) stops
    start-up with one FATAL line naming the file, the key's path and the nearest key, and the launch ends."""
    from unexmin.scripting.launcher import free_port, private_master_env, stop_process_group

    (tmp_path / "meshes").symlink_to(REPO / "worlds" / "meshes")
    file = tmp_path / "tank.world"
    text = (REPO / "worlds" / "tank.world").read_text()
    assert "anchor.stl" in text
    file.write_text(text.replace("file: meshes/anchor.stl,", "file: meshes/anchor.stl, albdo: [0.1, 0.1, 0.1],", 1))
    port = free_port()
    proc = subprocess.Popen(
        ["roslaunch", "-p", str(port), "unexmin", "world.launch", f"world_file:={file}", "rviz:=false"],
        env=private_master_env(port, tmp_path),
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        start_new_session=True,
    )
    try:
        output, _ = proc.communicate(timeout=120)
    finally:
        stop_process_group(proc)
    fatal = [line for line in output.splitlines() if "FATAL" in line]
    assert len(fatal) == 1, output
    assert (
        f"{file}: unknown key 'meshes[1].albdo' (accepted: name, file, scale, xyz, rpy, collision, visual, seen_by, "
        "albedo, material); did you mean 'albedo'?" in fatal[0]
    ), fatal[0]
    assert "REQUIRED process [simulator" in output, output

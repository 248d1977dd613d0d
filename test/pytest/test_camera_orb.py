"""Real vision software judges the cameras' images: OpenCV's ORB on frames of a mine wall.

Frames come from the simulator's own camera model (bench/camera_fps: the UX-1 description, worlds/mine.world
with its rock material, lights, water and seeded sensor noise, no ROS), written as PPM and read with OpenCV:

- in clear water (`none`), ORB (cv2.ORB_create(nfeatures=5000), default parameters otherwise) finds at least
  500 keypoints in each 640 x 480 frame of a wall at 1-3 m: camera 0 facing the entry shaft's wall (1.8 m) and
  camera 4 looking down at the first level's floor (2.5 m);
- the count falls from `none` to `low` to `medium` to `high`, strictly until it reaches 0 (the wall lost in the
  murk, here from `medium` on). Nearer walls are not used: at 1.0-1.3 m in clear water the fixed exposure
  saturates the LED's spot and `low` gives more keypoints than `none` (auto-exposure off, docs/vision.md "Limits");
- the same views with the walls' material made plain (one albedo, as a mesh without `material:`) give fewer
  than 50: the texture, not the noise or the lights, is what ORB finds.

Needs the built workspace (camera_fps), xacro on PATH and the generated mine (scripts/setup.sh).
Run: source scripts/env.sh; python -m pytest test/pytest/test_camera_orb.py -q
"""

import os
import re
import shutil
import subprocess
from pathlib import Path

import cv2  # opencv-python-headless, pinned in scripts/setup.sh: a missing one fails, never skips
import pytest

from unexmin.worlds.files import link_meshes

REPO = Path(__file__).resolve().parents[2]
MINE = REPO / "worlds" / "mine.world"
LEVELS = ["none", "low", "medium", "high"]
# camera, robot pose x y z [m] yaw [rad]
VIEWS = {"shaft_1.8m": ("camera_0", (4.6, 0.0, -5.0, -0.35)), "floor_2.5m": ("camera_4", (11.5, -0.07, -21.4, 0.0))}


def camera_fps():
    ws = os.environ.get("UNEXMIN_WS", str(REPO.parent / (REPO.name + "_ws")))
    path = Path(ws) / "devel" / "lib" / "unexmin" / "camera_fps"
    if not path.exists():
        pytest.fail(f"{path} not built: catkin_make -j2 camera_fps in {ws}")
    return path


@pytest.fixture(scope="module")
def urdf(tmp_path_factory):
    if not (REPO / "worlds" / "meshes" / "mine" / "mine_collision.ply").exists():
        pytest.fail("the mine's meshes are not generated: run scripts/setup.sh")
    xacro = shutil.which("xacro")
    assert xacro, "xacro not on PATH: source scripts/env.sh"
    out = tmp_path_factory.mktemp("orb") / "ux1.urdf"
    out.write_text(
        subprocess.run(
            [xacro, str(REPO / "urdf" / "ux1.urdf.xacro"), "name:=UX_1"], check=True, capture_output=True, text=True
        ).stdout
    )
    return out


@pytest.fixture(scope="module")
def plain_mine(tmp_path_factory):
    """worlds/mine.world with every `material:` removed (the walls' plain albedo), beside links to its meshes."""
    import yaml

    folder = tmp_path_factory.mktemp("plain")
    world = yaml.safe_load(MINE.read_text())
    for m in world["meshes"]:
        albedo = m.pop("material", {}).get("albedo")
        if albedo:
            m["albedo"] = albedo
    link_meshes(world["meshes"], str(MINE.parent), str(folder))
    path = folder / "mine.world"
    path.write_text(yaml.safe_dump(world))
    return path


def orb_count(urdf, world, view, level, out):
    camera, (x, y, z, yaw) = VIEWS[view]
    subprocess.run(
        [
            str(camera_fps()),
            str(urdf),
            str(world),
            "--camera",
            camera,
            "--size",
            "640x480",
            "--frames",
            "1",
            "--pose",
            str(x),
            str(y),
            str(z),
            str(yaw),
            "--visibility",
            level,
            "--ppm",
            str(out),
        ],
        check=True,
        capture_output=True,
        text=True,
        timeout=300,
    )
    image = cv2.imread(str(out), cv2.IMREAD_GRAYSCALE)
    assert image is not None and image.shape == (480, 640), f"no 640 x 480 frame in {out}"
    return len(cv2.ORB_create(nfeatures=5000).detect(image, None))


@pytest.mark.parametrize("view", sorted(VIEWS))
def test_orb_finds_the_rock_and_loses_it_in_murk(urdf, tmp_path, view):
    counts = [orb_count(urdf, MINE, view, level, tmp_path / f"{level}.ppm") for level in LEVELS]
    print(view, dict(zip(LEVELS, counts)))
    assert counts[0] >= 500, f"{view}: ORB keypoints in clear water {counts[0]}, expected >= 500"
    assert all(
        a > b or a == b == 0 for a, b in zip(counts, counts[1:])
    ), f"{view}: ORB keypoints must fall from none to high: {dict(zip(LEVELS, counts))}"


@pytest.mark.parametrize("view", sorted(VIEWS))
def test_plain_walls_give_orb_nothing(urdf, plain_mine, tmp_path, view):
    count = orb_count(urdf, plain_mine, view, "none", tmp_path / "plain.ppm")
    print(view, "plain", count)
    assert count < 50, f"{view}: {count} ORB keypoints on plain walls: expected few (no texture)"


def test_the_mine_world_has_its_seeds_rock():
    """worlds/mine.world's walls carry the material unexmin.worlds.generator.material draws from the mine's seed (7)."""
    import yaml

    from unexmin.worlds.generator import material as mine_material

    world = yaml.safe_load(MINE.read_text())
    walls = next(m for m in world["meshes"] if m["name"] == "mine")
    assert walls["material"] == mine_material.material(7)
    assert re.search(r"--seed 7\b", MINE.read_text())
    other = mine_material.material(8)
    assert other != mine_material.material(7) and other["kind"] == "rock" and other["seed"] == 8
    with pytest.raises(ValueError, match="seed"):
        mine_material.material(-1)

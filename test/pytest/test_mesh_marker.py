"""The mesh marker (python/unexmin/worlds/mesh_marker.py, nodes/mesh_marker, launch/mesh_marker.launch).

Geometry against closed forms (rotation conventions, a cube's and the tank's water surface: the
tank's interior is 6 m x 4 m, docs/worlds.md), then the real node through roslaunch on a private
master: the latched MarkerArray it publishes is the one build_markers makes.

Run: /work/main_ws/venv/bin/python -m pytest test/pytest/test_mesh_marker.py
"""

import json
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
import trimesh

from unexmin.worlds import mesh_marker as mm
from unexmin.worlds.files import load_world
from unexmin.worlds.meshes import MeshFormatError, read_mesh

REPO = Path(__file__).resolve().parents[2]
WORLDS = REPO / "worlds"


def polygon_area(xy):
    return 0.5 * abs(np.dot(xy[:, 0], np.roll(xy[:, 1], -1)) - np.dot(np.roll(xy[:, 0], -1), xy[:, 1]))


def triangles_area(tris):
    return 0.5 * np.abs(np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])[:, 2]).sum()


def test_read_mesh_gives_the_same_triangles_from_stl_and_ply(tmp_path):
    box = trimesh.creation.box(extents=(2.0, 3.0, 4.0))
    box.export(tmp_path / "b.stl")
    box.export(tmp_path / "b.ply")
    tri_sets = []
    for name in ("b.stl", "b.ply"):
        v, t = read_mesh(tmp_path / name)
        tri_sets.append(sorted(tuple(map(tuple, np.round(v[tri], 6))) for tri in t))
    assert tri_sets[0] == tri_sets[1] and len(tri_sets[0]) == 12
    (tmp_path / "a.stl").write_text("solid x\nendsolid x\n")
    with pytest.raises(MeshFormatError, match="not a binary STL"):
        read_mesh(tmp_path / "a.stl")


def test_cube_section_is_one_square_loop_whose_faces_point_out():
    box = trimesh.creation.box(extents=(2.0, 2.0, 2.0))
    loops = mm.plane_loops(np.asarray(box.vertices), np.asarray(box.faces), 0.25)
    assert len(loops) == 1
    points, normals = loops[0]
    assert polygon_area(points[:, :2]) == pytest.approx(4.0)
    np.testing.assert_allclose(points[:, 2], 0.25)
    assert not mm.faces_inwards(points, normals)  # a solid: no water inside
    inverted = np.asarray(box.faces)[:, ::-1]  # a 2 m cube of water
    points, normals = mm.plane_loops(np.asarray(box.vertices), inverted, 0.25)[0]
    assert mm.faces_inwards(points, normals)
    assert mm.plane_loops(np.asarray(box.vertices), np.asarray(box.faces), 1.5) == []


def test_ear_clipping_covers_a_non_convex_polygon_exactly():
    l_shape = np.array([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]], float)
    for poly in (l_shape, l_shape[::-1]):
        tris = mm.triangulate(poly)
        assert len(tris) == len(poly) - 2
        pts = poly[tris]
        signed = 0.5 * np.cross(pts[:, 1] - pts[:, 0], pts[:, 2] - pts[:, 0])
        assert (signed > 0).all()
        assert signed.sum() == pytest.approx(3.0)


def test_tank_markers_and_its_six_by_four_metre_water_surface():
    world = load_world(WORLDS / "tank.world")
    tris = mm.water_surface(world)
    assert triangles_area(tris) == pytest.approx(24.0, rel=1e-9)  # interior 6 m x 4 m
    np.testing.assert_allclose(tris[..., 2], 0.0, atol=1e-9)
    np.testing.assert_allclose(tris[..., 0].min(), -3.0, atol=1e-6)
    np.testing.assert_allclose(tris[..., 1].max(), 2.0, atol=1e-6)
    array = mm.build_markers(world)
    meshes = [m for m in array.markers if m.ns == "world_meshes"]
    assert [Path(m.mesh_resource[len("file://") :]) for m in meshes] == [
        WORLDS / "meshes/tank.stl",
        WORLDS / "meshes/anchor.stl",
    ]
    assert all(m.type == m.MESH_RESOURCE and m.header.frame_id == "world" for m in meshes)
    assert meshes[1].pose.position.z == pytest.approx(-1.8)
    assert (meshes[1].scale.x, meshes[1].scale.y, meshes[1].scale.z) == (1.0, 1.0, 1.0)
    water = [m for m in array.markers if m.ns == "water_surface"]
    assert len(water) == 1 and len(water[0].points) == 3 * len(tris) and water[0].color.a < 1.0


@pytest.mark.parametrize(
    "file, problem",
    [
        ("/etc/passwd", "is an absolute path"),
        ("../outside.stl", "is not inside the world file's folder"),
        ("meshes/../../outside.stl", "is not inside the world file's folder"),
        ("..", "is not inside the world file's folder"),
    ],
)
def test_a_world_file_cannot_name_a_mesh_outside_its_folder(tmp_path, file, problem):
    # Same rule as the simulator (docs/worlds.md, "Paths"): the node would otherwise read and publish that file.
    (tmp_path / "w").mkdir()
    shutil.copy(WORLDS / "meshes/test_box.stl", tmp_path / "outside.stl")
    world = tmp_path / "w" / "bad.world"
    world.write_text(f"name: w\nmeshes:\n  - {{name: m, file: '{file}'}}\nrobots: [{{name: UX_1}}]\n")
    with pytest.raises(ValueError) as err:
        load_world(world)
    assert str(err.value).startswith(f"{world}: 'meshes[0].file' {file} {problem}")
    # Inside its folder, '..' that stays inside included, it loads the file it names.
    (tmp_path / "w" / "meshes").mkdir()
    shutil.copy(WORLDS / "meshes/test_box.stl", tmp_path / "w" / "meshes" / "box.stl")
    world.write_text("name: w\nmeshes:\n  - {name: m, file: meshes/../meshes/box.stl}\nrobots: [{name: UX_1}]\n")
    assert load_world(world)["meshes"][0]["file"] == str(tmp_path / "w" / "meshes" / "box.stl")


def test_mine_water_surface_is_the_entry_shaft_section():
    man = json.loads((WORLDS / "meshes/mine/mine.json").read_text())
    world = load_world(WORLDS / "mine.world")
    assert [m["name"] for m in world["meshes"] if m["visual"]] == ["mine_visual"]
    tris = mm.water_surface(world)
    half, noise = man["preset"]["shaft_half"], man["wall_noise_max"]
    # inside the 6 m rounded-square shaft whose walls move by at most the noise amplitude
    assert np.abs(tris[..., :2] - man["shaft_xy"]).max() <= half * 2**0.5 + noise
    assert (2 * (half - noise)) ** 2 * 0.8 <= triangles_area(tris) <= (2 * (half + noise)) ** 2


CLIENT = textwrap.dedent("""
    import json, sys, threading
    import rospy
    from visualization_msgs.msg import MarkerArray
    rospy.init_node("mesh_marker_test_client", disable_signals=True)
    got, cond = [], threading.Condition()
    def cb(msg):
        with cond:
            got.append(msg)
            cond.notify_all()
    rospy.Subscriber("/world_meshes", MarkerArray, cb)
    with cond:
        ok = cond.wait_for(lambda: got, 60)
    if not ok:
        sys.exit("no MarkerArray on /world_meshes within 60 s")
    m = got[0]
    print(json.dumps([[k.ns, k.id, k.type, k.header.frame_id, k.mesh_resource, len(k.points),
                       [k.pose.position.x, k.pose.position.y, k.pose.position.z]] for k in m.markers]))
""")


def test_node_publishes_the_markers_latched(tmp_path):
    if not shutil.which("roslaunch"):
        pytest.skip("roslaunch not installed")
    from unexmin.scripting.launcher import free_port, private_master_env

    port = free_port()
    env = private_master_env(port, tmp_path)
    launch = subprocess.Popen(
        ["roslaunch", "--port", str(port), "unexmin", "mesh_marker.launch", f"world:={WORLDS / 'tank.world'}"],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        # The client subscribes whenever it is ready: it only gets the message because it is latched.
        res = subprocess.run([sys.executable, "-c", CLIENT], env=env, capture_output=True, text=True, timeout=90)
        assert res.returncode == 0, res.stderr
        got = json.loads(res.stdout.strip().splitlines()[-1])
    finally:
        os.killpg(launch.pid, 2)
        launch.wait(20)
    expected = mm.build_markers(load_world(WORLDS / "tank.world"))
    assert got == [
        [
            k.ns,
            k.id,
            k.type,
            k.header.frame_id,
            k.mesh_resource,
            len(k.points),
            [k.pose.position.x, k.pose.position.y, k.pose.position.z],
        ]
        for k in expected.markers
    ]


def test_a_large_visual_mesh_is_shown_decimated_near_its_surface(tmp_path):
    sphere = trimesh.creation.icosphere(6, 2.0)  # 81 920 triangles on a sphere of 2 m
    v, t, cell = mm.cluster_decimate(sphere.vertices, sphere.faces, 5000)
    assert 1000 <= len(t) <= 5000 and cell > 0
    assert np.abs(np.linalg.norm(v, axis=1) - 2.0).max() <= cell  # each vertex a mean of its cell's
    assert len(np.unique(np.sort(t, axis=1), axis=0)) == len(t)
    same = mm.cluster_decimate(sphere.vertices, sphere.faces, len(sphere.faces))
    assert same[2] == 0.0 and same[1] is sphere.faces
    from unexmin.worlds.meshes import write_ply

    write_ply(tmp_path / "ball.ply", sphere.vertices, sphere.faces, "ball", inward=False)
    world = {"meshes": [{"name": "ball", "file": str(tmp_path / "ball.ply"), "visual": True}]}
    shown = mm.display_files(world, 5000, str(tmp_path / "cache"))
    dv, dt = read_mesh(shown[str(tmp_path / "ball.ply")])
    assert len(dt) <= 5000 and np.allclose(dv, v, atol=1e-5)  # float32 in the file
    assert mm.display_files(world, 5000, str(tmp_path / "cache")) == shown  # reused, not rewritten
    assert mm.display_files(world, 100_000, str(tmp_path / "cache")) == {}  # small enough as it is

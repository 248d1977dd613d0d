"""A coloured scan keeps its colours through world_from_scan (docs/world_from_scan.md "Colours"): a 4 x 3 x 2 m room
scanned with a red floor and blue walls and ceiling gives a visual mesh whose vertices on the floor are red and the
others blue, a world file whose visual mesh is a vertex_colours material, and a world the simulator's core loads.

Run: python -m pytest test/pytest/test_world_from_scan_colours.py -q -p no:cacheprovider
"""

import numpy as np
import pytest
import trimesh
import yaml

from unexmin.worlds import from_scan as wfs
from unexmin.worlds.from_scan.colours import read_scan_colours, streamed_vertex_colours, vertex_colours
from unexmin.worlds.meshes import read_mesh

RED, BLUE = (200, 30, 30), (30, 60, 200)
FLOOR, TOP = -2.0, 0.0  # [m] the room's floor and ceiling


def room_scan(path, coloured=True):
    """Points every 5 cm (noise 1 cm) on the inside of the room x in [-2, 2], y in [-1.5, 1.5]; floor red."""
    import open3d as o3d

    room = trimesh.creation.box(extents=(4.0, 3.0, TOP - FLOOR))
    room.apply_translation((0.0, 0.0, (TOP + FLOOR) / 2))
    points = wfs.sample_scan(room.triangles, 0.05, 0.01, seed=4)
    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points))
    if coloured:
        colours = np.where((points[:, 2] < FLOOR + 0.05)[:, None], RED, BLUE) / 255.0
        cloud.colors = o3d.utility.Vector3dVector(colours)
    assert o3d.io.write_point_cloud(str(path), cloud)
    return points


@pytest.fixture(scope="module")
def room(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("room")
    room_scan(tmp / "room.ply")
    rep = wfs.build_world(tmp / "room.ply", tmp / "world", name="room", water_level=TOP, visual_edge=0.3, quiet=True)
    return tmp / "world", rep


def test_the_visual_mesh_keeps_the_scans_colours(room):
    import open3d as o3d

    out, rep = room
    assert rep["visual"]["colours"] is True
    mesh = o3d.io.read_triangle_mesh(str(out / rep["visual"]["file"]))
    assert mesh.has_vertex_colors()
    v = np.asarray(mesh.vertices)
    c = np.rint(np.asarray(mesh.vertex_colors) * 255).astype(int)
    floor, above = v[:, 2] < FLOOR + 0.03, v[:, 2] > FLOOR + 0.3
    assert floor.sum() > 20 and above.sum() > 20
    assert (c[floor] == RED).all(axis=1).mean() > 0.98  # the floor's edge may take a wall's point
    assert (c[above] == BLUE).all(axis=1).all()
    mv, mt = read_mesh(str(out / rep["visual"]["file"]))  # what rviz's mesh marker reads: colours skipped
    assert np.allclose(mv, v, atol=1e-6) and len(mt) == len(mesh.triangles)
    world = yaml.safe_load((out / rep["world"]).read_text())
    collision, visual = world["meshes"]
    assert visual["material"] == {"kind": "vertex_colours"}
    assert "seen_by" not in visual and "seen_by" not in collision  # the default rule: the cameras see the visual mesh


def test_an_uncoloured_scan_keeps_the_cameras_on_the_collision_mesh(tmp_path):
    room_scan(tmp_path / "grey.ply", coloured=False)
    assert read_scan_colours(tmp_path / "grey.ply") is None
    rep = wfs.build_world(tmp_path / "grey.ply", tmp_path / "world", water_level=TOP, quiet=True)
    assert rep["visual"]["colours"] is False
    collision, visual = yaml.safe_load((tmp_path / "world" / rep["world"]).read_text())["meshes"]
    assert collision["seen_by"] == ["cameras", "sonars"] and visual["seen_by"] == []
    assert "material" not in visual


def test_each_vertex_takes_its_nearest_points_colour():
    points = np.array([[0.0, 0, 0], [1, 0, 0], [0, 2, 0]])
    colours = np.array([[1, 2, 3], [4, 5, 6], [7, 8, 9]], dtype=np.uint8)
    got = vertex_colours(np.array([[0.9, 0.1, 0], [0.1, 1.5, 0.2], [-1, -1, 0]]), points, colours)
    assert got.tolist() == [[4, 5, 6], [7, 8, 9], [1, 2, 3]]


def test_the_simulator_loads_the_coloured_world(room):
    from unexmin.core import World

    out, rep = room
    world = World(str(out / rep["world"]), robots=1, sensors="none")
    world.step(10)
    assert world.time == pytest.approx(10 * world.dt)


def test_colours_streamed_in_chunks_are_those_of_the_whole_scan(tmp_path):
    """The scan read again chunk by chunk (as build_world does) gives each vertex its nearest point's colour over
    every chunk: the same as one k-d tree over the whole scan, with chunks far smaller than the scan."""
    room_scan(tmp_path / "room.ply")
    points, colours = read_scan_colours(tmp_path / "room.ply")
    rng = np.random.default_rng(7)
    vertices = rng.uniform((-2, -1.5, FLOOR), (2, 1.5, TOP), size=(300, 3))
    got = streamed_vertex_colours(tmp_path / "room.ply", vertices, chunk=997)
    assert len(points) > 20 * 997
    assert np.array_equal(got, vertex_colours(vertices, points, colours))

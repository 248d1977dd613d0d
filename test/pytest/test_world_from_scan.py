"""Worlds from scans (python/unexmin/worlds/from_scan/, docs/world_from_scan.md).

Known answers: point clouds are sampled here from meshes whose geometry is known (the tank's inner
walls, a section of a generated mine, a sphere, a box), with noise (sd 2 cm) and missing patches; the
reconstructed surface is measured against the true mesh both ways (Open3D's exact point-triangle
distance), the flooded volume against the tank's 6 x 4 x 3 m, the spawn points against the true walls.

Run: python -m pytest test/pytest/test_world_from_scan.py -q -p no:cacheprovider
"""

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import trimesh
import yaml

from unexmin.worlds import from_scan as wfs
from unexmin.worlds import generator as mg
from unexmin.worlds.from_scan.surface import boundary_loops
from unexmin.worlds.meshes import read_mesh, sample_surface

REPO = Path(__file__).resolve().parents[2]
TANK = REPO / "worlds" / "meshes" / "tank.stl"
NOISE = 0.02  # [m] sd of the scan noise (issue 17)
MEAN_TOL, P95_TOL = 0.05, 0.15  # [m] the bounds on the surface distance
HULL, CLEARANCE = 0.3, 0.6  # [m] UX-1 hull radius; the tool's default spawn clearance
TANK_X, TANK_Y, TANK_FLOOR, TANK_RIM = 3.0, 2.0, -3.0, 0.3  # [m] docs/worlds.md: interior 6 x 4, floor, rim
SECTION_X, SECTION_Z = 20.0, -28.0  # [m] the mine section: x < 20, z > -28 (shaft, level 0, pump station)


def tank_inner_triangles():
    """The faces of tank.stl that a scan from inside sees: the floor and the inner walls below the rim."""
    mesh = trimesh.load(str(TANK), force="mesh")
    c = mesh.triangles_center
    inner = (
        (np.abs(c[:, 0]) <= TANK_X + 1e-6)
        & (np.abs(c[:, 1]) <= TANK_Y + 1e-6)
        & (c[:, 2] >= TANK_FLOOR - 1e-6)
        & (c[:, 2] < TANK_RIM - 1e-6)
    )
    return mesh.triangles[inner]


def write_ply_cloud(path, points, normals=None):
    import open3d as o3d

    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points))
    if normals is not None:
        cloud.normals = o3d.utility.Vector3dVector(normals)
    assert o3d.io.write_point_cloud(str(path), cloud)


def surface_distances(recon_tris, true_tris, keep):
    """Both ways, on points sampled every 5 cm: reconstruction -> truth and truth -> reconstruction [m],
    only where `keep(points)` (the region the scan covered)."""
    out = []
    for src, dst in ((recon_tris, true_tris), (true_tris, recon_tris)):
        pts, _ = sample_surface(src, 0.05, seed=5)
        pts = pts[keep(pts)]
        flat = dst.reshape(-1, 3)
        scene = wfs.raycasting_scene(flat, np.arange(len(flat)).reshape(-1, 3))
        out.append(wfs.distances(scene, pts))
    return out


def world_of(out, rep):
    world = yaml.safe_load((out / rep["world"]).read_text())
    v, t = read_mesh(str(out / world["meshes"][0]["file"]))
    return world, v, t


@pytest.fixture(scope="module")
def tank(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("tank_scan")
    truth = tank_inner_triangles()
    points = wfs.sample_scan(truth, 0.05, NOISE, holes=6, hole_radius=0.5, seed=1)
    scan = tmp / "tank_scan.xyz"
    wfs.write_xyz(scan, points)
    rep = wfs.build_world(scan, tmp / "world", name="tank_scan", water_level=0.0, quiet=True)
    return tmp / "world", rep, truth, points


@pytest.fixture(scope="module")
def mine(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("mine_scan")
    mg.generate(tmp / "mine", seed=3, preset="small", quiet=True)
    v, t = read_mesh(str(tmp / "mine" / "mine_collision.ply"))
    tris = v[t]
    c = tris.mean(axis=1)
    section = tris[(c[:, 0] < SECTION_X) & (c[:, 2] > SECTION_Z)]
    points = wfs.sample_scan(section, 0.1, NOISE, holes=10, hole_radius=0.5, seed=2)
    scan = tmp / "section.ply"
    write_ply_cloud(scan, points)
    rep = wfs.build_world(scan, tmp / "world", water_level=0.0, quiet=True)
    return tmp / "world", rep, section, trimesh.Trimesh(v, t[:, ::-1])  # the void as an outward solid


def test_tank_surface_lies_on_the_true_walls(tank):
    out, rep, truth, _ = tank
    _, v, t = world_of(out, rep)

    def below_rim(p):  # the cap over the open top is not in the scan
        return p[:, 2] < TANK_RIM - 0.1

    to_truth, to_recon = surface_distances(v[t], truth, below_rim)
    for d in (to_truth, to_recon):
        assert d.mean() <= MEAN_TOL and np.percentile(d, 95) <= P95_TOL, (d.mean(), np.percentile(d, 95))
    assert rep["scan_to_mesh"]["mean"] <= MEAN_TOL and rep["scan_to_mesh"]["p95"] <= P95_TOL


def test_tank_water_is_closed_faces_the_water_and_holds_the_tank(tank):
    out, rep, _, _ = tank
    _, v, t = world_of(out, rep)
    mesh = trimesh.Trimesh(v, t, process=False)
    assert mesh.is_watertight and mesh.is_winding_consistent and rep["closed"]
    assert mesh.volume < 0  # faces into the enclosed void: the water side
    assert rep["holes_closed"] >= 1  # the open top at least
    flooded = 2 * TANK_X * 2 * TANK_Y * (0.0 - TANK_FLOOR)  # 72 m^3 below z = 0
    assert rep["flooded_volume"] == pytest.approx(flooded, rel=0.03)
    inner = 2 * TANK_X * 2 * TANK_Y + 2 * (2 * TANK_X + 2 * TANK_Y) * (TANK_RIM - TANK_FLOOR)  # 90 m^2
    assert rep["wall_area"] == pytest.approx(inner, rel=0.1)  # less the missing patches


def test_tank_spawns_are_in_the_water_with_clearance(tank):
    out, rep, _, _ = tank
    world, _, _ = world_of(out, rep)
    robots = [np.array(r["xyz"], dtype=float) for r in world["robots"]]
    assert len(robots) == 3 and [r["name"] for r in world["robots"]] == ["UX_1", "UX_2", "UX_3"]
    for x, y, z in robots:
        room = min(TANK_X - abs(x), TANK_Y - abs(y), z - TANK_FLOOR)  # the true walls
        assert room >= CLEARANCE - 0.05, (x, y, z)
        assert z + HULL <= world["water"]["surface_z"] - 0.4
    assert min(np.linalg.norm(a - b) for i, a in enumerate(robots) for b in robots[i + 1 :]) >= 1.5


def test_mine_section_surface_lies_on_the_true_walls(mine):
    out, rep, section, _ = mine
    _, v, t = world_of(out, rep)

    def covered(p):  # away from the cuts
        return (p[:, 0] < SECTION_X - 2.0) & (p[:, 2] > SECTION_Z + 2.0)

    to_truth, to_recon = surface_distances(v[t], section, covered)
    for d in (to_truth, to_recon):
        assert d.mean() <= MEAN_TOL and np.percentile(d, 95) <= P95_TOL, (d.mean(), np.percentile(d, 95))


def test_mine_section_water_is_closed_and_spawns_are_inside(mine):
    out, rep, _, solid = mine
    world, v, t = world_of(out, rep)
    mesh = trimesh.Trimesh(v, t, process=False)
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume < 0
    assert rep["holes_closed"] >= 2  # the section's cuts through level 0 and the shaft
    robots = np.array([r["xyz"] for r in world["robots"]], dtype=float)
    assert len(robots) == 3
    assert solid.contains(robots).all()
    _, room, _ = trimesh.proximity.closest_point(solid, robots)
    assert (room >= CLEARANCE - 0.1).all(), room
    assert (robots[:, 2] + HULL <= -0.4).all()


def test_normals_turn_towards_the_void_inside_a_sphere():
    rng = np.random.default_rng(4)
    d = rng.normal(size=(6000, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    points = 3.0 * d + rng.normal(0.0, NOISE, d.shape)
    normals = d * rng.choice([-1.0, 1.0], size=(len(d), 1))  # unoriented: random sides
    oriented, decided = wfs.orient_towards_void(points, normals, 0.1, seed=0)
    assert decided > 0.99
    assert (np.einsum("ij,ij->i", oriented, -d) > 0).all()  # every one towards the centre


def test_holes_close_into_a_consistent_closed_surface():
    box = trimesh.creation.box(extents=(2.0, 1.0, 1.0))
    top = np.where(box.face_normals[:, 2] > 0.5)[0]  # the two triangles of the 2 x 1 top
    t = np.delete(box.faces, top, axis=0)
    v, t2, holes, area, cap = wfs.close_holes(box.vertices, t)
    mesh = trimesh.Trimesh(v, t2, process=False)
    assert holes == 1 and cap.sum() == 4 and area == pytest.approx(2.0)
    assert mesh.is_watertight and mesh.is_winding_consistent
    assert mesh.volume == pytest.approx(2.0)


def test_two_holes_touching_at_a_vertex_are_two_loops_and_close():
    # the walk along the boundary enters the shared vertex twice: it must come out as two simple loops
    assert sorted(map(sorted, boundary_loops(np.array([[1, 2, 0], [3, 4, 0]])))) == [[0, 1, 2], [0, 3, 4]]
    sphere = trimesh.creation.icosphere(1, 1.0)  # 42 vertices, 80 faces
    faces = np.asarray(sphere.faces)
    for p in range(len(sphere.vertices)):  # at each vertex, two of its faces that share only that vertex
        around = np.where((faces == p).any(axis=1))[0]
        pair = next((a, b) for a in around for b in around if a < b and len(set(faces[a]) & set(faces[b])) == 1)
        t = np.delete(faces, pair, axis=0)
        v, t2, holes, area, cap = wfs.close_holes(np.asarray(sphere.vertices), t)
        mesh = trimesh.Trimesh(v, t2, process=False)
        assert holes == 2 and mesh.is_watertight and mesh.is_winding_consistent, f"holes meeting at vertex {p}"
        assert mesh.volume == pytest.approx(sphere.volume, rel=0.02)


def test_a_fold_in_the_stitched_surface_is_mended_into_a_closed_one():
    from unexmin.worlds.from_scan.stages.stitching import mend_folds

    sphere = trimesh.creation.icosphere(3, 2.0)
    v, t = np.asarray(sphere.vertices), np.asarray(sphere.faces, dtype=np.int64)
    assert mend_folds(v, t)[2] == 0  # a closed surface is left as it is
    folded = t.copy()
    folded[7] = folded[7][::-1]  # one face turned over: its three edges each run the same way as a neighbour's
    mv, mt, folds = mend_folds(v, folded)
    mesh = trimesh.Trimesh(mv, mt, process=False)
    assert folds == 3 and mesh.is_watertight and mesh.is_winding_consistent
    assert mesh.volume == pytest.approx(sphere.volume, rel=0.01)


def test_readers_agree(tmp_path):
    rng = np.random.default_rng(6)
    points = rng.uniform(-5, 5, size=(500, 3))
    normals = rng.normal(size=(500, 3))
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    write_ply_cloud(tmp_path / "a.ply", points, normals)
    np.savetxt(tmp_path / "a.csv", points, delimiter=",", fmt="%.6f")
    import laspy

    las = laspy.LasData(laspy.LasHeader(point_format=3, version="1.2"))
    las.header.scales, las.header.offsets = [0.001] * 3, [0.0] * 3
    las.x, las.y, las.z = points.T
    las.write(str(tmp_path / "a.laz"))
    p, n = wfs.read_scan(tmp_path / "a.ply")
    assert np.allclose(p, points, atol=1e-6) and np.allclose(n, normals, atol=1e-6)
    p, n = wfs.read_scan(tmp_path / "a.csv")
    assert np.allclose(p, points, atol=1e-6) and n is None
    p, n = wfs.read_scan(tmp_path / "a.laz")
    assert np.allclose(p, points, atol=1e-3) and n is None
    (tmp_path / "a.e57").write_text("x")
    with pytest.raises(wfs.ScanError, match=r"a\.e57: unknown point cloud extension"):
        wfs.read_scan(tmp_path / "a.e57")
    with pytest.raises(wfs.ScanError, match="no such file"):
        wfs.read_scan(tmp_path / "missing.ply")


@pytest.mark.parametrize("case", ["line", "few", "wall"])
def test_a_cloud_with_no_usable_surface_is_one_clear_error_line(tmp_path, case):
    rng = np.random.default_rng(8)
    if case == "line":  # a pole: points along a 20 m line
        s = rng.uniform(0, 20, 3000)
        points = np.column_stack([s, 0.5 * s, np.zeros_like(s)]) + rng.normal(0, NOISE, (3000, 3))
    elif case == "few":  # 50 points
        points = rng.uniform(-5, 5, size=(50, 3))
    else:  # one flat wall: a surface, but it holds no water
        xy = rng.uniform(0, 8, size=(8000, 2))
        points = np.column_stack([xy, rng.normal(0, NOISE, 8000)])
    scan = tmp_path / f"{case}.xyz"
    wfs.write_xyz(scan, points)
    run = subprocess.run(
        [sys.executable, "-m", "unexmin.worlds.from_scan", str(scan), "--out", str(tmp_path / "o"), "--quiet"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 2
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"world_from_scan: error: {scan}: no usable surface"), run.stderr
    assert not (tmp_path / "o").exists() or not any((tmp_path / "o").iterdir())


def test_the_world_launches_the_robot_moves_and_the_m3_sees_the_scanned_walls(tank, tmp_path):
    """`roslaunch unexmin world.launch world_file:=...` with the world made from the tank's scan: the
    M3's ranges at rest are those of rays cast against the true tank, and thrust moves the robot."""
    import open3d as o3d
    import rospy
    import tf2_ros

    from unexmin import Simulation
    from unexmin.geometry import quaternion_to_rpy, rpy_matrix

    out, rep, _, _ = tank
    launch = tmp_path / "scan_world.launch"
    launch.write_text(
        '<launch><include file="$(find unexmin)/launch/world.launch">'
        f'<arg name="world_file" value="{out / rep["world"]}"/><arg name="robots" value="1"/>'
        '<arg name="realtime" value="false"/><arg name="paused" value="true"/><arg name="sensors" value="m3"/>'
        '</include></launch>\n'
    )
    tank_mesh = trimesh.load(str(TANK), force="mesh")  # the true walls, whole
    scene = wfs.raycasting_scene(tank_mesh.vertices, tank_mesh.faces)
    with Simulation.launch(launch_file=launch, log_dir=str(tmp_path / "log"), timeout=120.0) as sim:
        ux = sim.robot("UX_1", streams=["m3/scan"])
        tf = tf2_ros.Buffer()
        tf2_ros.TransformListener(tf)
        sim.run_for(0.5)
        scan = ux.latest("m3/scan")
        pose = ux.odom().pose.pose
        mount = tf.lookup_transform("UX_1/base_link", scan.header.frame_id, rospy.Time(0), rospy.Duration(30.0))
        # world <- m3: the robot's pose then the URDF mount (static)
        R_b = rpy_matrix(
            quaternion_to_rpy(pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w)
        )
        m = mount.transform
        R_m = rpy_matrix(quaternion_to_rpy(m.rotation.x, m.rotation.y, m.rotation.z, m.rotation.w))
        origin = np.array([pose.position.x, pose.position.y, pose.position.z]) + R_b @ [
            m.translation.x,
            m.translation.y,
            m.translation.z,
        ]
        ranges = np.array(scan.ranges)
        azimuth = scan.angle_min + scan.angle_increment * np.arange(len(ranges))
        expected = np.full(len(ranges), np.inf)
        for elevation in np.radians([-1.5, -0.75, 0.0, 0.75, 1.5]):  # the fan's 3 deg: first echo
            d = (
                np.column_stack(
                    [
                        np.cos(azimuth) * math.cos(elevation),
                        np.sin(azimuth) * math.cos(elevation),
                        np.full(len(ranges), math.sin(elevation)),
                    ]
                )
                @ (R_b @ R_m).T
            )
            rays = o3d.core.Tensor(np.hstack([np.tile(origin, (len(d), 1)), d]).astype(np.float32))
            expected = np.minimum(expected, scene.cast_rays(rays)["t_hit"].numpy())
        valid = np.isfinite(ranges) & (ranges >= scan.range_min) & (ranges <= scan.range_max)
        assert valid.sum() >= 0.9 * len(ranges)
        err = np.abs(ranges[valid] - expected[valid])
        assert np.median(err) <= 0.05 and np.percentile(err, 95) <= P95_TOL, (np.median(err), np.percentile(err, 95))
        start = np.array([pose.position.x, pose.position.y, pose.position.z])
        ux.thrusts(20.0 * np.array([0.5, 0.0, -0.5, 0.0, 0.5, 0.0, -0.5, 0.0]))  # surge (test/rostest/mine_multi.py)
        sim.run_for(3.0)
        p = ux.odom().pose.pose.position
        moved = np.array([p.x, p.y, p.z]) - start
        assert moved[0] > 0.5 and abs(moved[1]) < 0.2, moved

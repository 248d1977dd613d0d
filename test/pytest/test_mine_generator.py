"""The mine generator (python/unexmin/worlds/generator/) and the mine world (worlds/mine.world).

Expected values come from geometry written here (capsule and superellipse volumes, the hull radius,
the Kaatiala figures of thesis 6.3), and trimesh (an independent library) reads back what the
generator wrote. The fast checks use the `small` preset (same construction, a few seconds); the full
Kaatiala-size mesh that scripts/setup.sh generates into worlds/meshes/mine/ is checked as shipped.

Run: /work/main_ws/venv/bin/python -m pytest test/pytest/test_mine_generator.py
"""

import dataclasses
import hashlib
import json
import math
from pathlib import Path

import numpy as np
import pytest
import trimesh
import yaml

from unexmin.worlds.generator import generator as mg

REPO = Path(__file__).resolve().parents[2]
MINE_WORLD = REPO / "worlds" / "mine.world"
SHIPPED = REPO / "worlds" / "meshes" / "mine"
SETUP_SEED = 7  # scripts/setup.sh and worlds/mine.world
R_HULL = 0.3  # [m] UX-1 hull radius (0.6 m sphere)
CLEARANCE = 0.3  # [m] water required between a spawned hull and the rock
SEED = 3


class NoWalls:
    """Smooth walls (no noise), for closed-form volumes."""

    def __call__(self, pts, min_wavelength=0.0):
        return np.zeros(len(pts))


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    out = tmp_path_factory.mktemp("mine_small")
    man = mg.generate(out, seed=SEED, preset="small", quiet=True)
    return out, man


def test_generator_reports_the_rock_of_its_seed(small):
    """The report names the walls' material drawn from the mine's seed (unexmin.worlds.generator.material)."""
    from unexmin.worlds.generator import material as mine_material

    assert small[1]["material"] == mine_material.material(SEED, "small")
    assert small[1]["material"]["seed"] == SEED and small[1]["material"]["kind"] == "rock"


def sha(path):
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def as_solid(path):
    """The void as an outward-facing solid (the files face into the void), so that trimesh's
    containment and signed distance are positive in the water."""
    mesh = trimesh.load(str(path), force="mesh")
    mesh.invert()
    return mesh


def world_robots():
    """The UX-1s of worlds/mine.world (the generator's spawns); the other vehicles: other_vehicles()."""
    return [r for r in yaml.safe_load(MINE_WORLD.read_text())["robots"] if r["description"] == "ux1.urdf.xacro"]


def other_vehicles():
    return [r for r in yaml.safe_load(MINE_WORLD.read_text())["robots"] if r["description"] != "ux1.urdf.xacro"]


# ------------------------------------------------------------------------------------------------
# one capsule against closed-form volumes
# ------------------------------------------------------------------------------------------------
def superellipse_area(a, b, p):
    """Area of |y/a|^p + |z/b|^p <= 1."""
    return 4.0 * a * b * math.gamma(1.0 + 1.0 / p) ** 2 / math.gamma(1.0 + 2.0 / p)


def capsule_manifold(A, B, tunnel, edge):
    import manifold3d as mf

    v, t = mg.capsule(np.array(A, float), np.array(B, float), tunnel, edge, NoWalls(), 0.0)
    return mf.Manifold(mf.Mesh(vert_properties=v.astype(np.float32), tri_verts=t.astype(np.uint32)))


def test_smooth_elliptic_capsule_has_the_volume_of_a_cylinder_plus_an_ellipsoid():
    a, b, c, length = 2.0, 1.5, 1.7, 10.0
    tunnel = mg.Tunnel("gallery", [[0, 0, 0], [1, 0, 0]], a=a, b=b, c=c, p_floor=2.0, p_roof=2.0)
    m = capsule_manifold([1.0, 2.0, -3.0], [1.0 + 6.0, 2.0 + 8.0, -3.0], tunnel, 0.1)  # |AB| = 10
    assert m.status().name == "NoError"
    expected = math.pi * a * b * length + 4.0 / 3.0 * math.pi * a * b * c
    assert m.volume() == pytest.approx(expected, rel=2e-3)
    assert m.volume() < expected  # inscribed polygons


def test_superellipse_cross_section_area_per_metre_of_gallery():
    a, b, pf, pr = 2.1, 1.9, 2.6, 2.0
    tunnel = mg.Tunnel("gallery", [[0, 0, 0], [1, 0, 0]], a=a, b=b, p_floor=pf, p_roof=pr)
    long = capsule_manifold([0, 0, 0], [12.0, 0, 0], tunnel, 0.08).volume()
    short = capsule_manifold([0, 0, 0], [4.0, 0, 0], tunnel, 0.08).volume()
    # floor half from exponent pf, roof half from pr; the rounded ends cancel in the difference
    area = 0.5 * superellipse_area(a, b, pf) + 0.5 * superellipse_area(a, b, pr)
    assert (long - short) / 8.0 == pytest.approx(area, rel=3e-3)


def test_vertical_shaft_capsule_spans_its_end_points_plus_its_cap():
    tunnel = mg.Tunnel("shaft", [[0, 0, 0], [1, 0, 0]], a=3.0, b=3.0, c=3.0, p_floor=2.6, p_roof=2.6)
    lo, hi = np.reshape(capsule_manifold([5, 1, 3], [5, 1, -40], tunnel, 0.3).bounding_box(), (2, 3))
    assert lo[2] == pytest.approx(-43.0, abs=1e-3) and hi[2] == pytest.approx(6.0, abs=1e-3)
    # rounded square: at least the half size along the frame's axes, at most a sqrt(2) diagonal
    assert np.all(hi[:2] - np.array([5, 1]) >= 3.0 - 1e-3) and np.all(hi[:2] - np.array([5, 1]) <= 3.0 * 1.42)


def test_rough_walls_are_bounded_by_the_sum_of_the_octave_amplitudes_and_use_them():
    walls = mg.RoughWalls(mg.PRESETS["full"].octaves, seed=11)
    pts = np.random.default_rng(0).uniform(-300.0, 300.0, (200_000, 3))
    d = walls(pts)
    bound = sum(amp for _, amp in mg.PRESETS["full"].octaves)
    assert walls.max_amplitude() == pytest.approx(bound)
    assert np.abs(d).max() <= bound
    assert d.std() > 0.1 * bound  # not flat
    coarse = walls(pts, min_wavelength=3.0)  # only the 18 m and 6 m octaves
    assert np.abs(d - coarse).max() <= 0.07 + 0.035 + 1e-12
    assert np.array_equal(walls(pts), mg.RoughWalls(mg.PRESETS["full"].octaves, seed=11)(pts))


# ------------------------------------------------------------------------------------------------
# the generated small mine
# ------------------------------------------------------------------------------------------------
def test_same_seed_gives_the_same_bytes_and_another_seed_another_mine(small, tmp_path):
    out, man = small
    again = mg.generate(tmp_path / "again", seed=SEED, preset="small", quiet=True)
    for key in ("collision", "visual"):
        assert again[key]["sha256"] == man[key]["sha256"] == sha(out / man[key]["file"])
        assert sha(tmp_path / "again" / man[key]["file"]) == man[key]["sha256"]
    other = mg.generate(tmp_path / "other", seed=SEED + 1, preset="small", quiet=True)
    assert other["collision"]["sha256"] != man["collision"]["sha256"]


@pytest.mark.parametrize("key", ["collision", "visual"])
def test_meshes_are_closed_face_the_water_and_match_the_report(small, key):
    out, man = small
    rep = man[key]
    mesh = trimesh.load(str(out / rep["file"]), force="mesh")  # merges vertices by position
    assert mesh.is_watertight and mesh.is_winding_consistent
    assert len(mesh.faces) == rep["triangles"]
    assert mesh.volume < 0.0  # faces point into the void
    assert -mesh.volume == pytest.approx(rep["volume"], rel=1e-5)
    assert mesh.area == pytest.approx(rep["area"], rel=1e-5)
    np.testing.assert_allclose(mesh.bounds, [rep["bbox_min"], rep["bbox_max"]], atol=2e-3)
    assert rep["flooded_volume"] < rep["volume"]  # the shaft's top is dry
    if key == "collision":
        assert rep["triangles"] >= mg.PRESETS["small"].min_triangles


def test_visual_mesh_is_lighter_and_close_to_the_collision_mesh(small):
    out, man = small
    c, v = man["collision"], man["visual"]
    assert v["triangles"] < c["triangles"] / 2
    assert v["volume"] == pytest.approx(c["volume"], rel=0.06)
    np.testing.assert_allclose(v["bbox_min"], c["bbox_min"], atol=0.3)
    np.testing.assert_allclose(v["bbox_max"], c["bbox_max"], atol=0.3)


def test_small_mine_volume_is_that_of_its_smooth_tunnels_within_the_wall_noise(small):
    _, man = small
    P = mg.PRESETS["small"]
    smooth = mg.build_solid(mg.make_layout(P, SEED), 0.3, NoWalls(), 0.0).volume()
    # walls move by at most the noise amplitude: the void's volume by at most that times its area
    assert abs(man["collision"]["volume"] - smooth) <= man["wall_noise_max"] * man["collision"]["area"]
    assert abs(man["collision"]["volume"] - smooth) < 0.1 * smooth


def chain(segments):
    """Closed polylines (K x 2) from unordered segments (S x 2 x 2) whose ends meet exactly."""
    keys = [tuple(np.round(p, 6)) for p in segments.reshape(-1, 2)]
    ends = {}
    for i, k in enumerate(keys):
        ends.setdefault(k, []).append(i // 2)
    assert all(len(v) == 2 for v in ends.values()), "open section"
    used, loops = set(), []
    for start in range(len(segments)):
        if start in used:
            continue
        loop, s, k = [], start, keys[2 * start]
        while s not in used:
            used.add(s)
            loop.append(k)
            k = keys[2 * s + 1] if keys[2 * s] == k else keys[2 * s]
            s = ends[k][0] if ends[k][1] == s else ends[k][1]
        loops.append(np.array(loop))
    return loops


def test_only_the_entry_shaft_reaches_the_water_surface(small):
    out, man = small
    mesh = trimesh.load(str(out / man["collision"]["file"]), force="mesh")
    segments = trimesh.intersections.mesh_plane(mesh, [0, 0, 1], [0, 0, man["surface_z"]])
    loops = chain(segments[:, :, :2])
    assert len(loops) == 1
    xy = loops[0]
    np.testing.assert_allclose(xy.mean(axis=0), man["shaft_xy"], atol=0.5)
    half = mg.PRESETS["small"].shaft_half
    area = 0.5 * abs(np.dot(xy[:, 0], np.roll(xy[:, 1], -1)) - np.dot(np.roll(xy[:, 0], -1), xy[:, 1]))
    # a 6 m rounded square (superellipse p = 2.6) whose walls move by at most the noise amplitude
    nominal = superellipse_area(half, half, 2.6)
    assert superellipse_area(half - man["wall_noise_max"], half - man["wall_noise_max"], 2.6) <= area
    assert area <= superellipse_area(half + man["wall_noise_max"], half + man["wall_noise_max"], 2.6)
    assert area == pytest.approx(nominal, rel=0.25)


def test_cli_skips_current_outputs_and_regenerates_on_force(tmp_path, capsys):
    args = ["--preset", "small", "--seed", "5", "--out", str(tmp_path), "--quiet"]
    assert mg.main(args) == 0
    first = (tmp_path / "mine_collision.ply").stat().st_mtime_ns
    assert "collision:" in capsys.readouterr().out
    assert mg.main(args) == 0
    assert "up to date" in capsys.readouterr().out
    assert (tmp_path / "mine_collision.ply").stat().st_mtime_ns == first
    (tmp_path / "mine_visual.ply").write_bytes(b"damaged")
    assert not mg.is_current(tmp_path, "mine", 5, mg.PRESETS["small"])
    assert not mg.is_current(tmp_path, "mine", 6, mg.PRESETS["small"])
    assert mg.main(args + ["--force"]) == 0
    assert mg.is_current(tmp_path, "mine", 5, mg.PRESETS["small"])


def test_bad_seed_and_preset_are_rejected(tmp_path):
    with pytest.raises(ValueError, match="seed must be a non-negative integer"):
        mg.generate(tmp_path, seed=-1, preset="small")
    with pytest.raises(ValueError, match="a ramp at gradient"):
        mg.make_layout(dataclasses.replace(mg.PRESETS["small"], level_spacing=40.0), 0)
    with pytest.raises(SystemExit):
        mg.main(["--out", str(tmp_path), "--preset", "huge"])


# ------------------------------------------------------------------------------------------------
# spawn points of worlds/mine.world
# ------------------------------------------------------------------------------------------------
def test_world_spawns_are_the_generator_spawns_submerged_and_apart():
    robots = world_robots()
    assert [r["name"] for r in robots] == ["UX_1", "UX_2", "UX_3"]
    world = yaml.safe_load(MINE_WORLD.read_text())
    for preset in ("small", "full"):
        layout = mg.make_layout(mg.PRESETS[preset], SETUP_SEED)
        np.testing.assert_allclose([r["xyz"] for r in robots], layout.spawns, atol=1e-9)
    for i, r in enumerate(robots):
        assert r["xyz"][2] + R_HULL <= world["water"]["surface_z"] - 1.0  # a metre of water above
        for other in robots[i + 1 :]:
            assert math.dist(r["xyz"], other["xyz"]) >= 2 * R_HULL + 1.0


def spawn_clearances(solid, points):
    inside = solid.contains(points)
    _, distance, _ = trimesh.proximity.closest_point(solid, points)
    return inside, distance


def test_small_mine_spawn_points_are_in_water_with_clearance(small):
    out, man = small
    points = np.array([r["xyz"] for r in world_robots()])
    inside, distance = spawn_clearances(as_solid(out / man["collision"]["file"]), points)
    assert inside.all()
    assert (distance >= R_HULL + CLEARANCE).all(), distance
    # and a point in the rock beside the shaft is outside the water
    rock = np.array([[man["shaft_xy"][0], 14.0, -10.0]])
    assert not as_solid(out / man["collision"]["file"]).contains(rock).any()


# ------------------------------------------------------------------------------------------------
# the full-size mine generated by scripts/setup.sh
# ------------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def shipped():
    path = SHIPPED / "mine.json"
    if not path.exists():
        pytest.fail(f"{path} is missing: run scripts/setup.sh (it generates the mine meshes)")
    return json.loads(path.read_text())


def test_shipped_mine_is_current_full_size_and_kaatiala_scale(shipped):
    assert mg.is_current(SHIPPED, "mine", SETUP_SEED, mg.PRESETS["full"])
    c = shipped["collision"]
    assert c["triangles"] >= 1_000_000
    header = (SHIPPED / c["file"]).read_bytes()[:400].decode("ascii", "replace")
    assert f"element face {c['triangles']}\n" in header
    size = np.subtract(c["bbox_max"], c["bbox_min"])
    assert 600.0 <= size[0] <= 640.0  # thesis 6.3: max length 620 m
    assert size[1] <= 30.0  # max width 30 m
    assert 340.0 <= -c["bbox_min"][2] <= 370.0  # max depth 353 m below the water
    assert shipped["visual"]["triangles"] <= 300_000
    assert shipped["tunnels"]["chamber"] >= 3 and shipped["tunnels"]["crosscut"] >= 20
    assert len(shipped["levels_z"]) >= 8


def test_world_file_points_at_the_shipped_meshes():
    meshes = {m["name"]: m for m in yaml.safe_load(MINE_WORLD.read_text())["meshes"]}
    assert (MINE_WORLD.parent / meshes["mine"]["file"]).resolve() == (SHIPPED / "mine_collision.ply").resolve()
    assert meshes["mine"]["collision"] and not meshes["mine"]["visual"]
    assert (MINE_WORLD.parent / meshes["mine_visual"]["file"]).resolve() == (SHIPPED / "mine_visual.ply").resolve()
    assert meshes["mine_visual"]["visual"] and not meshes["mine_visual"]["collision"]


def test_shipped_mine_spawn_points_are_in_water_with_clearance(shipped):
    points = np.array([r["xyz"] for r in world_robots()])
    inside, distance = spawn_clearances(as_solid(SHIPPED / shipped["collision"]["file"]), points)
    assert inside.all()
    assert (distance >= R_HULL + CLEARANCE).all(), distance


# [m] the half-length of each other vehicle's hull (docs/adding_a_vehicle.md): the BlueROV2 Heavy's half diagonal of
# 0.457 x 0.575 x 0.254 m, the REMUS 100's half length 1.33 / 2
HALF_SIZE = {"bluerov2_heavy.urdf.xacro": 0.5 * math.sqrt(0.457**2 + 0.575**2 + 0.254**2), "remus100.urdf.xacro": 0.665}


def test_shipped_mine_other_vehicles_are_in_water_with_clearance(shipped):
    others = other_vehicles()
    assert [r["name"] for r in others] == ["ROV_1", "AUV_1"]
    inside, distance = spawn_clearances(as_solid(SHIPPED / shipped["collision"]["file"]), [r["xyz"] for r in others])
    assert inside.all()
    assert (distance >= [HALF_SIZE[r["description"]] + CLEARANCE for r in others]).all(), distance


def test_world_file_holds_the_water_and_geology_of_its_seed():
    """worlds/mine.world's `water:` and `geology:` are what the generator draws from the mine's seed."""
    from unexmin.worlds.generator import science

    world = yaml.safe_load(MINE_WORLD.read_text())
    assert world["water"] == science.water(SETUP_SEED)
    assert world["geology"] == science.geology(SETUP_SEED)
    assert yaml.safe_load(science.world_blocks(SETUP_SEED)) == {
        "water": science.water(SETUP_SEED),
        "geology": science.geology(SETUP_SEED),
    }


@pytest.mark.parametrize("seed, preset", [(SETUP_SEED, "full"), (SEED, "small"), (11, "small")])
def test_science_of_a_seed_is_stratified_water_and_ore_where_a_dive_reaches(seed, preset):
    """The column: a warm, fresher, neutral layer over a chemocline below level 0 with acid, conductive water; the
    ore bodies: every one crossing or touching level 0's gallery or the entry shaft within its first 150 m."""
    from unexmin.worlds.generator import science

    P = mg.PRESETS[preset]
    w, g = science.water(seed, preset), science.geology(seed, preset)
    assert science.water(seed, preset) == w and science.geology(seed, preset) == g  # deterministic
    rows = w["profile"]
    depths = [r["depth"] for r in rows]
    assert depths == sorted(depths) and depths[0] == 0.0
    assert depths[-1] == pytest.approx(P.surface_z - (P.first_level_z - (P.levels - 1) * P.level_spacing - 2.0))
    upper, lower = rows[1], rows[2]
    level0 = P.surface_z - P.first_level_z
    assert level0 < upper["depth"] < lower["depth"] < level0 + P.level_spacing
    assert upper["temperature"] > lower["temperature"]
    assert lower["conductivity"] > 4 * upper["conductivity"]
    assert lower["ph"] < 5.0 < 7.0 <= upper["ph"]
    assert upper["depth"] < w["boundary"]["depth"] < lower["depth"]
    names = [b["name"] for b in g["bodies"]]
    for body in ("sulphide_vein", "magnetite_lens", "gossan", "uranium_fractures"):
        assert body in names
    assert sum(n.startswith("calcite_vein") for n in names) == 2
    for body in [g["host"]] + [b["minerals"] for b in g["bodies"]]:
        assert sum(m["fraction"] for m in body) == pytest.approx(1.0, abs=1e-6)
    layout = mg.make_layout(P, seed)
    gallery = [t for t in layout.tunnels if t.kind == "gallery"][0]
    for b in g["bodies"]:
        x = np.array(b["xyz"])
        if b["name"].startswith("calcite"):
            assert np.hypot(*(x[:2] - np.array(layout.shaft_xy))) < 1e-3
            assert P.first_level_z < x[2] < P.surface_z
            continue
        assert 0.0 < x[0] < 160.0
        centre = mg.point_on(gallery.points, x[0])
        if b["kind"] == "vein":  # through the gallery's centreline
            assert np.linalg.norm(x - centre) < 1e-3
        elif b["kind"] == "ellipsoid":  # beside the gallery: 1 m of host rock between it and the smooth wall
            assert abs(x[1] - centre[1]) - b["radii"][1] == pytest.approx(gallery.a + 1.0, abs=1e-2)


def test_bad_science_seed_is_rejected():
    from unexmin.worlds.generator import science

    for bad in (-1, 1.5, "7"):
        with pytest.raises(ValueError, match="seed"):
            science.geology(bad)
        with pytest.raises(ValueError, match="seed"):
            science.water(bad)

"""python -m unexmin.map_quality against a synthetic map of known quality: a 4 m x 3 m x 2 m box world, a .bt
made by OctoMap's own binvox2bt from a voxel grid holding the x = 0 wall (600 voxels) and 60 voxels in
mid-room (0.75-1.05 m from the nearest wall). Expected: precision 600/660, recall = the wall's share of the box's area
(more with the strips of the neighbouring walls within tau), recall 1 over the surface seen from a point in
front of that wall, F-score 2PR/(P+R)."""

import json
import shutil
import subprocess

import numpy as np
import pytest

from unexmin import map_quality
from unexmin.worlds.files import world_path

RES = 0.1
needs_tools = pytest.mark.skipif(shutil.which("binvox2bt") is None, reason="octomap-tools missing")


def write_binvox(path, occupied, dim, origin):
    """A binvox file (voxel index order x, z, y; run-length coded) of the occupied (i, j, k) voxels."""
    grid = np.zeros((dim, dim, dim), np.uint8)
    for i, j, k in occupied:
        grid[i, k, j] = 1
    data, out, n = grid.reshape(-1), bytearray(), 0
    while n < len(data):
        run = 1
        while n + run < len(data) and data[n + run] == data[n] and run < 255:
            run += 1
        out += bytes([data[n], run])
        n += run
    header = (
        f"#binvox 1\ndim {dim} {dim} {dim}\ntranslate {origin[0]} {origin[1]} {origin[2]}\nscale {dim * RES}\ndata\n"
    )
    path.write_bytes(header.encode() + bytes(out))


@pytest.fixture(scope="module")
def case(tmp_path_factory):
    import trimesh

    tmp = tmp_path_factory.mktemp("map_quality")
    box = trimesh.creation.box(extents=(4.0, 3.0, 2.0))
    box.apply_translation((2.0, 1.5, 1.0))
    box.export(tmp / "room.stl")
    (tmp / "room.world").write_text(
        "name: room\nmeshes:\n  - {name: room, file: room.stl, collision: true, visual: false}\nrobots: []\n"
    )
    wall = [(0, j, k) for j in range(30) for k in range(20)]  # centres x = 0.05: 0.05 m from x = 0
    stray = [(20, 10 + j, 10) for j in range(60 // 6) for _ in range(1)] + [
        (20 + di, 10 + j, 10 + dk) for j in range(10) for di, dk in ((1, 0), (0, 1), (1, 1), (2, 0), (0, 2))
    ]
    assert len(set(stray)) == 60
    write_binvox(tmp / "map.binvox", wall + stray, 64, (0.0, 0.0, 0.0))
    out = subprocess.run(
        ["binvox2bt", "-o", str(tmp / "map.bt"), str(tmp / "map.binvox")], capture_output=True, text=True, timeout=60
    )
    assert out.returncode == 0, out.stdout + out.stderr
    return tmp


@needs_tools
def test_reads_the_bt_with_octomaps_tools(case):
    leaves, leaf_sizes = map_quality.read_bt(str(case / "map.bt"))
    assert len(leaves) < 660  # OctoMap pruned the wall into larger cubes
    centres, sizes = map_quality.expand(leaves, leaf_sizes)
    assert len(centres) == 660
    assert np.allclose(sizes, RES)
    assert np.sum(np.isclose(centres[:, 0], 0.05)) == 600


@needs_tools
def test_precision_recall_and_distances_match_the_construction(case):
    r = map_quality.run(str(case / "map.bt"), str(case / "room.world"), str(case / "out"))
    assert r["tau_m"] == pytest.approx(RES)
    assert r["precision"] == pytest.approx(600 / 660, abs=1e-9)
    area = 2 * (4 * 3 + 4 * 2 + 3 * 2)
    # The x = 0 wall, plus at most the strips (< tau + half a voxel wide) of the four walls next to it.
    assert 6.0 / area * 0.97 <= r["recall"] <= (6.0 + 0.15 * 2 * (3 + 2)) / area
    assert r["f_score"] == pytest.approx(2 * r["precision"] * r["recall"] / (r["precision"] + r["recall"]))
    # 600 voxels at 0.05 m, 60 at 0.75 .. 1.05 m (mid-room, nearest the ceiling): the mean lies between.
    assert (600 * 0.05 + 60 * 0.75) / 660 - 0.01 <= r["mean_distance_m"] <= (600 * 0.05 + 60 * 1.05) / 660 + 0.01
    assert r["p95_distance_m"] > 0.7  # the 9 % of stray voxels are the top 5 %
    saved = json.loads((case / "out" / "map_quality.json").read_text())
    assert saved["precision"] == r["precision"]
    assert (case / "out" / "map_quality.png").stat().st_size > 10000


@needs_tools
def test_recall_counts_only_the_surface_within_range_of_the_path(case):
    (case / "path.csv").write_text("t,x,y,z\n0,0.5,1.5,1.0\n1,0.5,1.6,1.0\n")
    r = map_quality.run(
        str(case / "map.bt"),
        str(case / "room.world"),
        str(case / "out_path"),
        trajectory=str(case / "path.csv"),
        sensor_range=0.9,
    )
    assert r["recall"] >= 0.97  # only the x = 0 wall is within 0.9 m of the path, and it is all mapped
    assert r["surface_area_m2"] == pytest.approx(np.pi * (0.9**2 - 0.5**2) + 0.1 * 1.6, rel=0.15)
    assert r["precision"] == pytest.approx(600 / 660, abs=1e-9)


def test_unknown_world_is_named():
    with pytest.raises(FileNotFoundError, match="--world nowhere"):
        world_path("nowhere")

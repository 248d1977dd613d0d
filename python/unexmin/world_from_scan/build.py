"""A surveyed point cloud of a mine (laser, sonar, the robots' own maps) to a simulator world in one
command (docs/world_from_scan.md): what the thesis did by hand for Kaatiala (5.2) with MeshLab.

    python -m unexmin.world_from_scan SCAN --out DIR [--name NAME] [--resolution 0.1] [--water-level Z]

Stages: read (PLY, PCD, XYZ/TXT, LAS/LAZ), voxel down-sampling to the resolution, normals (estimated
when the scan has none) turned to face the void, screened Poisson reconstruction (Open3D), trimming of
the surface the scan does not support, hole closing (the water volume becomes a closed surface), a
lighter visual mesh, spawn points in the water with clearance, the world file and a report.
Units: [m]; frame: the scan's own, taken as the world frame (ENU, z up).
"""

import argparse
import json
import math
import resource
import sys
import time
from pathlib import Path

import numpy as np

from unexmin.world_from_scan.colours import read_scan_colours, vertex_colours
from unexmin.world_from_scan.scan import (
    ScanError,
    check_usable,
    downsample,
    estimate_normals,
    orient_towards_void,
    orientation_cell,
    orientation_samples,
    orientation_steps,
    point_spacing,
    read_scan,
)
from unexmin.world_from_scan.surface import (
    HULL_RADIUS,
    close_holes,
    closed_surface,
    distances,
    find_spawns,
    flooded_volume,
    poisson_depth,
    raycasting_scene,
    reconstruct,
    scanned_area,
    simplify,
    trim_unsupported,
)
from unexmin.worlds.meshes import write_ply
from unexmin.worlds.schema import read_world


# ------------------------------------------------------------------------------------------ outputs
def world_yaml(name, surface_z, visibility, current_speed, collision_file, visual_file, spawns, source, coloured=False):
    lines = [
        f"# World made from the scan {source} by python -m unexmin.world_from_scan (docs/world_from_scan.md).",
        "# Schema: docs/worlds.md. Units: SI; world frame = the scan's frame (ENU, z up).",
        f"name: {name}",
        "gravity: 9.81                                 # [m/s^2]",
        f"water: {{density: 1000.0, surface_z: {surface_z:.4f}}}   # [kg/m^3]; [m] the water level",
        "atmospheric_pressure: 101325.0                # [Pa] at the free surface",
        f"visibility: {{level: {visibility}, colour: [0.32, 0.28, 0.18]}}   # suspended sediment: brownish murk",
        "ray_caster: embree",
        "current:                                      # bounded Gauss-Markov per variable",
        f"  speed: {{mean: {current_speed}, min: 0.0, max: {max(0.1, 2 * current_speed)}, noise: "
        f"{0.1 * current_speed:.4g}, mu: 0.02}}   # [m/s]",
        "  horizontal_angle: {mean: 0.0, min: -3.1416, max: 3.1416, noise: 0.0, mu: 0.01}   # [rad]",
        "  vertical_angle: {mean: 0.0, min: -0.15, max: 0.15, noise: 0.0, mu: 0.05}        # [rad]",
        "meshes:                                       # closed surface, faces towards the water",
        # the cameras see the coloured visual mesh, else the finer collision mesh (docs/worlds.md "Who sees a mesh")
        f"  - {{name: {name}, file: {collision_file}, scale: [1, 1, 1], xyz: [0, 0, 0], rpy: [0, 0, 0], "
        "collision: true, visual: false" + ("}" if coloured else ", seen_by: [cameras, sonars]}"),
        f"  - {{name: {name}_visual, file: {visual_file}, scale: [1, 1, 1], xyz: [0, 0, 0], rpy: [0, 0, 0], "
        "collision: false, visual: true" + (", material: {kind: vertex_colours}}" if coloured else ", seen_by: []}"),
        "robots:                                       # checked: in the water, clearance [m] to the walls",
    ]
    for k, (xyz, room) in enumerate(spawns):
        lines.append(
            f"  - {{name: UX_{k + 1}, description: ux1.urdf.xacro, xyz: [{xyz[0]:.3f}, {xyz[1]:.3f}, "
            f"{xyz[2]:.3f}], rpy: [0, 0, 0]}}   # clearance {room:.2f} m"
        )
    return "\n".join(lines) + "\n"


def build_world(
    scan,
    out,
    name=None,
    resolution=0.1,
    water_level=None,
    max_gap=1.0,
    clearance=0.6,
    edge=0.3,
    visual_edge=1.0,
    visibility="medium",
    current_speed=0.0,
    seed=0,
    quiet=False,
):
    """The whole pipeline; returns the report (dict), also written as <out>/<name>.json."""
    from tqdm import tqdm

    if not resolution > 0:
        raise ScanError(f"--resolution must be > 0 [m], got {resolution}")
    if not (edge > 0 and visual_edge > 0):
        raise ScanError(f"--edge and --visual-edge must be > 0 [m], got {edge} and {visual_edge}")
    if not max_gap > resolution:
        raise ScanError(f"--max-gap must exceed the resolution {resolution} m, got {max_gap}")
    if visibility not in ("none", "low", "medium", "high"):
        raise ScanError(f"--visibility must be none, low, medium or high, got {visibility!r}")
    scan = Path(scan)
    name = name or scan.stem
    out = Path(out)
    times = {}
    t_all = time.monotonic()

    def stage(label, total=1, unit="step"):
        return tqdm(total=total, desc=f"{label:<12}", unit=unit, disable=quiet, file=sys.stderr, leave=True)

    def timed(key, label, fn, *args, total=1, unit="step", **kw):
        t0 = time.monotonic()
        with stage(label, total, unit) as bar:
            result = fn(*args, **kw, **({"progress": bar} if total > 1 else {}))
            bar.update(bar.total - bar.n)
        times[key] = round(time.monotonic() - t0, 2)
        return result

    raw, raw_normals = timed("read", "read", read_scan, scan)
    points, normals = timed("downsample", "downsample", downsample, raw, raw_normals, resolution)
    check_usable(points, resolution, scan)
    if normals is None:
        normals = timed("normals", "normals", estimate_normals, points, resolution)
    extent = points.max(axis=0) - points.min(axis=0)
    steps = 2 * len(orientation_steps(extent, orientation_cell(extent, resolution)))
    spacing = point_spacing(points, seed)
    normals, decided = timed(
        "orient",
        "orient",
        orient_towards_void,
        points,
        normals,
        resolution,
        seed=seed,
        samples=orientation_samples(len(points), spacing),
        total=steps,
        unit="ray step",
    )
    if spacing > resolution and not quiet:
        print(
            f"world_from_scan: note: the scan's points are {spacing:.3g} m apart, sparser than --resolution "
            f"{resolution} m: the surface is reconstructed at {spacing:.3g} m",
            file=sys.stderr,
        )
    depth = poisson_depth(points, max(resolution, spacing))
    v, t = timed("poisson", "poisson", reconstruct, points, normals, depth)
    v, t = timed("trim", "trim", trim_unsupported, v, t, points, max_gap)
    if len(t) == 0:
        raise ScanError(
            f"{scan}: no usable surface: nothing of the reconstruction lies within --max-gap "
            f"{max_gap} m of the scan"
        )
    v, t, holes, hole_area, cap = timed("holes", "close holes", close_holes, v, t)
    import trimesh

    mesh = trimesh.Trimesh(v, t, process=False)
    wall_area, bridged_area = scanned_area(mesh, cap, points, 3.0 * resolution)
    fine_triangles = len(t)
    closed = closed_surface(v, t)
    signed = float(mesh.volume) if closed else float("nan")
    if closed and signed > 0:  # faces must point into the void: the enclosed volume is then negative
        t, signed = t[:, ::-1].copy(), -signed
    cv, ct = timed("decimate", "decimate", simplify, v, t, edge)
    if closed and not closed_surface(cv, ct):  # the decimation opened the surface: keep the fine one
        cv, ct = v, t
    v, t = cv, ct
    volume = -float(trimesh.Trimesh(v, t, process=False).volume) if closed else float("nan")
    if closed and volume < (4 / 3) * math.pi * (HULL_RADIUS + clearance) ** 3:
        raise ScanError(
            f"{scan}: no usable surface: the closed surface holds {volume:.3g} m^3 of water, not "
            f"room for one robot (expected walls around a void)"
        )
    surface_z = float(points[:, 2].max()) if water_level is None else float(water_level)
    scene = raycasting_scene(v, t)
    t0 = time.monotonic()
    with stage("spawns") as bar:
        spawns = find_spawns(scene, points, normals, surface_z, clearance, seed=seed)
        bar.update(1)
    times["spawns"] = round(time.monotonic() - t0, 2)
    if not spawns:
        raise ScanError(
            f"{scan}: no point of the water (below z = {surface_z:.2f} m) has {clearance} m of "
            "clearance to the walls: no room for a robot"
        )
    vv, vt = timed("visual", "visual mesh", simplify, v, t, visual_edge)
    coloured = read_scan_colours(scan)  # the scan's RGB onto the visual mesh's vertices (colours.py)
    visual_colours = vertex_colours(vv, *coloured) if coloured is not None else None
    t0 = time.monotonic()
    with stage("evaluate") as bar:
        rng = np.random.default_rng(seed)
        probe = raw if len(raw) <= 1_000_000 else raw[rng.choice(len(raw), 1_000_000, replace=False)]
        d = distances(scene, probe)
        flooded = flooded_volume(v, t, surface_z) if closed else None
        bar.update(1)
    times["evaluate"] = round(time.monotonic() - t0, 2)
    out.mkdir(parents=True, exist_ok=True)
    collision_file, visual_file = f"{name}_collision.ply", f"{name}_visual.ply"
    comment = f"unexmin world_from_scan {scan.name} resolution {resolution}"
    write_ply(out / collision_file, v, t, comment + " collision", inward=False)
    write_ply(out / visual_file, vv, vt, comment + " visual", inward=False, colours=visual_colours)
    world_path = out / f"{name}.world"
    world_path.write_text(
        world_yaml(
            name,
            surface_z,
            visibility,
            current_speed,
            collision_file,
            visual_file,
            spawns,
            scan.name,
            coloured=visual_colours is not None,
        )
    )
    read_world(world_path)  # what the simulator will read follows the schema
    rep = {
        "scan": str(scan),
        "points_read": int(len(raw)),
        "points_used": int(len(points)),
        "normals": "read" if raw_normals is not None else "estimated",
        "orientation_samples_decided": round(decided, 3),
        "resolution": resolution,
        "point_spacing": round(spacing, 4),
        "poisson_depth": depth,
        "max_gap": max_gap,
        "poisson_triangles": int(fine_triangles),
        "collision": {"file": collision_file, "triangles": int(len(t)), "vertices": int(len(v)), "edge": edge},
        "visual": {
            "file": visual_file,
            "triangles": int(len(vt)),
            "vertices": int(len(vv)),
            "edge": visual_edge,
            "colours": visual_colours is not None,
        },
        "world": world_path.name,
        "closed": closed,
        "volume": round(volume, 3) if closed else None,
        "flooded_volume": round(flooded, 3) if flooded is not None else None,
        "water_level": surface_z,
        "wall_area": round(wall_area, 3),
        "bridged_area": round(bridged_area, 3),
        "holes_closed": holes,
        "holes_area": round(hole_area, 3),
        "scan_to_mesh": {
            "mean": round(float(d.mean()), 4),
            "p95": round(float(np.percentile(d, 95)), 4),
            "max": round(float(d.max()), 4),
            "points": int(len(d)),
        },
        "bbox_min": [round(x, 3) for x in v.min(axis=0)],
        "bbox_max": [round(x, 3) for x in v.max(axis=0)],
        "spawns": [{"xyz": [round(float(x), 3) for x in s], "clearance": round(c, 3)} for s, c in spawns],
        "seconds": times,
        "total_seconds": round(time.monotonic() - t_all, 2),
        "peak_rss_mb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1),
    }
    (out / f"{name}.json").write_text(json.dumps(rep, indent=1) + "\n")
    return rep


def report(rep):
    s = rep["scan_to_mesh"]
    vol = f"{rep['volume']:,.1f}" if rep["volume"] is not None else "n/a (not closed)"
    flooded = f"{rep['flooded_volume']:,.1f}" if rep["flooded_volume"] is not None else "n/a"
    return "\n".join(
        [
            f"world '{rep['world']}' from {rep['scan']}: {rep['points_read']:,} points read, {rep['points_used']:,} at "
            f"{rep['resolution']} m, normals {rep['normals']}, Poisson depth {rep['poisson_depth']}, "
            f"{rep['total_seconds']} s, peak {rep['peak_rss_mb']:.0f} MB",
            f"  collision: {rep['collision']['triangles']:,} triangles "
            f"(edge {rep['collision']['edge']} m, from Poisson's "
            f"{rep['poisson_triangles']:,}), {rep['collision']['file']}",
            f"  visual:    {rep['visual']['triangles']:,} triangles, {rep['visual']['file']}",
            f"  closed: {rep['closed']}, void volume {vol} m^3, flooded (below z = {rep['water_level']:.2f}) "
            f"{flooded} m^3, "
            f"wall area {rep['wall_area']:,.1f} m^2 (and {rep['bridged_area']:,.1f} m^2 bridged over gaps)",
            f"  holes closed: {rep['holes_closed']} ({rep['holes_area']:,.1f} m^2)",
            f"  scan to mesh: mean {s['mean'] * 100:.1f} cm, 95th percentile {s['p95'] * 100:.1f} cm, "
            f"max {s['max']:.2f} m",
            "  spawns: " + ", ".join(f"{sp['xyz']} (clearance {sp['clearance']:.2f} m)" for sp in rep["spawns"]),
        ]
    )


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m unexmin.world_from_scan", description=__doc__.split("\n\n")[0])
    ap.add_argument("scan", help="point cloud: .ply .pcd .xyz .xyzn .pts .txt .csv .las .laz [m]")
    ap.add_argument("--out", required=True, help="output folder (created)")
    ap.add_argument("--name", help="world and file name prefix (default: the scan's file name)")
    ap.add_argument("--resolution", type=float, default=0.1, help="[m] voxel size and Poisson cell (default 0.1)")
    ap.add_argument("--water-level", type=float, help="[m] z of the water surface (default: the scan's top)")
    ap.add_argument(
        "--max-gap",
        type=float,
        default=1.0,
        help="[m] surface farther than this from every scan point is trimmed (default 1.0)",
    )
    ap.add_argument(
        "--clearance",
        type=float,
        default=0.6,
        help="[m] least distance from a spawn point to the walls (default 0.6: hull 0.3 + 0.3)",
    )
    ap.add_argument("--visibility", default="medium", help="none|low|medium|high (default medium)")
    ap.add_argument("--current-speed", type=float, default=0.0, help="[m/s] mean water current (default 0)")
    ap.add_argument(
        "--edge",
        type=float,
        default=0.3,
        help="[m] triangle edge of the collision mesh, decimated from Poisson's (default 0.3)",
    )
    ap.add_argument("--visual-edge", type=float, default=1.0, help="[m] triangle edge of the visual mesh (default 1.0)")
    ap.add_argument("--seed", type=int, default=0, help="seed of the samplings (default 0)")
    ap.add_argument("--quiet", action="store_true", help="no progress bars")
    args = ap.parse_args(argv)
    try:
        rep = build_world(
            args.scan,
            args.out,
            args.name,
            args.resolution,
            args.water_level,
            args.max_gap,
            args.clearance,
            args.edge,
            args.visual_edge,
            args.visibility,
            args.current_speed,
            args.seed,
            args.quiet,
        )
    except ScanError as e:
        print(f"world_from_scan: error: {e}", file=sys.stderr)
        return 2
    print(report(rep))
    return 0

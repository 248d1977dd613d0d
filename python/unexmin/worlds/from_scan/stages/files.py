"""Stages write_meshes and write_worlds: the whole meshes and the parts by tile as binary PLY, then two world files
(the whole meshes; the parts), each checked against the world schema."""

import numpy as np

from unexmin.worlds.from_scan.colours import streamed_vertex_colours
from unexmin.worlds.meshes import write_ply
from unexmin.worlds.schema import read_world


def world_yaml(name, surface_z, visibility, current_speed, meshes, spawns, source):
    """The world file's text; `meshes`: (entry name, file, collision, visual, extra keys) per mesh."""
    lines = [
        f"# World made from the scan {source} by python -m unexmin.worlds.from_scan (docs/world_from_scan.md).",
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
        "meshes:                                       # together a closed surface, faces towards the water",
    ]
    for entry, file, collision, visual, extra in meshes:
        lines.append(
            f"  - {{name: {entry}, file: {file}, scale: [1, 1, 1], xyz: [0, 0, 0], rpy: [0, 0, 0], "
            f"collision: {str(collision).lower()}, visual: {str(visual).lower()}{extra}}}"
        )
    lines.append("robots:                                       # checked: in the water, clearance [m] to the walls")
    for k, (xyz, room) in enumerate(spawns):
        lines.append(
            f"  - {{name: UX_{k + 1}, description: ux1.urdf.xacro, xyz: [{xyz[0]:.3f}, {xyz[1]:.3f}, "
            f"{xyz[2]:.3f}], rpy: [0, 0, 0]}}   # clearance {room:.2f} m"
        )
    return "\n".join(lines) + "\n"


def split_parts(v, t, axis, seams):
    """The surface's triangles by tile (the slab holding each centroid): a list of (v, t) compacted."""
    k = np.searchsorted(np.asarray(seams, dtype=float), v[t].mean(axis=1)[:, axis], side="right")
    parts = []
    for i in range(len(seams) + 1):
        tk = t[k == i]
        used = np.unique(tk)
        remap = np.full(len(v), -1, dtype=np.int64)
        remap[used] = np.arange(len(used))
        parts.append((v[used], remap[tk]))
    return parts


def write_meshes(b):
    """Writes OUT/NAME_collision.ply, OUT/NAME_visual.ply (with the scan's colours, read again in chunks, when it
    has them) and the parts by tile OUT/NAME_{collision,visual}_KKK.ply; fills b.collision_file, b.visual_file,
    b.visual_colours and b.parts."""
    (v, t), (vv, vt), axis = b.collision, b.visual, b.layout["axis"]
    b.out.mkdir(parents=True, exist_ok=True)
    b.collision_file, b.visual_file = f"{b.name}_collision.ply", f"{b.name}_visual.ply"
    comment = f"unexmin world_from_scan {b.scan.name} resolution {b.options.resolution}"
    write_ply(b.out / b.collision_file, v, t, comment + " collision", inward=False)
    b.visual_colours = streamed_vertex_colours(b.scan, vv) if b.layout["rgb"] else None
    write_ply(b.out / b.visual_file, vv, vt, comment + " visual", inward=False, colours=b.visual_colours)
    whole_visual = None  # a part's vertices are the whole visual mesh's: their colours are found in it
    if b.visual_colours is not None:
        from scipy.spatial import cKDTree

        whole_visual = cKDTree(vv)
    b.parts = []
    for k, ((pv, pt), (qv, qt)) in enumerate(zip(split_parts(v, t, axis, b.seams), split_parts(vv, vt, axis, b.seams))):
        files = (f"{b.name}_collision_{k:03d}.ply", f"{b.name}_visual_{k:03d}.ply")
        write_ply(b.out / files[0], pv, pt, f"{comment} collision tile {k}", inward=False)
        part_colours = None if whole_visual is None else b.visual_colours[whole_visual.query(qv, k=1)[1]]
        write_ply(b.out / files[1], qv, qt, f"{comment} visual tile {k}", inward=False, colours=part_colours)
        b.parts.append({"index": k, "collision": files[0], "visual": files[1], "triangles": int(len(pt))})
    return b


def write_worlds(b):
    """Writes OUT/NAME.world (the whole meshes) and OUT/NAME_parts.world (the parts), each read back through the
    world schema; fills b.world_path and b.parts_path."""
    name, o = b.name, b.options
    b.world_path, b.parts_path = b.out / f"{name}.world", b.out / f"{name}_parts.world"
    # the cameras see the coloured visual mesh, else the finer collision mesh (docs/worlds.md "Who sees a mesh")
    if b.visual_colours is not None:
        seen, look = "", ", material: {kind: vertex_colours}"
    else:
        seen, look = ", seen_by: [cameras, sonars]", ", seen_by: []"
    whole = [(name, b.collision_file, True, False, seen), (f"{name}_visual", b.visual_file, False, True, look)]
    by_part = [(f"{name}_{p['index']:03d}", p["collision"], True, False, seen) for p in b.parts]
    by_part += [(f"{name}_visual_{p['index']:03d}", p["visual"], False, True, look) for p in b.parts]
    for path, meshes in ((b.world_path, whole), (b.parts_path, by_part)):
        path.write_text(world_yaml(name, b.surface_z, o.visibility, o.current_speed, meshes, b.spawns, b.scan.name))
        read_world(path)  # what the simulator will read follows the schema
    return b

"""World files (docs/worlds.md): the shipped worlds by name, reading a world file's mesh entries with the
simulator's path rule, linking a world's meshes beside a copy of it, and its collision triangles.
Needs only numpy and PyYAML (no ROS)."""

import os
from pathlib import Path

import numpy as np

from unexmin.geometry import rpy_matrix
from unexmin.worlds.meshes import read_mesh
from unexmin.worlds.schema import read_world

#: The package's root folder (worlds/, urdf/, launch/ live there).
PACKAGE_DIR = Path(__file__).resolve().parents[3]


def world_path(world, base=""):
    """The world file of a shipped world's name (`mine`, `tank`, `test_box`: the package's worlds/<name>.world)
    or of a path (relative to `base`); FileNotFoundError naming `world` when it is neither."""
    shipped = PACKAGE_DIR / "worlds" / f"{world}.world"
    if shipped.is_file():
        return str(shipped)
    path = os.path.join(base, world)
    if not os.path.exists(path):
        names = sorted(p.stem for p in (PACKAGE_DIR / "worlds").glob("*.world"))
        raise FileNotFoundError(
            f"--world {world}: neither a shipped world ({', '.join(names)}) nor an existing world file"
        )
    return path


def inside_path(world, base, file, key):
    """`file` (key `key` of world file `world`, whose folder is `base`) resolved against `base`: a relative path
    that stays inside that folder once normalised, as the simulator requires (docs/worlds.md, "Paths");
    ValueError naming the file, the key and the path otherwise."""
    file = str(file)
    if os.path.isabs(file):
        raise ValueError(
            f"{world}: '{key}' {file} is an absolute path: expected a path relative to the world "
            f"file's folder {base} and inside it"
        )
    norm = os.path.normpath(file)
    if norm == "." or norm == ".." or norm.startswith("../"):
        raise ValueError(
            f"{world}: '{key}' {file} is not inside the world file's folder {base}: expected a "
            f"relative path to a file in it or below it (no '..' out of it)"
        )
    return os.path.join(base, norm)


def link_meshes(meshes, source_base, target_dir):
    """Make the mesh entries of a world file in folder `source_base` usable by a copy of it written to
    `target_dir`: a world file reads only files in its own folder (docs/worlds.md, "Paths"), so each mesh gets a
    symbolic link `target_dir/meshes/<i>_<name>` to the real file and its `file` becomes that relative path.
    Changes the entries in place."""
    folder = os.path.join(target_dir, "meshes")
    os.makedirs(folder, exist_ok=True)
    for i, m in enumerate(meshes):
        source = os.path.realpath(os.path.join(source_base, m["file"]))
        rel = os.path.join("meshes", f"{i}_{os.path.basename(source)}")
        link = os.path.join(target_dir, rel)
        if os.path.lexists(link):
            os.remove(link)
        os.symlink(source, link)
        m["file"] = rel


def load_world(path):
    """The world file's name, surface height [m] and mesh entries (absolute file, scale, xyz, rpy, flags); the file
    checked against the world-file schema first (unexmin.worlds.schema: WorldFileError, a ValueError)."""
    world = read_world(path)
    base = os.path.dirname(os.path.abspath(path))
    meshes = []
    for i, m in enumerate(world.get("meshes") or []):
        if "file" not in m:
            raise ValueError(f"{path}: meshes[{i}] has no 'file'")
        entry = {
            "name": m.get("name", f"mesh{i}"),
            "file": inside_path(path, base, m["file"], f"meshes[{i}].file"),
            "scale": [float(v) for v in m.get("scale", [1, 1, 1])],
            "xyz": [float(v) for v in m.get("xyz", [0, 0, 0])],
            "rpy": [float(v) for v in m.get("rpy", [0, 0, 0])],
            "collision": bool(m.get("collision", True)),
            "visual": bool(m.get("visual", True)),
        }
        if len(entry["scale"]) != 3 or len(entry["xyz"]) != 3 or len(entry["rpy"]) != 3:
            raise ValueError(f"{path}: meshes[{i}] scale, xyz and rpy need 3 numbers each")
        meshes.append(entry)
    surface = float((world.get("water") or {}).get("surface_z", 0.0))
    return {"name": world.get("name", "world"), "surface_z": surface, "meshes": meshes}


def placed_mesh(entry):
    """(vertices N x 3 [m, world frame], triangles M x 3) of a mesh entry of load_world: read, scaled, rotated
    and moved to its pose."""
    v, t = read_mesh(entry["file"])
    return (v * np.array(entry["scale"])) @ rpy_matrix(entry["rpy"]).T + np.array(entry["xyz"]), t


def world_triangles(path):
    """T x 3 x 3 [m, world frame] of the world's collision meshes."""
    tris = []
    for entry in load_world(path)["meshes"]:
        if not entry["collision"]:
            continue
        v, t = placed_mesh(entry)
        tris.append(v[t])
    if not tris:
        raise ValueError(f"{path}: no collision mesh")
    return np.concatenate(tris)

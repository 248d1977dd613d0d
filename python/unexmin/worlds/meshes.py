"""Triangle meshes: reading binary STL and PLY, writing binary PLY, sampling a surface by area. numpy only."""

import numpy as np


class MeshFormatError(ValueError):
    """A mesh file this module cannot read (only binary STL and binary little-endian PLY)."""


def read_mesh(path):
    """(vertices N x 3 float64, triangles M x 3 int64) of a binary STL or binary little-endian PLY
    (float x y z vertices, then optionally uchar red green blue, skipped; triangle faces). STL vertices are merged by
    exact position."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] == b"ply\n":
        end = data.index(b"end_header\n") + len(b"end_header\n")
        header = data[:end].decode("ascii").split("\n")
        if "format binary_little_endian 1.0" not in header:
            raise MeshFormatError(f"{path}: only binary little-endian PLY is read here")
        n_v = n_f = None
        props = []
        for line in header:
            words = line.split()
            if words[:2] == ["element", "vertex"]:
                n_v = int(words[2])
            elif words[:2] == ["element", "face"]:
                n_f = int(words[2])
            elif words[:1] == ["property"] and n_f is None:
                props.append(words[1:])
        colour = [["uchar", c] for c in ("red", "green", "blue")]
        if props[:3] != [["float", "x"], ["float", "y"], ["float", "z"]] or props[3:] not in ([], colour):
            raise MeshFormatError(f"{path}: PLY vertices must be float x, y, z (then uchar red, green, blue)")
        if n_v is None or n_f is None:
            raise MeshFormatError(f"{path}: PLY needs a vertex and a face element")
        vertex = np.dtype([("p", "<f4", (3,))] + ([("c", "u1", (3,))] if props[3:] else []))
        v = np.frombuffer(data, vertex, n_v, end)["p"].astype(np.float64)
        faces = np.frombuffer(data, [("n", "u1"), ("i", "<i4", (3,))], n_f, end + vertex.itemsize * n_v)
        if n_f and (faces["n"] != 3).any():
            raise MeshFormatError(f"{path}: PLY faces must be triangles")
        return v, faces["i"].astype(np.int64)
    if len(data) < 84 or len(data) != 84 + 50 * int(np.frombuffer(data, "<u4", 1, 80)[0]):
        raise MeshFormatError(f"{path}: not a binary STL nor a binary PLY")
    n = int(np.frombuffer(data, "<u4", 1, 80)[0])
    rec = np.frombuffer(data, [("n", "<f4", (3,)), ("v", "<f4", (3, 3)), ("a", "<u2")], n, 84)
    v, inverse = np.unique(rec["v"].reshape(-1, 3), axis=0, return_inverse=True)
    return v.astype(np.float64), inverse.reshape(-1, 3).astype(np.int64)


def write_ply(path, verts, tris, comment, inward=True, colours=None):
    """Binary little-endian PLY (float x y z, int triangles): compact, and loaded by assimp ten times
    faster than STL. `inward` reverses the winding so the faces point into the void (the water). `colours`
    (N x 3 uint8, sRGB): vertex colours as uchar red, green, blue."""
    if inward:
        tris = tris[:, ::-1]
    vertex = np.zeros(len(verts), dtype=[("p", "<f4", (3,))] + ([("c", "u1", (3,))] if colours is not None else []))
    vertex["p"] = verts
    if colours is not None:
        vertex["c"] = colours
    faces = np.zeros(len(tris), dtype=[("n", "u1"), ("i", "<i4", (3,))])
    faces["n"], faces["i"] = 3, tris
    header = (
        f"ply\nformat binary_little_endian 1.0\ncomment {comment}\nelement vertex {len(verts)}\n"
        "property float x\nproperty float y\nproperty float z\n"
        + ("property uchar red\nproperty uchar green\nproperty uchar blue\n" if colours is not None else "")
        + f"element face {len(tris)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(vertex.tobytes())
        f.write(faces.tobytes())


def sample_surface(tris, spacing, seed=0):
    """Area-uniform samples of the triangles, one per spacing^2 on average (seeded): N x 3 [m]."""
    rng = np.random.default_rng(seed)
    a, b, c = tris[:, 0], tris[:, 1], tris[:, 2]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    expected = area / spacing**2
    counts = np.floor(expected + rng.random(len(tris))).astype(np.int64)
    idx = np.repeat(np.arange(len(tris)), counts)
    u, v = rng.random(len(idx)), rng.random(len(idx))
    flip = u + v > 1.0
    u[flip], v[flip] = 1.0 - u[flip], 1.0 - v[flip]
    return a[idx] + u[:, None] * (b[idx] - a[idx]) + v[:, None] * (c[idx] - a[idx]), float(area.sum())

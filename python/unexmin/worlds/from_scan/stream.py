"""Point clouds read in chunks, never whole (docs/world_from_scan.md#reading): PLY (ascii, binary), PCD
(ascii, binary), XYZ/XYZN/PTS/TXT/CSV/ASC (columns), LAS/LAZ (laspy's chunk iterator, lazrs back end).

Each reader yields Chunk(points N x 3 [m] float64, normals N x 3 or None, rgb N x 3 uint8 or None, done):
`done` is how far through the file the reader is, in the unit of `scan_size(path)` (points, or bytes for
text), for a progress bar with the time left. Non-finite rows are passed on: the caller counts and drops them.
"""

import os
from collections import namedtuple
from pathlib import Path

import numpy as np

from unexmin.worlds.from_scan.errors import ScanError

CHUNK = 1_000_000  # points per chunk: about 60 MB with normals and colours

EXTENSIONS = ".ply .pcd .xyz .xyzn .xyzrgb .pts .txt .csv .asc .las .laz"

Chunk = namedtuple("Chunk", "points normals rgb done")


def _check_file(path):
    path = Path(path)
    if not path.is_file():
        raise ScanError(f"{path}: no such file (expected a point cloud: {EXTENSIONS})")
    ext = path.suffix.lower()
    if ext not in EXTENSIONS.split():
        raise ScanError(f"{path}: unknown point cloud extension '{ext}' (expected {EXTENSIONS})")
    return path, ext


def scan_size(path):
    """(total, unit) of the progress through `path`: its points when the header says, else its bytes."""
    path, ext = _check_file(path)
    if ext in (".las", ".laz"):
        import laspy

        with laspy.open(str(path)) as f:
            return int(f.header.point_count), "point"
    if ext == ".ply":
        return _ply_header(path)["count"], "point"
    if ext == ".pcd":
        return _pcd_header(path)["count"], "point"
    return os.path.getsize(path), "B"


def iter_chunks(path, chunk=CHUNK):
    """Chunks of the cloud in `path` (see the module's doc); a clear ScanError on a file it cannot read."""
    path, ext = _check_file(path)
    if ext in (".las", ".laz"):
        yield from _las_chunks(path, chunk)
    elif ext == ".ply":
        yield from _ply_chunks(path, chunk)
    elif ext == ".pcd":
        yield from _pcd_chunks(path, chunk)
    else:
        yield from _text_chunks(path, ext, chunk)


# ----------------------------------------------------------------------------------------- columns
def _normals(table, names):
    if all(n in names for n in ("nx", "ny", "nz")):
        return np.column_stack([table[n] for n in ("nx", "ny", "nz")]).astype(np.float64)
    return None


def _rgb(table, names, divisor=None):
    """Colours as uint8 RGB: 8-bit values as they are, 16-bit ones (LAS, PLY ushort) divided by 256."""
    for keys in (("red", "green", "blue"), ("r", "g", "b"), ("diffuse_red", "diffuse_green", "diffuse_blue")):
        if all(k in names for k in keys):
            c = np.column_stack([np.asarray(table[k], dtype=np.float64) for k in keys])
            if divisor is None:  # by the column's type
                divisor = 256.0 if np.asarray(table[keys[0]]).dtype.itemsize == 2 else 1.0
            return np.clip(np.nan_to_num(c / divisor), 0, 255).astype(np.uint8)
    return None


def _chunk(table, names, done, divisor=None):
    points = np.column_stack([np.asarray(table[n], dtype=np.float64) for n in ("x", "y", "z")])
    return Chunk(points, _normals(table, names), _rgb(table, names, divisor), done)


# -------------------------------------------------------------------------------------------- LAS
def _las_chunks(path, chunk):
    import laspy

    try:
        f = laspy.open(str(path))
    except Exception as e:  # laspy's own errors name no file
        raise ScanError(f"{path}: not a readable LAS/LAZ file ({e})") from None
    with f:
        names = set(f.header.point_format.dimension_names)
        done, divisor = 0, None

        for pts in f.chunk_iterator(chunk):
            done += len(pts)
            table = {"x": pts.x, "y": pts.y, "z": pts.z}
            if {"red", "green", "blue"} <= names:
                table.update(red=pts.red, green=pts.green, blue=pts.blue)
                if divisor is None and len(pts):  # LAS colours are 16-bit; some writers put 8-bit values in them
                    top = max(int(np.max(pts.red)), int(np.max(pts.green)), int(np.max(pts.blue)))
                    divisor = 256.0 if top > 255 else 1.0
            yield _chunk(table, set(table), done, divisor)


# -------------------------------------------------------------------------------------------- PLY
_PLY_TYPES = {
    "char": "i1",
    "int8": "i1",
    "uchar": "u1",
    "uint8": "u1",
    "short": "i2",
    "int16": "i2",
    "ushort": "u2",
    "uint16": "u2",
    "int": "i4",
    "int32": "i4",
    "uint": "u4",
    "uint32": "u4",
    "float": "f4",
    "float32": "f4",
    "double": "f8",
    "float64": "f8",
}


def _ply_header(path):
    """The vertex element of a PLY file: format, count, property names and dtypes, data offset, and
    how many (ascii) lines come before its rows."""
    with open(path, "rb") as f:
        if f.readline().strip() != b"ply":
            raise ScanError(f"{path}: not a PLY file (expected the line 'ply' first)")
        fmt, count, props, element, before, lines = None, None, [], None, 0, 0
        while True:
            line = f.readline()
            if not line:
                raise ScanError(f"{path}: PLY header without end_header")
            lines += 1
            words = line.decode("ascii", "replace").split()
            if not words:
                continue
            if words[0] == "format":
                fmt = words[1]
            elif words[0] == "element":
                element = words[1]
                if element == "vertex":
                    count = int(words[2])
                elif count is None:
                    before += int(words[2])  # an element before the vertices: its rows come first
            elif words[0] == "property" and element == "vertex":
                if words[1] == "list":
                    raise ScanError(f"{path}: PLY vertex property lists are not supported (expected x y z ...)")
                if words[1] not in _PLY_TYPES:
                    raise ScanError(f"{path}: unknown PLY property type '{words[1]}'")
                props.append((words[2], _PLY_TYPES[words[1]]))
            elif words[0] == "end_header":
                break
        offset = f.tell()
    names = [p[0] for p in props]
    if count is None or not {"x", "y", "z"} <= set(names):
        raise ScanError(f"{path}: PLY without a vertex element of x y z (expected a point cloud)")
    if before and fmt != "ascii":
        raise ScanError(f"{path}: binary PLY with an element before the vertices (expected the vertices first)")
    return {"format": fmt, "count": count, "props": props, "offset": offset, "skip": lines + 1 + before}


def _ply_chunks(path, chunk):
    h = _ply_header(path)
    names = set(p[0] for p in h["props"])
    if h["format"] == "ascii":
        yield from _table_chunks(path, [p[0] for p in h["props"]], r"\s+", h["skip"], h["count"], chunk, h["count"])
        return
    order = {"binary_little_endian": "<", "binary_big_endian": ">"}.get(h["format"])
    if order is None:
        raise ScanError(f"{path}: unknown PLY format '{h['format']}'")
    dtype = np.dtype([(n, order + t) for n, t in h["props"]])
    yield from _memmap_chunks(path, dtype, h["offset"], h["count"], names, chunk)


def _memmap_chunks(path, dtype, offset, count, names, chunk, colours=None):
    if os.path.getsize(path) < offset + count * dtype.itemsize:
        raise ScanError(f"{path}: the file is shorter than the {count} points its header announces (truncated?)")
    rows = np.memmap(path, dtype=dtype, mode="r", offset=offset, shape=(count,))
    for i in range(0, count, chunk):
        part = np.array(rows[i : i + chunk])  # a copy: the map's pages are released as it goes
        c = _chunk(part, names, min(i + chunk, count))
        yield c if colours is None else c._replace(rgb=colours(part, names))
    del rows


# -------------------------------------------------------------------------------------------- PCD
def _pcd_header(path):
    with open(path, "rb") as f:
        h = {}
        while True:
            line = f.readline()
            if not line:
                raise ScanError(f"{path}: PCD header without a DATA line")
            words = line.decode("ascii", "replace").split()
            if not words or words[0].startswith("#"):
                continue
            h[words[0].upper()] = words[1:]
            if words[0].upper() == "DATA":
                break
        offset = f.tell()
    try:
        fields, sizes, types = h["FIELDS"], [int(s) for s in h["SIZE"]], h["TYPE"]
        counts = [int(c) for c in h.get("COUNT", ["1"] * len(fields))]
        count = int(h["POINTS"][0]) if "POINTS" in h else int(h["WIDTH"][0]) * int(h["HEIGHT"][0])
    except (KeyError, ValueError, IndexError) as e:
        raise ScanError(f"{path}: PCD header without FIELDS, SIZE, TYPE or POINTS ({e})") from None
    if not {"x", "y", "z"} <= set(fields):
        raise ScanError(f"{path}: PCD without fields x y z (got {' '.join(fields)})")
    return {
        "fields": fields,
        "sizes": sizes,
        "types": types,
        "counts": counts,
        "count": count,
        "data": h["DATA"][0].lower(),
        "offset": offset,
    }


def _pcd_rgb(part, names):
    """PCL packs r, g, b into the bytes of one float field 'rgb' (or 'rgba')."""
    key = "rgb" if "rgb" in names else "rgba" if "rgba" in names else None
    if key is None:
        return None
    packed = np.ascontiguousarray(np.asarray(part[key], dtype=np.float32)).view(np.uint32)
    return np.column_stack([(packed >> 16) & 255, (packed >> 8) & 255, packed & 255]).astype(np.uint8)


def _pcd_chunks(path, chunk):
    h = _pcd_header(path)
    names = set(h["fields"])
    if h["data"] == "ascii":
        cols = []
        for name, c in zip(h["fields"], h["counts"]):
            cols += [name] if c == 1 else [f"{name}_{k}" for k in range(c)]
        yield from _table_chunks(path, cols, r"\s+", None, h["count"], chunk, h["count"], h["offset"], _pcd_rgb)
        return
    if h["data"] != "binary":
        raise ScanError(
            f"{path}: PCD DATA {h['data']} cannot be read in chunks (expected ascii or binary: convert it, "
            "e.g. pcl_convert_pcd_ascii_binary in.pcd out.pcd 1)"
        )
    fields = []
    for name, size, typ, c in zip(h["fields"], h["sizes"], h["types"], h["counts"]):
        kind = {"F": "f", "I": "i", "U": "u"}[typ.upper()]
        fields.append((name, f"<{kind}{size}") if c == 1 else (name, f"<{kind}{size}", (c,)))
    dtype = np.dtype(fields)
    yield from _memmap_chunks(path, dtype, h["offset"], h["count"], names, chunk, colours=_pcd_rgb)


def _table_chunks(path, names, sep, skip, count, chunk, total, start=None, colours=None):
    """Rows of numbers with the columns `names`, `chunk` rows at a time (pandas' C reader). `done` counts
    rows when `total` is the row count, else bytes of the file."""
    import pandas as pd

    with open(path, "rb") as f:
        if start is not None:
            f.seek(start)
        try:
            reader = pd.read_csv(
                f,
                sep=sep,
                header=None,
                names=names,
                usecols=range(len(names)),
                skiprows=skip,
                nrows=count,
                chunksize=chunk,
                comment="#",
                dtype=np.float64,
                engine="c",
            )
            done = 0
            for part in reader:
                done = done + len(part) if count is not None else f.tell()
                table = {n: part[n].to_numpy() for n in names}
                c = _chunk(table, set(names), done)
                yield c if colours is None else c._replace(rgb=colours(table, set(names)))
        except (ValueError, pd.errors.ParserError) as e:
            raise ScanError(f"{path}: expected rows of numbers ({' '.join(names)}) ({e})") from None


# ------------------------------------------------------------------------------------------- text
_COLUMNS = {  # columns per row -> their names (x y z first; extra columns ignored)
    3: ["x", "y", "z"],
    4: ["x", "y", "z", "i"],
    6: ["x", "y", "z", "nx", "ny", "nz"],
    7: ["x", "y", "z", "nx", "ny", "nz", "i"],
    9: ["x", "y", "z", "nx", "ny", "nz", "red", "green", "blue"],
    10: ["x", "y", "z", "nx", "ny", "nz", "red", "green", "blue", "i"],
}


def _first_rows(path, sep):
    """The first data rows' column count, and whether a first line holding one number (a PTS count) comes first."""
    with open(path, "r", errors="replace") as f:
        rows = []
        for line in f:
            s = line.strip()
            if not s or s.startswith("#") or s.startswith("//"):
                continue
            rows.append(s.split(sep) if sep == "," else s.split())
            if len(rows) == 2:
                break
    if not rows:
        return None, False
    count_line = len(rows[0]) == 1 and len(rows) > 1
    return len(rows[1] if count_line else rows[0]), count_line


def _text_chunks(path, ext, chunk):
    sep = "," if ext == ".csv" else r"\s+"
    columns, count_line = _first_rows(path, "," if ext == ".csv" else None)
    if columns is None:
        return
    if ext == ".pts" and columns == 7:  # the PTS convention: x y z intensity r g b
        names = ["x", "y", "z", "i", "red", "green", "blue"]
    elif ext == ".xyzrgb" and columns == 6:
        names = ["x", "y", "z", "red", "green", "blue"]
    elif columns in _COLUMNS:
        names = _COLUMNS[columns]
    else:
        raise ScanError(
            f"{path}: expected 3 (x y z), 6 (x y z nx ny nz) or 9 (x y z nx ny nz r g b) columns, got {columns}"
        )
    skip = 1 if count_line else None
    yield from _table_chunks(path, names, sep, skip, None, chunk, None)

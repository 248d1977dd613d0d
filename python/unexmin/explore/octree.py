"""An OctoMap `.bt` file read in Python: its leaves as integer key boxes (no ROS, no OctoMap library).

The binary format is OctoMap's `writeBinaryData`: a header (`# Octomap OcTree binary file`, `id OcTree`,
`size N`, `res R`, `data`), then the tree depth first, two bytes per inner node, two bits per child
(child i: bits 2i and 2i+1 of byte i // 4): 00 no child (unknown), 01 free leaf, 10 occupied leaf, 11 inner
node (its own two bytes follow, children in order). Child i of a node is on the + side of x, y, z when bit 0,
1, 2 of i is set. Keys: voxel k along an axis spans [(k - 32768) res, (k - 32767) res) [m].
"""

import numpy as np

TREE_DEPTH = 16
KEY_OFFSET = 1 << (TREE_DEPTH - 1)  # 32768: key of the voxel whose lower corner is the origin

# For each byte value, the (child index within the byte's four, 2-bit code) of its existing children.
_CHILDREN = [[(i, (b >> (2 * i)) & 3) for i in range(4) if (b >> (2 * i)) & 3] for b in range(256)]
FREE, OCCUPIED = 1, 2  # 2-bit codes of a leaf; 3: inner node


def read_bt(path):
    """(resolution [m], data bytes) of an OctoMap .bt file; ValueError naming the file when it is not one."""
    with open(path, "rb") as f:
        first = f.readline()
        if not first.startswith(b"# Octomap OcTree binary file"):
            raise ValueError(f"{path}: not an OctoMap .bt file (first line {first[:40]!r})")
        header = {}
        while True:
            line = f.readline()
            if not line:
                raise ValueError(f"{path}: OctoMap header without a 'data' line")
            if line.startswith(b"#"):
                continue
            words = line.decode("ascii", "replace").split()
            if words == ["data"]:
                break
            if len(words) == 2:
                header[words[0]] = words[1]
        if header.get("id", "OcTree") != "OcTree":
            raise ValueError(f"{path}: tree id {header['id']!r}, expected OcTree")
        if "res" not in header:
            raise ValueError(f"{path}: OctoMap header without 'res'")
        return float(header["res"]), f.read()


def leaves(data):
    """Every leaf of a binary tree stream: (lower-corner keys N x 3 int64, edge in keys N, occupied N bool)."""
    keys, sizes, occupied = [], [], []
    if not data:
        return np.zeros((0, 3), np.int64), np.zeros(0, np.int64), np.zeros(0, bool)
    buf = memoryview(data)
    pos = 0
    stack = [(0, 0, 0, 1 << TREE_DEPTH)]  # inner nodes to read: lower-corner key, edge in keys
    while stack:
        x, y, z, size = stack.pop()
        if pos + 2 > len(buf):
            raise ValueError(f"OctoMap data ends inside a node at byte {pos}")
        half = size >> 1
        inner = []
        for byte, base in ((buf[pos], 0), (buf[pos + 1], 4)):
            for i, code in _CHILDREN[byte]:
                c = base + i
                cx, cy, cz = x + (half if c & 1 else 0), y + (half if c & 2 else 0), z + (half if c & 4 else 0)
                if code == 3:
                    inner.append((cx, cy, cz, half))
                else:
                    keys.append((cx, cy, cz))
                    sizes.append(half)
                    occupied.append(code == OCCUPIED)
        pos += 2
        stack.extend(reversed(inner))  # depth first, children in order: the stream's order
    if pos != len(buf):
        raise ValueError(f"OctoMap data: {len(buf) - pos} bytes left after the tree")
    return np.array(keys, np.int64).reshape(-1, 3), np.array(sizes, np.int64), np.array(occupied, bool)


def read_leaves(path):
    """(resolution [m], keys, sizes, occupied) of a .bt file (see leaves())."""
    res, data = read_bt(path)
    return (res, *leaves(data))


def leaf_centres(res, keys, sizes):
    """World centres [m] and edges [m] of leaves given by key boxes."""
    return (keys - KEY_OFFSET + sizes[:, None] / 2.0) * res, sizes * res

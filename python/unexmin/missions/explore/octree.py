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

# For each 16-bit node word (first byte low), the children that are inner nodes (code 3), last first: the order in
# which they go on the decoder's stack.
_INNER = [tuple(c for c in range(7, -1, -1) if (w >> (2 * c)) & 3 == 3) for w in range(1 << 16)]
FREE, OCCUPIED = 1, 2  # 2-bit codes of a leaf; 3: inner node
_BITS = np.array([[(c >> a) & 1 for a in range(3)] for c in range(8)], np.int64)  # child index -> (x, y, z) side


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
    """Every leaf of a binary tree stream: (lower-corner keys N x 3 int64, edge in keys N, occupied N bool).

    Every node is two bytes in the stream, depth first: only the inner nodes' corners are found in a Python loop,
    the leaves are then read from the node words with numpy."""
    if len(data) % 2:
        raise ValueError(f"OctoMap data of {len(data)} bytes: expected two bytes per node")
    words = np.frombuffer(data, "<u2")
    n = len(words)
    if not n:
        return np.zeros((0, 3), np.int64), np.zeros(0, np.int64), np.zeros(0, bool)
    corners = np.empty((n, 4), np.int64)  # x, y, z, edge [keys] of each inner node in stream order
    stack = [(0, 0, 0, 1 << TREE_DEPTH)]
    inner = _INNER
    i = 0
    for i, w in enumerate(words.tolist()):
        if not stack:
            raise ValueError(f"OctoMap data: {2 * (n - i)} bytes left after the tree")
        node = stack.pop()
        corners[i] = node
        x, y, z, size = node
        half = size >> 1
        for c in inner[w]:
            stack.append((x + (half if c & 1 else 0), y + (half if c & 2 else 0), z + (half if c & 4 else 0), half))
    if stack:
        raise ValueError(f"OctoMap data ends inside a node at byte {2 * n}")
    codes = (words[:, None].astype(np.int64) >> (2 * np.arange(8))) & 3  # n x 8 child codes
    node, child = np.nonzero((codes == FREE) | (codes == OCCUPIED))
    half = corners[node, 3] >> 1
    keys = corners[node, :3] + _BITS[child] * half[:, None]
    return keys, half, codes[node, child] == OCCUPIED


def read_leaves(path):
    """(resolution [m], keys, sizes, occupied) of a .bt file (see leaves())."""
    res, data = read_bt(path)
    return (res, *leaves(data))


def leaf_centres(res, keys, sizes):
    """World centres [m] and edges [m] of leaves given by key boxes."""
    return (keys - KEY_OFFSET + sizes[:, None] / 2.0) * res, sizes * res

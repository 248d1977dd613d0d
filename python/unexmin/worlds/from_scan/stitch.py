"""Tiles' surfaces cut at their seams and zipped into one (docs/world_from_scan.md#tiles). Units: [m].

Each tile's surface reaches a little past its core slab; choose_seams() moves a seam within that reach
(seam_shifts) to where the two tiles' loops pair up, and clip_parts() clips every surface exactly at the
seams (clip_slab: triangles across a plane are split, new vertices lie on it), so the two tiles of a seam
both end on the same plane, each with boundary loops around the galleries it crosses. stitch() pairs the
loops of the two sides (the nearest, one to one) and joins each pair by a strip of triangles in the plane:
no gap, no overlap, one consistently wound surface. What no loop of the other side matches stays a hole for
close_holes.
"""

import math

import numpy as np

from unexmin.worlds.from_scan.surface import boundary_loops

SNAP = 1e-6  # [m] a vertex this close to a cutting plane is moved onto it


def _compact(v, t):
    t = t[(t[:, 0] != t[:, 1]) & (t[:, 1] != t[:, 2]) & (t[:, 2] != t[:, 0])]
    used = np.unique(t)
    remap = np.full(len(v), -1, dtype=np.int64)
    remap[used] = np.arange(len(used))
    return v[used], remap[t]


def clip_plane(v, t, axis, c, keep_above):
    """The part of the surface (v, t) on one side of the plane x[axis] = c (above it when `keep_above`):
    triangles across it are split, the new vertices lie exactly on it and are shared by the triangles of
    an edge; the winding is kept. Returns (v, t) compacted."""
    if len(t) == 0:
        return v, t
    v = v.copy()
    d = (v[:, axis] - c) * (1.0 if keep_above else -1.0)
    near = np.abs(d) < SNAP
    v[near, axis] = c
    d[near] = 0.0
    inside = d >= 0.0
    count = inside[t].sum(axis=1)
    whole = t[count == 3]
    cut = t[(count == 1) | (count == 2)]
    if len(cut) == 0:
        return _compact(v, whole)
    cnt = inside[cut].sum(axis=1)
    odd = np.where(cnt == 1, np.argmax(inside[cut], axis=1), np.argmin(inside[cut], axis=1))
    rows = np.arange(len(cut))
    a, b, e = cut[rows, odd], cut[rows, (odd + 1) % 3], cut[rows, (odd + 2) % 3]  # cyclic order kept
    # crossing edges: (odd, next) and (prev, odd), each keyed without direction
    pairs = np.concatenate([np.sort(np.column_stack([a, b]), axis=1), np.sort(np.column_stack([e, a]), axis=1)])
    keys, inverse = np.unique(pairs[:, 0] * len(v) + pairs[:, 1], return_inverse=True)
    i, j = keys // len(v), keys % len(v)
    di, dj = d[i], d[j]
    s = di / (di - dj)
    points = v[i] + s[:, None] * (v[j] - v[i])
    points[:, axis] = c
    new = len(v) + np.arange(len(keys))
    new = np.where(di == 0.0, i, np.where(dj == 0.0, j, new))  # a vertex on the plane is its own crossing
    ab, ea = new[inverse[: len(cut)]], new[inverse[len(cut) :]]
    one = cnt == 1  # a inside, b and e outside: the triangle (a, ab, ea)
    tris = [whole, np.column_stack([a, ab, ea])[one]]
    two = ~one  # a outside, b and e inside: the quad (b, e, ea, ab)
    tris += [np.column_stack([b, e, ea])[two], np.column_stack([b, ea, ab])[two]]
    return _compact(np.concatenate([v, points]), np.concatenate(tris))


def clip_slab(v, t, axis, lo, hi):
    """The part of (v, t) with lo <= x[axis] <= hi (an infinite bound: no cut on that side)."""
    if np.isfinite(lo):
        v, t = clip_plane(v, t, axis, lo, keep_above=True)
    if np.isfinite(hi):
        v, t = clip_plane(v, t, axis, hi, keep_above=False)
    return v, t


def plane_rings(v, t, axis, c):
    """Boundary loops of (v, t) lying in the plane x[axis] = c (every vertex on it), as vertex lists in the
    direction of the surface's boundary half-edges."""
    return [loop for loop in boundary_loops(t) if np.all(v[loop, axis] == c)] if len(t) else []


def _signed_area(xy):
    x, y = xy[:, 0], xy[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def zip_rings(v, ring_a, ring_b, axis):
    """Triangles joining two loops of the same plane (vertex lists into v): ring_a runs along its surface's
    boundary half-edges, ring_b along the other surface's, the opposite way round. Each triangle uses
    one loop edge reversed, so the strip continues both surfaces' winding; the diagonal of each step is
    the shorter one. None when the two loops turn the same way (not the two sides of one seam)."""
    a = np.asarray(ring_a)
    b = np.asarray(ring_b)[::-1]  # now the same way round as ring_a
    plane = [k for k in range(3) if k != axis]
    if _signed_area(v[a][:, plane]) * _signed_area(v[b][:, plane]) <= 0.0:
        return None
    start = int(np.argmin(np.linalg.norm(v[b] - v[a[0]], axis=1)))
    b = np.roll(b, -start)
    n, m = len(a), len(b)
    i = j = 0
    tris = []
    while i < n or j < m:
        ai, ai1 = a[i % n], a[(i + 1) % n]
        bj, bj1 = b[j % m], b[(j + 1) % m]
        advance_a = j >= m or (i < n and np.linalg.norm(v[ai1] - v[bj]) <= np.linalg.norm(v[ai] - v[bj1]))
        if advance_a:
            tris.append((ai1, ai, bj))  # uses ring_a's edge ai -> ai1 reversed
            i += 1
        else:
            tris.append((ai, bj, bj1))  # ring_b's own edge was bj1 -> bj
            j += 1
    return np.array(tris, dtype=np.int64)


def pair_rings(v, rings_a, rings_b, tolerance):
    """One-to-one pairs (index in rings_a, index in rings_b) of loops whose vertices lie, on average,
    within `tolerance` [m] of the other loop's (the nearest pairs first)."""
    from scipy.spatial import cKDTree

    cost = []
    trees = [cKDTree(v[r]) for r in rings_b]
    for i, ra in enumerate(rings_a):
        for j, tree in enumerate(trees):
            d1 = tree.query(v[ra])[0].mean()
            d2 = cKDTree(v[ra]).query(v[rings_b[j]])[0].mean()
            if max(d1, d2) <= tolerance:
                cost.append((max(d1, d2), i, j))
    pairs, used_a, used_b = [], set(), set()
    for _, i, j in sorted(cost):
        if i not in used_a and j not in used_b:
            pairs.append((i, j))
            used_a.add(i)
            used_b.add(j)
    return pairs


def seam_shifts(overlap, resolution):
    """[m] the offsets from its planned place at which a seam is tried, nearest first: 0, then +- steps of two
    resolutions up to a quarter of the overlap (each tile's surface reaches that far past its core: build_tile),
    well inside the part of the overlap where Poisson's fit is as close as in the core."""
    step = 2.0 * resolution
    shifts = [0.0]
    for k in range(1, int(math.floor(0.25 * overlap / step + 1e-9)) + 1):
        shifts += [k * step, -k * step]
    return shifts


def _left_open(a, b, axis, c, tolerance):
    """Loops of the seam plane x[axis] = c that stitch() would leave open between the surfaces a and b (each
    (v, t) or None), a kept below the plane and b above."""
    if a is None or b is None:
        return 0
    va, ta = clip_plane(a[0], a[1], axis, c, keep_above=False)
    vb, tb = clip_plane(b[0], b[1], axis, c, keep_above=True)
    rings_a, rings_b = plane_rings(va, ta, axis, c), plane_rings(vb, tb, axis, c)
    v = np.concatenate([va, vb])
    rings_b = [np.asarray(r) + len(va) for r in rings_b]
    zipped = sum(
        zip_rings(v, rings_a[i], rings_b[j], axis) is not None for i, j in pair_rings(v, rings_a, rings_b, tolerance)
    )
    return len(rings_a) + len(rings_b) - 2 * zipped


def choose_seams(parts, axis, seams, tolerance, shifts):
    """Each seam of `seams` [m] moved by the first offset of `shifts` [m] at which no loop of the plane is left
    open between its two tiles' surfaces `parts` (each reaching past its core by the largest shift; None for a
    failed tile), else by the one that leaves the fewest: a plane through a feature that the two surfaces end on
    differently (a pillar, a gallery's section pinched on one side) is moved off it. Returns the seams [m]."""
    chosen = []
    for k, c in enumerate(seams):
        best = None
        for s in shifts:
            left = _left_open(parts[k], parts[k + 1], axis, c + s, tolerance)
            if best is None or left < best[0]:
                best = (left, c + s)
            if left == 0:
                break
        chosen.append(best[1])
    return chosen


def clip_parts(parts, axis, seams):
    """Each part (v, t), or None, clipped to its slab between `seams` [m] (open at both ends)."""
    bounds = [-math.inf] + list(seams) + [math.inf]
    return [None if p is None else clip_slab(p[0], p[1], axis, bounds[k], bounds[k + 1]) for k, p in enumerate(parts)]


def stitch(parts, axis, seams, tolerance):
    """One surface of the tiles' clipped surfaces `parts` (list of (v, t) in seam order, None for a tile that
    failed) joined at `seams` [m] (the plane between part k and k + 1). Returns (v, t, zipped loops, loops
    left open at the seams)."""
    vs, ts, offset, first = [], [], 0, []
    for p in parts:
        first.append(offset)
        if p is None:
            continue
        vs.append(p[0])
        ts.append(p[1] + offset)
        offset += len(p[0])
    v = np.concatenate(vs) if vs else np.zeros((0, 3))
    t = np.concatenate(ts) if ts else np.zeros((0, 3), np.int64)
    strips, zipped, left = [], 0, 0
    for k, c in enumerate(seams):
        a, b = parts[k], parts[k + 1]
        rings_a = [np.asarray(r) + first[k] for r in plane_rings(a[0], a[1], axis, c)] if a is not None else []
        rings_b = [np.asarray(r) + first[k + 1] for r in plane_rings(b[0], b[1], axis, c)] if b is not None else []
        done_a, done_b = set(), set()
        for i, j in pair_rings(v, rings_a, rings_b, tolerance):
            strip = zip_rings(v, rings_a[i], rings_b[j], axis)
            if strip is not None:
                strips.append(strip)
                done_a.add(i)
                done_b.add(j)
                zipped += 1
        left += len(rings_a) - len(done_a) + len(rings_b) - len(done_b)
    if strips:
        t = np.concatenate([t] + strips)
    return v, t, zipped, left

"""The world's visual meshes for rviz (the thesis's rviz_mesh node; docs/mesh_marker.md).

Reads a world file (docs/worlds.md) and publishes, latched, one visualization_msgs/MarkerArray on
`world_meshes`: a MESH_RESOURCE marker per mesh with `visual: true` (frame `world`, the mesh entry's
xyz/rpy/scale, file:// resource) and, where a visual mesh crosses the free surface, a translucent
TRIANGLE_LIST of the water surface (the cross-section of the mesh at `water.surface_z` on the side its
faces point to: the tank's water, the mine's entry shaft).

The geometry below needs only numpy (the node runs under the system Python); the ROS part is `main`.
"""

import math
import os

import numpy as np

from unexmin.geometry import rpy_quaternion
from unexmin.worlds.files import load_world, placed_mesh
from unexmin.worlds.meshes import MeshFormatError, read_mesh, write_ply

ROCK = (0.42, 0.47, 0.55, 1.0)  # slate grey-blue: apart from the hull's yellow and rviz's grey
WATER = (0.10, 0.45, 0.95, 0.45)


def plane_loops(v, t, z):
    """Closed loops where the surface (v, t) crosses the plane at height z: a list of
    (points K x 3, normals K x 3) with the points in order around the loop and, per segment from point
    k to k+1, the normal of the triangle it was cut from. A vertex exactly on the plane counts as below."""
    above = v[:, 2] > z
    crossing = np.nonzero(above[t].sum(axis=1) % 3 != 0)[0]
    if len(crossing) == 0:
        return []
    tri = t[crossing]
    edges = np.stack([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]], axis=1)  # (C, 3, 2)
    cut = above[edges[..., 0]] != above[edges[..., 1]]  # two per triangle
    keys = np.sort(edges, axis=2)
    n = len(v)
    ids, inverse = np.unique((keys[..., 0] * n + keys[..., 1])[cut], return_inverse=True)
    a, b = v[ids // n], v[ids % n]
    points = a + ((z - a[:, 2]) / (b[:, 2] - a[:, 2]))[:, None] * (b - a)
    seg = inverse.reshape(-1, 2)  # edge-point pairs
    p0, p1, p2 = (v[tri[:, i]] for i in range(3))
    normals = np.cross(p1 - p0, p2 - p0)
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-300)
    touching = [[] for _ in range(len(ids))]
    for s, (i, j) in enumerate(seg):
        touching[i].append(s)
        touching[j].append(s)
    if any(len(x) != 2 for x in touching):
        raise ValueError("the surface is not closed where it crosses the plane")
    used = np.zeros(len(seg), bool)
    loops = []
    for start in range(len(seg)):
        if used[start]:
            continue
        order, norms = [], []
        s, point = start, seg[start][0]
        while not used[s]:
            used[s] = True
            order.append(point)
            norms.append(normals[s])
            point = seg[s][1] if seg[s][0] == point else seg[s][0]
            s = touching[point][0] if touching[point][1] == s else touching[point][1]
        loops.append((points[order], np.array(norms)))
    return loops


def signed_area(xy):
    x, y = xy[:, 0], xy[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def faces_inwards(points, normals):
    """True when the triangles a loop was cut from face into the loop's interior (seen from above)."""
    xy = points[:, :2]
    d = np.roll(xy, -1, axis=0) - xy
    left = np.column_stack([-d[:, 1], d[:, 0]]) * math.copysign(1.0, signed_area(xy))
    return float(np.sum(normals[:, :2] * left)) > 0.0


def triangulate(xy):
    """Ear clipping of a simple polygon (K x 2, either orientation): K-2 triangles of indices, CCW."""
    idx = list(range(len(xy))) if signed_area(xy) > 0 else list(range(len(xy)))[::-1]
    tris = []

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    while len(idx) > 3:
        for k in range(len(idx)):
            i, j, q = idx[k - 1], idx[k], idx[(k + 1) % len(idx)]
            a, b, c = xy[i], xy[j], xy[q]
            if cross(a, b, c) <= 0.0:
                continue  # reflex (or flat) corner
            if any(
                cross(a, b, xy[m]) >= 0 and cross(b, c, xy[m]) >= 0 and cross(c, a, xy[m]) >= 0
                for m in idx
                if m not in (i, j, q)
            ):
                continue  # another vertex inside this ear
            tris.append((i, j, q))
            del idx[k]
            break
        else:
            raise ValueError("polygon is not simple: no ear left to clip")
    tris.append(tuple(idx))
    return np.array(tris, dtype=np.int64)


def water_surface(world):
    """Triangles (T x 3 x 3, world frame [m]) of the free surface inside the visual meshes that cross
    it, on the side their faces point to. Meshes this module cannot read are skipped."""
    out = []
    for entry in world["meshes"]:
        if not entry["visual"]:
            continue
        v, t = placed_mesh(entry)
        for points, normals in plane_loops(v, t, world["surface_z"]):
            if len(points) >= 3 and faces_inwards(points, normals):
                out.append(points[triangulate(points[:, :2])])
    return np.concatenate(out) if out else np.zeros((0, 3, 3))


def cluster_decimate(v, t, max_triangles):
    """At most `max_triangles` triangles of (v, t) by vertex clustering (numpy only): the vertices in each
    cubic cell merged into their mean, the triangles that collapse or repeat dropped; the cell [mesh
    units] grows by 25 % until the count fits, from the edge of equilateral triangles of that count
    over the surface's area. Returns (v, t, cell); cell 0 when the mesh already fits."""
    if len(t) <= max_triangles:
        return v, t, 0.0
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    area = 0.5 * float(np.linalg.norm(np.cross(b - a, c - a), axis=1).sum())
    cell = math.sqrt(area / (max(1, max_triangles) * math.sqrt(3) / 4))
    lo = v.min(axis=0)
    while True:
        keys, inverse = np.unique(np.floor((v - lo) / cell).astype(np.int64), axis=0, return_inverse=True)
        inverse = inverse.reshape(-1)
        counts = np.bincount(inverse, minlength=len(keys)).astype(float)
        cv = np.column_stack([np.bincount(inverse, weights=v[:, k], minlength=len(keys)) for k in range(3)])
        cv /= counts[:, None]
        ct = inverse[t]
        ct = ct[(ct[:, 0] != ct[:, 1]) & (ct[:, 1] != ct[:, 2]) & (ct[:, 2] != ct[:, 0])]
        _, first = np.unique(np.sort(ct, axis=1), axis=0, return_index=True)
        ct = ct[np.sort(first)]
        if len(ct) <= max_triangles:
            return cv, ct, cell
        cell *= 1.25


def display_files(world, max_triangles, cache_dir):
    """{mesh file: the file rviz should load}: the visual meshes with more than `max_triangles` triangles
    decimated (cluster_decimate) into `cache_dir`, reused while the source's size and time are unchanged;
    the others as they are. Meshes this module cannot read are shown as they are."""
    shown = {}
    for entry in world["meshes"]:
        if not entry["visual"]:
            continue
        path = entry["file"]
        st = os.stat(path)
        base = os.path.splitext(os.path.basename(path))[0]
        target = os.path.join(cache_dir, f"{base}_{max_triangles}_{st.st_size}_{st.st_mtime_ns}.ply")
        if os.path.isfile(target):
            shown[path] = target
            continue
        try:
            v, t = read_mesh(path)
        except MeshFormatError:
            continue
        if len(t) <= max_triangles:
            continue
        dv, dt, _ = cluster_decimate(v, t, max_triangles)
        os.makedirs(cache_dir, exist_ok=True)
        write_ply(target + ".part", dv, dt, f"{base} decimated to {len(dt)} triangles for rviz", inward=False)
        os.replace(target + ".part", target)
        shown[path] = target
    return shown


def build_markers(world, frame_id="world", color=ROCK, water_color=WATER, mesh_colors=None, water=True, shown=None):
    """visualization_msgs/MarkerArray for a loaded world (see load_world); `shown`: {mesh file: the file
    the marker names instead} (display_files)."""
    from geometry_msgs.msg import Point
    from std_msgs.msg import ColorRGBA
    from visualization_msgs.msg import Marker, MarkerArray

    array = MarkerArray()
    for i, entry in enumerate(m for m in world["meshes"] if m["visual"]):
        mk = Marker()
        mk.header.frame_id = frame_id  # stamp 0: rviz uses the latest transform
        mk.ns, mk.id, mk.type, mk.action = "world_meshes", i, Marker.MESH_RESOURCE, Marker.ADD
        mk.pose.position.x, mk.pose.position.y, mk.pose.position.z = entry["xyz"]
        q = rpy_quaternion(entry["rpy"])
        mk.pose.orientation.x, mk.pose.orientation.y, mk.pose.orientation.z, mk.pose.orientation.w = q
        mk.scale.x, mk.scale.y, mk.scale.z = entry["scale"]
        mk.color = ColorRGBA(*((mesh_colors or {}).get(entry["name"], color)))
        mk.mesh_resource = "file://" + (shown or {}).get(entry["file"], entry["file"])
        mk.mesh_use_embedded_materials = False
        array.markers.append(mk)
    if water:
        tris = water_surface(world)
        if len(tris):
            mk = Marker()
            mk.header.frame_id = frame_id
            mk.ns, mk.id, mk.type, mk.action = "water_surface", 0, Marker.TRIANGLE_LIST, Marker.ADD
            mk.pose.orientation.w = 1.0
            mk.scale.x = mk.scale.y = mk.scale.z = 1.0
            mk.color = ColorRGBA(*water_color)
            mk.points = [Point(*p) for p in tris.reshape(-1, 3)]
            array.markers.append(mk)
    return array


def _rgba(name, value):
    value = [float(c) for c in value]
    if len(value) != 4 or not all(0.0 <= c <= 1.0 for c in value):
        raise ValueError(f"parameter ~{name} = {value}: expected [r, g, b, a], each in [0, 1]")
    return tuple(value)


def main():
    import rospy
    from visualization_msgs.msg import MarkerArray

    rospy.init_node("mesh_marker")
    world_file = rospy.get_param("~world_file", "")
    if not world_file or not os.path.isfile(world_file):
        raise SystemExit(
            f"mesh_marker: parameter ~world_file = '{world_file}': expected an existing world "
            "file, e.g. $(find unexmin)/worlds/mine.world"
        )
    try:
        world = load_world(world_file)
    except ValueError as e:  # a key the world-file schema does not know, a bad value, a path out of its folder
        raise SystemExit(f"mesh_marker: {e}") from None
    color = _rgba("color", rospy.get_param("~color", list(ROCK)))
    water_color = _rgba("water_color", rospy.get_param("~water_color", list(WATER)))
    mesh_colors = {k: _rgba(f"mesh_colors/{k}", v) for k, v in rospy.get_param("~mesh_colors", {}).items()}
    water = bool(rospy.get_param("~water_surface", True))
    frame_id = rospy.get_param("~frame_id", "world")
    max_triangles = int(rospy.get_param("~max_triangles", 1_000_000))
    if max_triangles < 1000:
        raise SystemExit(f"mesh_marker: parameter ~max_triangles = {max_triangles}: expected at least 1000")
    ros_home = os.environ.get("ROS_HOME", os.path.join(os.path.expanduser("~"), ".ros"))
    cache_dir = rospy.get_param("~cache_dir", os.path.join(ros_home, "mesh_marker"))
    for entry in world["meshes"]:
        if entry["visual"] and not os.path.isfile(entry["file"]):
            raise SystemExit(f"mesh_marker: {world_file}: mesh '{entry['name']}' file {entry['file']} does not exist")
    shown = display_files(world, max_triangles, cache_dir)
    for source, target in shown.items():
        rospy.loginfo("mesh_marker: %s shown decimated: %s", source, target)
    try:
        array = build_markers(world, frame_id, color, water_color, mesh_colors, water, shown)
    except MeshFormatError as e:
        rospy.logwarn("mesh_marker: no water surface marker: %s", e)
        array = build_markers(world, frame_id, color, water_color, mesh_colors, False, shown)
    pub = rospy.Publisher("world_meshes", MarkerArray, queue_size=1, latch=True)
    pub.publish(array)
    rospy.loginfo(
        "mesh_marker: %d marker(s) of world '%s' on %s (latched)", len(array.markers), world["name"], pub.resolved_name
    )
    rospy.spin()

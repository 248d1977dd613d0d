#!/usr/bin/env python3
"""Generate the laboratory-tank and test-box meshes of the shipped worlds (binary STL).

Writes, into worlds/meshes/ (or --out):
  tank.stl      open-top rectangular tank: floor and four walls as one watertight thin-walled solid,
                faces towards the water pointing into the water. Interior 6 m (x) x 4 m (y), floor at
                z = -3 m, rim at z = +0.3 m (the free surface of tank.world is z = 0).
  anchor.stl    a simple admiralty-style metal anchor about 0.6 m tall, in its own frame: top of the
                ring at z = 0, hanging down along -z (tank.world places it at z = -1.8 m).
  test_box.stl  closed 4 m cube shell centred on the origin, inner faces pointing inwards.
  target.stl    a thin plate for the checkerboard calibration target, centred on its frame's origin, faces along
                +-z (tank_target.world gives it the checkerboard material).

All dimensions are [m]. Deterministic: no randomness, so re-running reproduces the same files.
Usage: python3 worlds/tools/make_tank.py [--out DIR]
"""

import argparse
import os

import numpy as np
import trimesh

# ---- tank (ours: the thesis gives no size) ----
TANK_X = 6.0  # [m] interior length along x
TANK_Y = 4.0  # [m] interior width along y
TANK_FLOOR_Z = -3.0  # [m] interior floor height (3 m of water below the surface at z = 0)
TANK_RIM_Z = 0.3  # [m] top of the walls
WALL = 0.05  # [m] wall and floor thickness (tank and test box)

# ---- test box ----
BOX_SIZE = 4.0  # [m] interior edge of the closed cube, centred on the origin

# ---- calibration target plate: 9 x 7 squares of 0.08 m and a 0.06 m margin (docs/worlds.md, checkerboard) ----
TARGET_SIZE = (0.84, 0.68, 0.01)  # [m] along x, y, z

# ---- anchor (admiralty pattern, made of boxes and cylinders) ----
RING_RADIUS = 0.04  # [m] ring: major radius
RING_TUBE = 0.008  # [m] ring: tube radius
SHANK_RADIUS = 0.02  # [m]
SHANK_TOP = -0.08  # [m] shank from here ...
SHANK_BOTTOM = -0.56  # [m] ... down to the crown
STOCK_RADIUS = 0.015  # [m] stock: bar across the top, along y (perpendicular to the arms)
STOCK_LENGTH = 0.5  # [m]
STOCK_Z = -0.12  # [m]
ARM_LENGTH = 0.30  # [m] each arm, from the crown
ARM_SECTION = (0.035, 0.03)  # [m] arm cross-section (in the arms' plane, across it)
ARM_ELEVATION = np.radians(45.0)  # [rad] arms rise from the crown at this angle, in the x-z plane
FLUKE_SIZE = (0.12, 0.10, 0.01)  # [m] palm: along the arm, across (y), thickness
CROWN_RADIUS = 0.03  # [m]
SECTIONS = 24  # facets around cylinders and the ring


def _quad(a, b, c, d):
    """Two triangles of the quad a-b-c-d (vertex indices)."""
    return [[a, b, c], [a, c, d]]


def open_tank(x, y, floor_z, rim_z, t):
    """Watertight thin-walled open-top box; interior [-x/2, x/2] x [-y/2, y/2] x [floor_z, rim_z]."""
    hx, hy = x / 2.0, y / 2.0
    # Corner order around a rectangle (counter-clockwise seen from +z).
    ring = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
    verts = []
    for sx, sy in ring:  # 0..3 inner floor
        verts.append((sx * hx, sy * hy, floor_z))
    for sx, sy in ring:  # 4..7 inner rim
        verts.append((sx * hx, sy * hy, rim_z))
    for sx, sy in ring:  # 8..11 outer bottom
        verts.append((sx * (hx + t), sy * (hy + t), floor_z - t))
    for sx, sy in ring:  # 12..15 outer rim
        verts.append((sx * (hx + t), sy * (hy + t), rim_z))
    faces = []
    # Counter-clockwise seen from outside the wall solid: normals point out of the walls, which on
    # the inner faces is into the water.
    faces += _quad(0, 1, 2, 3)  # inner floor, +z
    faces += _quad(11, 10, 9, 8)  # outer bottom, -z
    for i in range(4):
        j = (i + 1) % 4
        faces += _quad(i, 4 + i, 4 + j, j)  # inner walls, towards the centre
        faces += _quad(8 + i, 8 + j, 12 + j, 12 + i)  # outer walls, away from it
        faces += _quad(4 + i, 12 + i, 12 + j, 4 + j)  # rim, +z
    return trimesh.Trimesh(np.array(verts, float), np.array(faces, np.int64), process=True)


def closed_box_shell(size, t):
    """Hollow cube: interior edge `size`, walls `t` thick; inner faces point inwards."""
    outer = trimesh.creation.box(extents=[size + 2 * t] * 3)
    inner = trimesh.creation.box(extents=[size] * 3)
    inner.invert()
    return trimesh.util.concatenate([outer, inner])


def _cylinder_between(p0, p1, radius):
    p0, p1 = np.asarray(p0, float), np.asarray(p1, float)
    return trimesh.creation.cylinder(radius=radius, segment=np.array([p0, p1]), sections=SECTIONS)


def _box_along(center, direction, extents):
    """Box with extents (along, across-y, thickness) whose first axis follows `direction` in x-z."""
    d = np.asarray(direction, float)
    d /= np.linalg.norm(d)
    pitch = -np.arctan2(d[2], d[0])  # rotate +x onto d about y
    tf = trimesh.transformations.rotation_matrix(pitch, [0, 1, 0])
    tf[:3, 3] = center
    return trimesh.creation.box(extents=extents, transform=tf)


def anchor():
    parts = []
    ring_centre_z = -(RING_RADIUS + RING_TUBE)
    ring = trimesh.creation.torus(
        major_radius=RING_RADIUS, minor_radius=RING_TUBE, major_sections=SECTIONS, minor_sections=12
    )
    ring.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [1, 0, 0]))  # ring in x-z plane
    ring.apply_translation([0, 0, ring_centre_z])
    parts.append(ring)
    parts.append(_cylinder_between([0, 0, SHANK_TOP], [0, 0, SHANK_BOTTOM], SHANK_RADIUS))
    parts.append(_cylinder_between([0, -STOCK_LENGTH / 2, STOCK_Z], [0, STOCK_LENGTH / 2, STOCK_Z], STOCK_RADIUS))
    crown = np.array([0.0, 0.0, SHANK_BOTTOM])
    parts.append(trimesh.creation.icosphere(subdivisions=2, radius=CROWN_RADIUS).apply_translation(crown))
    for side in (-1.0, 1.0):
        d = np.array([side * np.cos(ARM_ELEVATION), 0.0, np.sin(ARM_ELEVATION)])
        parts.append(_box_along(crown + d * ARM_LENGTH / 2, d, [ARM_LENGTH, ARM_SECTION[1], ARM_SECTION[0]]))
        # Palm on the upper (inner) face of the arm, near its tip.
        normal = np.array([-d[2] * side, 0.0, d[0] * side])  # perpendicular to d in x-z, pointing up
        centre = crown + d * (ARM_LENGTH - FLUKE_SIZE[0] / 2) + normal * (ARM_SECTION[0] / 2 + FLUKE_SIZE[2] / 2)
        parts.append(_box_along(centre, d, list(FLUKE_SIZE[:2]) + [FLUKE_SIZE[2]]))
    return trimesh.util.concatenate(parts)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--out", default=os.path.join(here, os.pardir, "meshes"), help="output folder (default: worlds/meshes)"
    )
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)

    tank = open_tank(TANK_X, TANK_Y, TANK_FLOOR_Z, TANK_RIM_Z, WALL)
    box = closed_box_shell(BOX_SIZE, WALL)
    for name, mesh in (("tank", tank), ("test_box", box)):
        if not (mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0):
            raise RuntimeError("%s mesh is not a closed, consistently wound solid" % name)
    meshes = {"tank": tank, "anchor": anchor(), "test_box": box, "target": trimesh.creation.box(extents=TARGET_SIZE)}
    for name, mesh in meshes.items():
        path = os.path.normpath(os.path.join(args.out, name + ".stl"))
        with open(path, "wb") as f:
            f.write(trimesh.exchange.stl.export_stl(mesh))
        lo, hi = mesh.bounds
        print(
            "%-9s %5d faces  bounds [%s] .. [%s]  -> %s"
            % (name, len(mesh.faces), " ".join("%.3f" % v for v in lo), " ".join("%.3f" % v for v in hi), path)
        )


if __name__ == "__main__":
    main()

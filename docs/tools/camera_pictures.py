#!/usr/bin/env python3
"""The camera pictures of README.md and docs/vision.md: cameras 0 and 4 of UX_1 in the mine's first-level gallery at
the four visibility levels, one strip of four frames per camera.

UX_1 at x = 11.5, y = -0.07, z = -21.4 m, yaw 70 deg (the gallery runs along +x): camera 0, 20 deg left of the bow,
faces the gallery's left wall; camera 4 looks forward and 55 deg down at the floor towards that wall. The default UX-1
description (its lights, SLS lasers, exposure, noise) with the cameras at 640 x 480, rendered in-process
(unexmin.core, visual mode, seed 1), the first frame (t = 0.1 s), one world per level; each frame halved to 320 x 240
and the four put side by side (none, low, medium, high), written as an 8-bit palette PNG (256 colours: small files).

    source scripts/env.sh && python docs/tools/camera_pictures.py [--out docs/images]

Writes camera0_mine_visibility.png and camera4_mine_visibility.png.
"""

import argparse
import shutil
import subprocess
import tempfile
from pathlib import Path

import cv2
import numpy as np
import yaml

REPO = Path(__file__).resolve().parents[2]
POSE = [11.5, -0.07, -21.4]  # [m] UX_1 in the first level's gallery
YAW = 1.22  # [rad] 70 deg: camera 0 (20 deg left of the bow) faces the gallery's left wall
LEVELS = ["none", "low", "medium", "high"]
CAMERAS = ["camera_0", "camera_4"]


def description(folder):
    """UX_1 with its cameras at 640 x 480 (an overrides file in `folder`)."""
    overrides = Path(folder) / "overrides.xacro"
    overrides.write_text(
        '<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:property name="camera_width" value="640"/>\n'
        '  <xacro:property name="camera_height" value="480"/>\n</robot>\n'
    )
    xacro = shutil.which("xacro")
    if not xacro:
        raise SystemExit("camera_pictures: xacro not on PATH (source scripts/env.sh)")
    args = [xacro, str(REPO / "urdf" / "ux1.urdf.xacro"), "name:=UX_1", f"overrides:={overrides}"]
    return subprocess.run(args, check=True, capture_output=True, text=True).stdout


def gallery_world(folder):
    """worlds/mine.world with UX_1 alone at POSE, beside links to the mine's meshes."""
    from unexmin.worlds.files import link_meshes

    world = yaml.safe_load((REPO / "worlds" / "mine.world").read_text())
    world["robots"] = [dict(world["robots"][0], xyz=POSE, rpy=[0.0, 0.0, YAW])]
    link_meshes(world["meshes"], str(REPO / "worlds"), str(folder))
    path = Path(folder) / "gallery.world"
    path.write_text(yaml.safe_dump(world))
    return path


def frames(world, urdf):
    """{camera: [RGB frame per level]}."""
    from unexmin.core import World

    out = {c: [] for c in CAMERAS}
    for level in LEVELS:
        w = World(str(world), seed=1, sensors="camera", visibility=level, mode="visual", descriptions={"UX_1": urdf})
        ux = w.robot("UX_1")
        while any(ux.sample(c)["count"] == 0 for c in CAMERAS):  # the first frame: t = 1/rate
            w.step(1)
        for c in CAMERAS:
            out[c].append(ux.sample(c)["image"].copy())
    return out


def write_strip(images, path):
    """The frames halved and side by side, as a 256-colour palette PNG."""
    from PIL import Image

    strip = np.hstack([cv2.resize(i, (i.shape[1] // 2, i.shape[0] // 2), interpolation=cv2.INTER_AREA) for i in images])
    Image.fromarray(strip).quantize(256, dither=Image.Dither.NONE).save(path, optimize=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(REPO / "docs" / "images"), help="output folder (default docs/images)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        got = frames(gallery_world(folder), description(folder))
    for c, images in got.items():
        path = Path(args.out) / f"{c.replace('_', '')}_mine_visibility.png"
        write_strip(images, path)
        means = ", ".join(f"{lv} {i.mean():.1f}" for lv, i in zip(LEVELS, images))
        print(f"{path} ({path.stat().st_size // 1024} kB): mean level {means}")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Cost of the cameras' rock texture and relief, and the visual-mode figures that depend on it
(docs/benchmarks.md, "Cameras"; docs/vision.md, "Cost").

    source scripts/env.sh && python bench/texture_cost.py [--rounds 5] [--frames 10] [--callgrind]
                                                           [--rtf] [--rtf-repeat 3] [--full] [--camera-fps EXE]...

Three copies of worlds/mine.world, beside links to its meshes, differ only in the walls' material:
  plain   the material's albedo alone (no texture)
  flat    the shipped rock with relief 0 (texture, no relief)
  rock    the shipped rock (texture and relief)
and two views of camera_fps (the ROS-free camera at 640 x 480, its SLS line, noise on):
  wall    camera 0, the shaft wall at 1.8 m in clear water (pose 4.6 0 -5 -0.35, visibility none)
  spawn   camera 0 at UX_1's spawn in the world's water (visibility medium)
Printed:
  * CPU time per frame (all threads; stays near an idle machine's figure under load), the median of --rounds
    rounds in which the three worlds alternate, and the texture's and relief's shares of the rock frame:
    texture = (flat - plain) / rock, relief = (rock - flat) / rock;
  * with --callgrind: instructions per frame under `valgrind --tool=callgrind` (one caster thread, only inside
    CameraSensor::render; repeatable whatever the load), the same shares, and the part inside
    RockTexture::shadeManyFrom (RockTexture::shadeMany in a build without it). Each of the six runs loads the
    mine's 1.13M triangles under valgrind: minutes of CPU each;
  * with --rtf: bench/visual_rtf.py (mine, 1 robot, every sensor, 5 cameras at 640 x 480 and 10 fps, images
    subscribed; RTF, CPU, resident memory now and peak) and, with --full, its 2054 x 1544 figure.
"""

import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

import yaml

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "python"))
from unexmin.worlds.files import link_meshes  # noqa: E402

WORLDS = ("plain", "flat", "rock")
VIEWS = {
    "wall": ["--pose", "4.6", "0", "-5", "-0.35", "--visibility", "none"],
    "spawn": ["--visibility", "medium"],
}


def workspace():
    return os.environ.get("UNEXMIN_WS", os.path.join(os.path.dirname(REPO), os.path.basename(REPO) + "_ws"))


def write_worlds(tmp):
    """The three worlds of the module docstring, in tmp; their paths by name."""
    source = os.path.join(REPO, "worlds", "mine.world")
    with open(source) as f:
        text = f.read()
    paths = {}
    for name in WORLDS:
        world = yaml.safe_load(text)
        textured = [m for m in world["meshes"] if "material" in m]
        if not textured:
            sys.exit(f"{source}: no mesh has a material: nothing to compare")
        for m in textured:
            if name == "plain":
                m["albedo"] = m.pop("material")["albedo"]
            elif name == "flat":
                m["material"]["relief"] = 0.0
        folder = os.path.join(tmp, name)
        os.makedirs(folder)
        link_meshes(world["meshes"], os.path.dirname(source), folder)
        paths[name] = os.path.join(folder, "mine.world")
        with open(paths[name], "w") as f:
            yaml.safe_dump(world, f)
    return paths


EXE = os.path.join(workspace(), "devel", "lib", "unexmin", "camera_fps")


def camera_fps(exe, urdf, world, view, frames, extra=(), prefix=()):
    if not os.path.exists(exe):
        sys.exit(f"{exe} not built: catkin_make -j2 camera_fps in {workspace()}")
    cmd = list(prefix) + [exe, urdf, world, "--size", "640x480", "--frames", str(frames)]
    out = subprocess.run(cmd + VIEWS[view] + list(extra), check=True, capture_output=True, text=True)
    return out


def cpu_ms(out):
    """CPU per frame [ms] from camera_fps's 640x480 line."""
    for line in out.stdout.splitlines():
        if line.startswith("640x480"):
            return float(line.split()[5])
    sys.exit("camera_fps printed no 640x480 line:\n" + out.stdout + out.stderr)


def shares(v):
    return (v["flat"] - v["plain"]) / v["rock"], (v["rock"] - v["flat"]) / v["rock"]


def callgrind(exe, urdf, world, view, tmp, name):
    """Instructions per frame inside CameraSensor::render, and inside RockTexture::shadeMany (one caster thread)."""
    out_file = os.path.join(tmp, f"{name}_{view}.callgrind")
    frames = 1  # camera_fps renders frames + 1 (the first builds the tables, outside render)
    run = camera_fps(
        exe,
        urdf,
        world,
        view,
        frames,
        extra=["--threads", "1"],
        prefix=[
            "valgrind",
            "--tool=callgrind",
            f"--callgrind-out-file={out_file}",
            "--toggle-collect=unexmin::sensors::vision::CameraSensor::render*",
        ],
    )
    m = re.search(r"Collected : (\d+)", run.stderr)
    if not m:
        sys.exit("no callgrind count:\n" + run.stderr[-2000:])
    total = int(m.group(1)) / (frames + 1)
    annotate = subprocess.run(
        ["callgrind_annotate", "--inclusive=yes", "--threshold=100", out_file], capture_output=True, text=True
    ).stdout
    texture = 0
    for line in annotate.splitlines():
        if "RockTexture::shadeMany" in line:  # shadeManyFrom, or shadeMany where there is none
            texture = max(texture, int(line.split()[0].replace(",", "")))
    return total, texture / (frames + 1)


def load():
    return "load %.1f %.1f %.1f" % os.getloadavg()


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=5, help="rounds of the three worlds (CPU time: the median)")
    ap.add_argument("--frames", type=int, default=10, help="frames per camera_fps run")
    ap.add_argument("--callgrind", action="store_true", help="also the instruction counts (slow)")
    ap.add_argument("--rtf", action="store_true", help="also bench/visual_rtf.py at 640x480 (and --full)")
    ap.add_argument("--rtf-repeat", type=int, default=3, help="visual_rtf runs at 640x480")
    ap.add_argument("--full", action="store_true", help="with --rtf: one run at 2054x1544 too")
    ap.add_argument(
        "--camera-fps",
        action="append",
        help=f"a camera_fps binary (default {EXE}); given more than once, each in the same rounds (to compare builds)",
    )
    args = ap.parse_args()
    exes = args.camera_fps or [EXE]
    for tool in ["xacro"] + (["valgrind", "callgrind_annotate"] if args.callgrind else []):
        if not shutil.which(tool):
            sys.exit(f"{tool} not on PATH (source scripts/env.sh; valgrind: Debian's valgrind)")
    tmp = tempfile.mkdtemp(prefix="texture_cost_")
    try:
        urdf = os.path.join(tmp, "ux1.urdf")
        with open(urdf, "w") as f:
            f.write(
                subprocess.run(
                    ["xacro", os.path.join(REPO, "urdf", "ux1.urdf.xacro"), "name:=UX_1"],
                    check=True,
                    capture_output=True,
                    text=True,
                ).stdout
            )
        worlds = write_worlds(tmp)
        print(f"camera 0, 640x480, {os.cpu_count()} hardware threads; {load()}", flush=True)
        for k, exe in enumerate(exes):
            print(f"build {k}: {exe}")
        print(f"CPU time per frame [ms], median of {args.rounds} rounds of {args.frames} frames, worlds alternating")
        print(f"{'view':<6} {'build':>5} {'plain':>7} {'flat':>7} {'rock':>7} {'texture':>8} {'relief':>7} {'both':>6}")
        for view in VIEWS:
            runs = {(k, w): [] for k in range(len(exes)) for w in WORLDS}
            for _ in range(args.rounds):
                for k, exe in enumerate(exes):
                    for w in WORLDS:
                        runs[k, w].append(cpu_ms(camera_fps(exe, urdf, worlds[w], view, args.frames)))
            for k in range(len(exes)):
                v = {w: statistics.median(runs[k, w]) for w in WORLDS}
                t, r = shares(v)
                print(
                    f"{view:<6} {k:>5} {v['plain']:>7.2f} {v['flat']:>7.2f} {v['rock']:>7.2f} {100 * t:>7.1f}% "
                    f"{100 * r:>6.1f}% {100 * (t + r):>5.1f}%   ({load()})",
                    flush=True,
                )
        if args.callgrind:
            print("instructions per frame (callgrind, inside CameraSensor::render, 1 caster thread) [millions]")
            print(
                f"{'view':<6} {'build':>5} {'plain':>7} {'flat':>7} {'rock':>7} {'texture':>8} {'relief':>7} "
                f"{'both':>6}  shadeMany"
            )
            for view in VIEWS:
                for k, exe in enumerate(exes):
                    v, tex = {}, 0.0
                    for w in WORLDS:
                        v[w], t = callgrind(exe, urdf, worlds[w], view, tmp, f"{w}{k}")
                        tex = t if w == "rock" else tex
                    t, r = shares(v)
                    print(
                        f"{view:<6} {k:>5} {v['plain'] / 1e6:>7.2f} {v['flat'] / 1e6:>7.2f} {v['rock'] / 1e6:>7.2f} "
                        f"{100 * t:>7.1f}% {100 * r:>6.1f}% {100 * (t + r):>5.1f}%  {tex / 1e6:.2f} "
                        f"({100 * tex / v['rock']:.1f}% of the rock frame)",
                        flush=True,
                    )
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if args.rtf:
        bench = os.path.join(REPO, "bench", "visual_rtf.py")
        sizes = [("640x480", args.rtf_repeat, "10")] + ([("2054x1544", 1, "2")] if args.full else [])
        for size, repeat, seconds in sizes:
            cmd = [sys.executable, bench, "--size", size, "--repeat", str(repeat), "--sim-seconds", seconds]
            if subprocess.run(cmd).returncode != 0:
                return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

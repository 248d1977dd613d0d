#!/usr/bin/env python3
"""Real-time factor of the engine in-process (unexmin.core), no ROS: the tank, one robot.

    source scripts/env.sh && python bench/core_rtf.py [--world tank] [--seconds 60] [--repeat 3] [--threads 1]
                                                      [--mode visual] [--size 640x480]

Three configurations: dynamics only (sensors="none"), every operational-mode sensor but the science payload, and
every operational-mode sensor on (sensors="all", mode=operational: the cameras take no images); the last line gives
the science payload's share of the step's cost (1 - RTF_all / RTF_without, in CPU time). The robot holds a
thrust command the whole time; the script calls step(500) (1 s of sim time at 500 Hz) --seconds times and
prints sim time / wall time (and / this process's CPU time, which other processes on a loaded machine do not
inflate), best of --repeat, plus the cost of one step and the process's peak resident memory. --threads:
ray-casting threads (default 1: one core; 0 = every hardware thread, as the simulator's default). --mode
visual: the last two configurations render every camera's images (the mine: `--world mine --mode visual
--size 640x480 --seconds 5`); --size: every camera's image size (camera_width, camera_height of the robot
description, as bench/visual_rtf.py overrides them).
"""

import argparse
import os
import resource
import tempfile
import time

from unexmin.core import World

#: The UX-1's families without and with its science payload (urdf/sensor_plugins.xacro).
NAVIGATION = ("imu", "dvl", "pressure", "msis", "m3", "sls", "camera")
SCIENCE = ("water_probe", "water_sampler", "magnetometer", "gamma_counter")


def rtf(world, sensors, seconds, repeat, threads, mode="operational", size=None):
    extra = {}
    if size:
        from visual_rtf import overrides  # bench/visual_rtf.py: the same overrides file

        path = os.path.join(tempfile.mkdtemp(prefix="core_rtf_"), "cameras.xacro")
        overrides(path, *size, 10)
        extra["overrides"] = {"UX_1": path}
    w = World(world, robots=1, seed=0, sensors=sensors, ray_caster_threads=threads, mode=mode, **extra)
    ux = w.robot("UX_1")
    best = best_cpu = 0.0
    for _ in range(repeat):
        w.reset()
        ux.thrusts([5.0, 0, -5.0, 0, 5.0, 0, -5.0, 0])
        start, start_cpu = time.perf_counter(), time.process_time()
        for _ in range(seconds):
            w.step(500)
        best = max(best, w.time / (time.perf_counter() - start))
        best_cpu = max(best_cpu, w.time / (time.process_time() - start_cpu))
    return best, best_cpu, w.dt


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--world", default="tank")
    parser.add_argument("--seconds", type=int, default=60, help="sim time per run [s] (default 60)")
    parser.add_argument("--repeat", type=int, default=3, help="runs per configuration, the best counts")
    parser.add_argument("--threads", type=int, default=1, help="ray-casting threads (0: every hardware thread)")
    parser.add_argument("--mode", default="operational", choices=("operational", "visual"), help="/sim/mode")
    parser.add_argument("--size", help="WxH of every camera's image (default: the description's)")
    args = parser.parse_args()
    size = tuple(int(v) for v in args.size.split("x")) if args.size else None
    cpus = {}
    for label, sensors in (
        ("dynamics only", "none"),
        (f"every {args.mode}-mode sensor but the science payload", ",".join(NAVIGATION)),
        (f"every {args.mode}-mode sensor", "all"),
    ):
        value, cpu, dt = rtf(args.world, sensors, args.seconds, args.repeat, args.threads, args.mode, size)
        cpus[sensors] = cpu
        print(
            f"{args.world}, 1 robot, {label}: RTF {value:.4g} ({dt / value * 1e6:.2f} us of wall time per "
            f"{dt * 1e3:g} ms step), {cpu:.4g} in this process's CPU time"
        )
    share = 1.0 - cpus["all"] / cpus[",".join(NAVIGATION)]
    print(f"the science payload ({', '.join(SCIENCE)}): {100 * share:.1f} % of the every-sensor step's CPU")
    print(f"peak RSS {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Visual mode benchmark: real-time factor of the mine with one robot, every sensor and all five
cameras rendering, their images subscribed and counted (docs/benchmarks.md, "Cameras").

    source scripts/env.sh && python bench/visual_rtf.py [--size 640x480] [--fps 10] [--sim-seconds 10]
                                                        [--repeat 3] [--visibility LEVEL] [--sink cpp|python]

Each run, in a fresh process with its own ROS master:
  * writes an overrides file giving every camera the --size and --fps (camera_width, camera_height,
    camera_fps: the intrinsics follow, CameraInfo describes the image published);
  * launches `mine_world.launch robots:=1 realtime:=false mode:=visual sensors:=all
    lockstep_wait_subscribers:=true` (lockstep that waits for its subscribers' queues, so that every
    image reaches the benchmark), UX_1 in the entry shaft, its cameras facing the shaft's walls;
  * subscribes to the five `camera_<i>/image_raw` topics, every image received: --sink cpp (default) with
    bench/topic_counter.cpp (a C++ node, as image_view or a user's perception node would be; it copies each
    image once and counts it), --sink python with rospy subscribers in this process (each image
    deserialised by rospy, which costs the two cores a few per cent more);
  * pauses, then steps --sim-seconds through /sim/step in 1 s chunks while UX_1 surges into the wall;
  * RTF: sim time over the wall time it took; images received against 5 x fps x sim time; the
    simulator's CPU use and its resident memory (now and peak, VmHWM).
"""

import argparse
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from xmlrpc.client import ServerProxy

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mine_rtf import PATTERNS, cpu_seconds, machine, proc_status  # noqa: E402
from sensors_rtf import run_child  # noqa: E402

CAMERAS = 5


def overrides(path, width, height, fps):
    with open(path, "w") as f:
        f.write(f"""<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="camera_width" value="{width}"/>
  <xacro:property name="camera_height" value="{height}"/>
  <xacro:property name="camera_fps" value="{fps}"/>
</robot>
""")


def measure(width, height, fps, sim_seconds, seed, timeout, visibility, sink="cpp"):
    from unexmin.scripting.launcher import WorldProcess, wait_for

    tmp = tempfile.mkdtemp(prefix="visual_rtf_")
    xacro = os.path.join(tmp, "cameras.xacro")
    overrides(xacro, width, height, fps)
    extra = ["mode:=visual", "sensors:=all", "lockstep_wait_subscribers:=true", f"UX_1_overrides:={xacro}"]
    if visibility:
        extra.append(f"visibility:={visibility}")
    world = WorldProcess(world="mine", robots=1, seed=seed, realtime=False, paused=True, extra_args=extra)
    try:
        import rosgraph
        import rospy
        from sensor_msgs.msg import Image
        from std_msgs.msg import Float64

        from unexmin.srv import Step
        from unexmin.topics import sync_publisher

        rospy.init_node("visual_bench", anonymous=True, disable_signals=True)
        rospy.wait_for_service("/sim/step", timeout)
        topics = [f"/UX_1/camera_{i}/image_raw" for i in range(CAMERAS)]
        received = [0] * CAMERAS
        sizes = set()
        master = rosgraph.Master(rospy.get_name())
        counter = None
        if sink == "cpp":
            from sensors_rtf import build_counter

            window = os.path.join(tmp, "window")
            counter = subprocess.Popen(
                [str(build_counter(tmp)), window, "1000"] + topics, stdout=subprocess.PIPE, text=True
            )
            wait_for(
                lambda: sum(
                    any(n.startswith("/topic_counter") for n in nodes)
                    for t, nodes in master.getSystemState()[1]
                    if t in topics
                )
                == CAMERAS,
                timeout,
                "the C++ counter to subscribe to the five image_raw topics",
            )
        else:

            def on_image(msg, i):
                received[i] += 1
                sizes.add((msg.width, msg.height, len(msg.data)))

            subs = [
                rospy.Subscriber(t, Image, on_image, callback_args=i, queue_size=100, buff_size=2**26, tcp_nodelay=True)
                for i, t in enumerate(topics)
            ]
            wait_for(
                lambda: all(s.get_num_connections() > 0 for s in subs),
                timeout,
                "the simulator's five image_raw publishers",
            )
        thrusters = [sync_publisher(f"/UX_1/thrusters/{i}/input", Float64) for i in range(8)]
        wait_for(
            lambda: all(p.get_num_connections() > 0 for p in thrusters),
            timeout,
            "the simulator to subscribe to the thrusters",
        )
        pid = ServerProxy(master.lookupNode("/simulator")).getPid(rospy.get_name())[2]
        step = rospy.ServiceProxy("/sim/step", Step, persistent=True)
        sim0 = step(duration=0.0, steps=1, client="", commands=0, hold=True).time
        base = list(received)
        wall0, cpu0 = time.monotonic(), cpu_seconds(pid)
        sim1 = sim0
        while sim1 - sim0 < sim_seconds - 1e-9:
            for p, v in zip(thrusters, PATTERNS["UX_1"]):
                p.publish(Float64(v))
            sim1 = step(duration=1.0, steps=0, client="", commands=0, hold=True).time
        wall1, cpu1 = time.monotonic(), cpu_seconds(pid)
        expected = round((sim1 - sim0) * fps)
        # One more physics step, outside the timing: lockstep_wait_subscribers waits before it until the images of
        # the last timed step have been taken too (their stamp is sim1, inside the counted window).
        step(duration=0.0, steps=1, client="", commands=0, hold=True)
        if counter is not None:
            # lockstep_wait_subscribers: the step returns once the counter's queues have drained
            with open(window, "w") as f:
                f.write(f"{sim0} {sim1}")
            counter.send_signal(signal.SIGINT)  # it counts the images stamped inside the window, then exits
            counts = dict(line.split() for line in counter.communicate(timeout=timeout)[0].splitlines())
            received = [int(counts.get(t, 0)) for t in topics]
            base = [0] * CAMERAS
        else:
            try:
                wait_for(lambda: all(r - b >= expected for r, b in zip(received, base)), 30.0, "the last images")
            except TimeoutError:
                pass
        mem = proc_status(pid)
        return {
            "size": f"{width}x{height}",
            "fps": fps,
            "rtf": (sim1 - sim0) / (wall1 - wall0),
            "cpu_percent": 100.0 * (cpu1 - cpu0) / (wall1 - wall0),
            "rss_mb": mem["VmRSS"],
            "peak_rss_mb": mem["VmHWM"],
            "sim_seconds": sim1 - sim0,
            "images": [r - b for r, b in zip(received, base)],
            "expected_per_camera": expected,
            "image_sizes": sorted(sizes),
            "sink": sink,
        }
    finally:
        if counter is not None and counter.poll() is None:
            counter.kill()
            counter.wait()
        world.close()


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", default="640x480", help="every camera's WxH (default 640x480; full: 2054x1544)")
    ap.add_argument("--fps", type=float, default=10.0, help="every camera's frame rate [Hz]")
    ap.add_argument("--sim-seconds", type=float, default=10.0, help="sim seconds per run")
    ap.add_argument("--repeat", type=int, default=3, help="runs (the summary takes the median)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--timeout", type=float, default=180.0, help="wall seconds allowed for each wait")
    ap.add_argument("--visibility", default="", help="override the world's visibility (none|low|medium|high)")
    ap.add_argument(
        "--sink",
        choices=("cpp", "python"),
        default="cpp",
        help="who subscribes to the images: a C++ counter node (default) or rospy in this process",
    )
    ap.add_argument("--once", action="store_true", help="one run in this process, JSON out")
    args = ap.parse_args()
    width, height = (int(v) for v in args.size.lower().split("x"))
    if args.once:
        print(
            json.dumps(
                measure(width, height, args.fps, args.sim_seconds, args.seed, args.timeout, args.visibility, args.sink)
            )
        )
        return 0
    print(
        f"mine, 1 robot, mode:=visual, every sensor, 5 cameras at {args.size} and {args.fps:g} fps, images "
        f"subscribed ({args.sink} sink), lockstep_wait_subscribers; {args.sim_seconds:g} s of sim time per run; "
        f"{machine()}"
    )
    print(f"{'run':>4} {'RTF':>7} {'CPU %':>6} {'RSS MB':>7} {'peak MB':>8}  images per camera (expected)")
    runs = []
    for k in range(args.repeat):
        r = run_child(
            [
                __file__,
                "--once",
                "--size",
                args.size,
                "--fps",
                str(args.fps),
                "--sim-seconds",
                str(args.sim_seconds),
                "--seed",
                str(args.seed),
                "--timeout",
                str(args.timeout),
                "--visibility",
                args.visibility,
                "--sink",
                args.sink,
            ],
            f"run {k}",
        )
        if r is None:
            return 1
        runs.append(r)
        print(
            f"{k + 1:>4} {r['rtf']:>7.2f} {r['cpu_percent']:>6.0f} {r['rss_mb']:>7.0f} {r['peak_rss_mb']:>8.0f}  "
            f"{r['images']} "
            f"({r['expected_per_camera']}); image sizes {r['image_sizes']}",
            flush=True,
        )
    print(f"median RTF {np.median([r['rtf'] for r in runs]):.2f} (load average after: {os.getloadavg()[0]:.2f})")
    return 0


if __name__ == "__main__":
    sys.exit(main())

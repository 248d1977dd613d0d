#!/usr/bin/env python3
"""Soak (docs/benchmarks.md): hours of sim time in lockstep with every sensor, checking what
users rely on over a long run.

    source scripts/env.sh && python bench/soak.py [--sim-seconds 7200] [--world mine] [--robots 1] [--out DIR]

Launches `<world>_world.launch realtime:=false paused:=true record:=<DIR>/soak.bag` (the simulator records
every sensor, command, odometry, thrust and /current message itself: every message is built and kept), then
steps --sim-seconds through /sim/step in 60 s calls with `hold`, UX_1 holding a slow turn (so it moves and its
sensors see changing geometry). Reports:
  * the simulator's RSS (VmRSS) after 600 s of sim time and at the end, and their ratio (target: within 5 %);
  * RTF: sim seconds per wall second of the stepping;
  * from the bag (read back with rosbags, streaming): per topic, the message count against rate x time (the
    rates of SPEC / docs/sensors.md), bag times strictly increasing, and the header stamps equal to them;
    non-finite values: none allowed in odometry, IMU, KVH, magnetometer, pressure, thrusts, /current and the
    DVL velocity with bottom lock (REP-117 +-inf ranges and the DVL's NaN velocity without lock are markers,
    not faults, and are counted apart).
Prints one table and writes DIR/soak.json. The bag is deleted at the end unless --keep-bag.
"""

import argparse
import json
import math
import sys
import time
from pathlib import Path

RATES = {  # [Hz of sim time], per robot topic suffix (and /current)
    "imu": 500,
    "imu/mag": 500,
    "kvh/imu_raw": 500,
    "pressure": 10,
    "dvl": 8,
    "dvl_water_track": 8,
    "dvl_sonar0": 8,
    "dvl_sonar1": 8,
    "dvl_sonar2": 8,
    "dvl_sonar3": 8,
    "m3/scan": 40,
    "m3/points": 40,
    "tritech_micron/scan": 25,
    "msis/msis_r": 25,
    "odom": 50,
    **{f"sls_{i}/points": 10 for i in range(4)},
    **{f"sls_{i}/scan": 10 for i in range(4)},
    **{f"thrusters/{i}/thrust": 50 for i in range(8)},
}
TURN = [-5.0, 0.0, 5.0, 0.0, 5.0, 0.0, -5.0, 0.0]  # [N] per thruster: a slow yaw (thesis allocation)


def rss_mb(pid):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    raise RuntimeError("no VmRSS")


def finite_fields(msg, path=""):
    """Yield (name, value) of every float field of a rosbags message, recursively."""
    import numpy as np

    for name in getattr(msg, "__dataclass_fields__", {}):
        v = getattr(msg, name)
        if isinstance(v, float):
            yield path + name, v
        elif isinstance(v, np.ndarray) and v.dtype.kind == "f":
            for x in v.ravel():
                yield path + name, float(x)
        elif hasattr(v, "__dataclass_fields__"):
            yield from finite_fields(v, path + name + ".")


def analyse(bag, robots, seconds):
    from rosbags.highlevel import AnyReader
    from rosbags.typesys import Stores, get_typestore

    stats = {}
    strict = ("odom", "imu", "imu/mag", "kvh/imu_raw", "pressure", "thrust", "/current")
    with AnyReader([Path(bag)], default_typestore=get_typestore(Stores.ROS1_NOETIC)) as reader:
        for conn, t, raw in reader.messages():
            s = stats.setdefault(
                conn.topic,
                {"count": 0, "last": -1, "monotonic": True, "stamp_mismatch": 0, "nonfinite": 0, "markers": 0},
            )
            s["count"] += 1
            if t <= s["last"]:
                s["monotonic"] = False
            s["last"] = t
            msg = reader.deserialize(raw, conn.msgtype)
            header = getattr(msg, "header", None)
            if header is not None and conn.msgtype != "unexmin/msg/Dvl" and "water_track" not in conn.topic:
                stamp = header.stamp.sec * 1_000_000_000 + header.stamp.nanosec
                if abs(stamp - t) > 1000:  # 1 us
                    s["stamp_mismatch"] += 1
            is_strict = any(conn.topic.endswith(k) for k in strict) or "/thrusters/" in conn.topic
            if conn.msgtype.endswith("PointCloud2"):
                continue  # binary float32 payload: x y z of echoes only (no markers)
            for name, v in finite_fields(msg):
                if math.isfinite(v):
                    continue
                dvl_marker = "dvl" in conn.topic and not getattr(msg, "bottom_lock", True)
                if is_strict or math.isnan(v) and not dvl_marker and "range" not in name:
                    s["nonfinite"] += 1
                else:
                    s["markers"] += 1
    rows = []
    for r in robots:
        for suffix, rate in RATES.items():
            topic = f"/{r}/{suffix}"
            s = stats.get(topic, {"count": 0})
            rows.append((topic, rate * seconds, s))
    rows.append(("/current", 10 * seconds, stats.get("/current", {"count": 0})))
    return rows, stats


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sim-seconds", type=float, default=7200.0)
    ap.add_argument("--world", default="mine")
    ap.add_argument("--robots", type=int, default=1)
    ap.add_argument("--out", default="soak_out")
    ap.add_argument("--keep-bag", action="store_true")
    args = ap.parse_args()
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    bag = out / "soak.bag"

    import rospy

    from unexmin import Simulation
    from unexmin.scripting.launcher import WorldProcess
    from unexmin.srv import Record

    world = WorldProcess(
        world=args.world, robots=args.robots, paused=True, log_dir=str(out / "logs"), extra_args=[f"record:={bag}"]
    )
    report = {"world": args.world, "robots": args.robots, "sim_seconds": args.sim_seconds}
    try:
        sim = Simulation(world=world, timeout=120.0, node_name="soak")
        pid = _pid_of(world.marker, "simulator_node")
        robots = rospy.get_param("/sim/robots")
        for r in robots:
            sim.robot(r).thrusts(TURN)
        chunk, done, rss = 60.0, 0.0, {}
        t0 = time.monotonic()
        last_time = -1.0
        while done < args.sim_seconds - 1e-9:
            step = min(chunk, args.sim_seconds - done)
            t = sim.run_for(step)
            if not t > last_time:
                report["sim_time_not_increasing"] = (last_time, t)
            last_time = t
            done += step
            if abs(done - 600.0) < 1e-6:
                rss["600"] = rss_mb(pid)
        wall = time.monotonic() - t0
        rss["end"] = rss_mb(pid)
        stop = rospy.ServiceProxy("/sim/record", Record)(path="")
        report.update(
            rtf=args.sim_seconds / wall,
            wall_s=wall,
            rss_mb=rss,
            record=stop.message,
            rss_ratio=rss["end"] / rss["600"] if "600" in rss else None,
        )
    finally:
        world.close()
    rows, _ = analyse(bag, robots, args.sim_seconds)
    report["topics"] = {t: {"expected": e, **s} for t, e, s in rows}
    bad = [
        t
        for t, e, s in rows
        if abs(s["count"] - e) > 1
        or not s.get("monotonic", False)
        or s.get("nonfinite", 0)
        or s.get("stamp_mismatch", 0)
    ]
    report["bad_topics"] = bad
    if not args.keep_bag:
        bag.unlink()
    (out / "soak.json").write_text(json.dumps(report, indent=2))
    print(
        f"{args.world}, {args.robots} robot(s), {args.sim_seconds:.0f} s of sim time in {report['wall_s']:.0f} s "
        f"(RTF {report['rtf']:.1f}); simulator RSS at 600 s {rss.get('600', float('nan')):.1f} MB, at the end "
        f"{rss['end']:.1f} MB (ratio {report['rss_ratio'] or float('nan'):.3f}); {report['record']}"
    )
    print(f"{'topic':<32}{'expected':>10}{'count':>10}{'monotonic':>10}{'nonfinite':>10}{'markers':>9}")
    for t, e, s in rows:
        print(
            f"{t:<32}{e:>10.0f}{s['count']:>10}{str(s.get('monotonic', '-')):>10}{s.get('nonfinite', 0):>10}"
            f"{s.get('markers', 0):>9}"
        )
    print("every topic as expected" if not bad else f"NOT as expected: {bad}")
    return 0 if not bad and (report["rss_ratio"] is None or report["rss_ratio"] <= 1.05) else 1


def _pid_of(marker, name):
    from unexmin.scripting.launcher import marked_processes

    for pid in marked_processes(marker):
        try:
            cmd = Path(f"/proc/{pid}/cmdline").read_bytes().split(b"\0")[0]
        except OSError:
            continue
        if cmd.endswith(name.encode()):
            return pid
    raise RuntimeError(f"no {name} process")


if __name__ == "__main__":
    sys.exit(main())

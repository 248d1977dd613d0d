#!/usr/bin/env python3
"""Real-time factor with UX_1's navigation sensors, their translators and a rosbag record of them.

    source scripts/env.sh && python bench/sensors_rtf.py [--window 10] [--pace 0 100 50 25]

Scenarios (tank, 1 robot, physics 500 Hz; IMU 500 Hz, pressure 10 Hz, DVL 8 Hz), each run free
(lockstep as fast as possible after /sim/unpause, --pace 0) and paced at real-time factors (the
simulator's realtime_factor), because a free-running simulator outruns any subscriber:
  idle      sensors simulated, nobody subscribed (the models' own cost)
  bag       DVL translator (rospy) + the simulator's own kvh/imu_raw + rosbag record of all 11 sensor
            topics (imu, imu/mag, kvh/imu_raw, pressure, dvl, dvl_sonar0..3, dvl_twist, dvl_water_track)
  rospy-kvh as bag, but kvh/imu_raw built by the rospy KVH translator (kvh_translator:=true) from
            kvh/raw, which is then recorded too (12 topics)
  bag-kvh   as bag, recording only the real robot's two topics (kvh/imu_raw, dvl_water_track)
For each: RTF = sim time advanced / wall time over --window s, the CPU used by the simulator, the
translators and the recorder, and per topic the fraction of the messages due in the window that reached
the bag (1.00 = kept up). Each run has its own ROS master.
"""

import argparse
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from xmlrpc.client import ServerProxy

import rosgraph

HERE = Path(__file__).resolve().parent
RATES = {"/UX_1/imu": 500, "/UX_1/imu/mag": 500, "/UX_1/kvh/raw": 500, "/UX_1/kvh/imu_raw": 500,
         "/UX_1/pressure": 10, "/UX_1/dvl": 8, "/UX_1/dvl_sonar0": 8, "/UX_1/dvl_sonar1": 8,
         "/UX_1/dvl_sonar2": 8, "/UX_1/dvl_sonar3": 8, "/UX_1/dvl_twist": 8, "/UX_1/dvl_water_track": 8}
ALL_BUT_RAW = [t for t in RATES if t != "/UX_1/kvh/raw"]  # kvh/raw exists only for the rospy translator
SCENARIOS = {"idle": dict(bag=False, kvh_translator=False),
             "bag": dict(bag=True, kvh_translator=False, topics=ALL_BUT_RAW),
             "rospy-kvh": dict(bag=True, kvh_translator=True, topics=list(RATES)),
             "bag-kvh": dict(bag=True, kvh_translator=False, topics=["/UX_1/kvh/imu_raw", "/UX_1/dvl_water_track"])}


def cpu_seconds(pid):
    """utime + stime of a process and its threads [s]."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def node_pids(caller, names):
    master = rosgraph.Master(caller)
    out = {}
    for n in names:
        try:
            out[n] = ServerProxy(master.lookupNode(n)).getPid(caller)[2]
        except Exception:  # noqa: BLE001 - the node is not part of this scenario
            pass
    return out


def measure(name, pace, window, workdir):
    from unexmin import Simulation
    from unexmin.launcher import free_port, wait_for

    cfg = SCENARIOS[name]
    port = free_port()
    os.environ["ROS_MASTER_URI"] = f"http://127.0.0.1:{port}"
    bag = str(Path(workdir) / f"{name}.bag")
    args = ["roslaunch", "--port", str(port), str(HERE / "sensors_bench.launch"), f"pace:={pace}",
            f"kvh_translator:={str(cfg['kvh_translator']).lower()}", f"bag:={bag if cfg['bag'] else ''}"]
    topics = cfg.get("topics", list(RATES))
    if "topics" in cfg:
        args.append("topics:=" + " ".join(topics))
    log = open(Path(workdir) / f"{name}.log", "w")
    proc = subprocess.Popen(args, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
    try:
        sim = Simulation(node_name="sensors_bench", timeout=60.0)
        nodes = ["/simulator", "/UX_1/dvl_translator"] + (["/UX_1/kvh_translator"] if cfg["kvh_translator"] else [])
        if cfg["bag"]:
            import rospy
            nodes.append("/bag_record")
            for topic in ("/UX_1/dvl_water_track", "/UX_1/kvh/imu_raw"):
                wait_for(lambda: any(t == topic for t, _ in rospy.get_published_topics()), 30.0, topic)
            # rosbag record subscribes to every topic once they exist: wait for its 12 subscriptions.
            master = rosgraph.Master("/sensors_bench")
            wait_for(lambda: sum("/bag_record" in subs for t, subs in master.getSystemState()[1]
                                 if t in topics) == len(topics), 30.0, "rosbag record to subscribe")
        pids = node_pids("/sensors_bench", nodes)
        cpu0 = {n: cpu_seconds(p) for n, p in pids.items()}
        sim_t0 = sim.time
        sim.unpause()
        t0 = time.perf_counter()
        time.sleep(window)  # a benchmark window, not a test wait
        sim.pause()
        wall = time.perf_counter() - t0
        sim_t1 = sim.time
        cpu = {n: (cpu_seconds(p) - cpu0[n]) / wall for n, p in pids.items()}
        result = {"scenario": name, "pace": pace, "rtf": (sim_t1 - sim_t0) / wall, "sim_seconds": sim_t1 - sim_t0,
                  "cpu": cpu, "delivered": {}}
        if cfg["bag"]:
            time.sleep(3.0)  # let the translators and the recorder drain their queues (benchmark only)
            os.killpg(proc.pid, signal.SIGINT)
            proc.wait(30)
            result["delivered"] = count_bag(bag, sim_t0, sim_t1, topics)
        return result
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGINT)
            try:
                proc.wait(30)
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
        log.close()


def count_bag(path, t0, t1, topics):
    """Fraction of the messages due in (t0, t1] of sim time that the bag holds, per topic."""
    from rosbags.highlevel import AnyReader

    counts = {t: 0 for t in topics}
    with AnyReader([Path(path)]) as reader:
        for conn, _, raw in reader.messages(connections=[c for c in reader.connections if c.topic in counts]):
            stamp = reader.deserialize(raw, conn.msgtype).header.stamp
            s = stamp.sec + 1e-9 * stamp.nanosec
            if t0 < s <= t1 + 1e-9:
                counts[conn.topic] += 1
    return {t: counts[t] / max(1, round(RATES[t] * (t1 - t0))) for t in topics}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--window", type=float, default=10.0, help="wall seconds of running per run")
    parser.add_argument("--pace", type=float, nargs="+", default=[0, 100, 50, 25],
                        help="real-time factors to pace at (0 = free-running lockstep)")
    parser.add_argument("--scenarios", nargs="+", choices=list(SCENARIOS), default=list(SCENARIOS))
    parser.add_argument("--one", nargs=2, metavar=("SCENARIO", "PACE"), help=argparse.SUPPRESS)
    parser.add_argument("--verbose", action="store_true", help="print every topic's delivered fraction")
    args = parser.parse_args()
    if args.one:
        with tempfile.TemporaryDirectory() as tmp:
            os.environ.setdefault("ROS_LOG_DIR", tmp)
            print(json.dumps(measure(args.one[0], float(args.one[1]), args.window, tmp)))
        return
    print(f"tank, 1 robot, physics 500 Hz, {args.window:.0f} s of wall time per run; delivered = the smallest "
          "fraction of the messages due that reached the bag, over the 500 Hz topics | the 8-10 Hz topics")
    print(f"{'scenario':>9} {'pace':>5} {'RTF':>6} {'delivered':>11}  CPU")
    for name in args.scenarios:
        for pace in (args.pace if SCENARIOS[name]["bag"] else [0]):
            out = subprocess.run([sys.executable, __file__, "--one", name, str(pace), "--window", str(args.window)],
                                 capture_output=True, text=True)
            if out.returncode != 0:
                print(f"{name} pace {pace}: failed\n{out.stderr[-2000:]}", flush=True)
                continue
            r = json.loads(out.stdout.strip().splitlines()[-1])
            cpu = ", ".join(f"{n.split('/')[-1]} {100 * c:.0f} %" for n, c in r["cpu"].items())
            d = r["delivered"]
            fast = min((f for t, f in d.items() if RATES[t] == 500), default=float("nan"))
            slow = min((f for t, f in d.items() if RATES[t] < 500), default=float("nan"))
            pace_txt = "free" if pace == 0 else f"{pace:.0f}"
            print(f"{name:>9} {pace_txt:>5} {r['rtf']:6.1f} {fast:5.2f}|{slow:4.2f}  {cpu}", flush=True)
            if args.verbose:
                for topic, frac in d.items():
                    print(f"{'':>12}{topic:<26} {frac:5.2f}")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Real-time factor with UX_1's navigation sensors, their translators and a record of all their topics.

    source scripts/env.sh && python bench/sensors_rtf.py [--window 10] [--pace 0 100 50 25 10] [--verbose]
    source scripts/env.sh && python bench/sensors_rtf.py --core     # the models alone, no ROS

Tank, 1 robot, physics 500 Hz; IMU 500 Hz (imu, imu/mag, kvh/imu_raw), pressure 10 Hz, DVL 8 Hz (dvl,
dvl_sonar0..3, dvl_twist) and the DVL translator's dvl_water_track: 11 topics. Every run has its own
ROS master (bench/sensors_bench.launch) and runs --window s of wall time after /sim/unpause, either
free (lockstep as fast as possible, --pace 0) or paced at a real-time factor (the simulator's
realtime_factor): a free-running simulator outruns any subscriber, so what matters is the fastest
pace at which the consumers still get everything. Sinks:
  none          nothing but the DVL translator subscribed (the sensors' own cost)
  cpp-sink      bench/topic_counter.cpp (built here with g++): a C++ subscriber with deep queues
                (100000) on the 11 topics; what any consumer that keeps up receives
  rosbag        `rosbag record` of the 11 topics (its subscriber queues are fixed at 100 messages)
  rospy-kvh     the rospy KVH translator builds kvh/imu_raw from kvh/raw (kvh_translator:=true);
                cpp-sink on the 11 topics + kvh/raw
Reported: RTF = sim time advanced / wall time; delivered = the smallest fraction, over the 500 Hz
topics | over the 8-10 Hz topics, of the messages stamped inside the window that reached the sink
(1.00 = kept up); CPU of each process over the window.
"""

import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from xmlrpc.client import ServerProxy

import rosgraph

HERE = Path(__file__).resolve().parent
RATES = {
    "/UX_1/imu": 500,
    "/UX_1/imu/mag": 500,
    "/UX_1/kvh/imu_raw": 500,
    "/UX_1/kvh/raw": 500,
    "/UX_1/pressure": 10,
    "/UX_1/dvl": 8,
    "/UX_1/dvl_sonar0": 8,
    "/UX_1/dvl_sonar1": 8,
    "/UX_1/dvl_sonar2": 8,
    "/UX_1/dvl_sonar3": 8,
    "/UX_1/dvl_twist": 8,
    "/UX_1/dvl_water_track": 8,
}
ELEVEN = [t for t in RATES if t != "/UX_1/kvh/raw"]  # kvh/raw is advertised only for the rospy translator
SINKS = {
    "none": dict(sink=None, kvh_translator=False, topics=[]),
    "cpp-sink": dict(sink="counter", kvh_translator=False, topics=ELEVEN),
    "rosbag": dict(sink="rosbag", kvh_translator=False, topics=ELEVEN),
    "rospy-kvh": dict(sink="counter", kvh_translator=True, topics=list(RATES)),
}
COUNTER_QUEUE = 100000


def build_counter(workdir):
    """Compile bench/topic_counter.cpp against the system's roscpp (no catkin target needed)."""
    exe = Path(workdir) / "topic_counter"
    cxx = shutil.which("g++")
    if not cxx:
        raise RuntimeError("g++ not found: the cpp-sink runs need it")
    subprocess.run(
        [
            cxx,
            "-O2",
            "-std=c++17",
            str(HERE / "topic_counter.cpp"),
            "-o",
            str(exe),
            "-lroscpp",
            "-lrosconsole",
            "-lroscpp_serialization",
            "-lrostime",
            "-ltopic_tools",
        ],
        check=True,
    )
    return exe


def cpu_seconds(pid):
    """utime + stime of a process and its threads [s]."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def node_pids(caller, names):
    master = rosgraph.Master(caller)
    return {n: ServerProxy(master.lookupNode(n)).getPid(caller)[2] for n in names}


def stop_bench(counter, proc, log):
    """Stop the topic counter (if still running) and the launched world's process group; close its log."""
    from unexmin.scripting.launcher import stop_process_group

    if counter and counter.poll() is None:
        counter.kill()
    stop_process_group(proc, 30.0)
    log.close()


def wait_for_sink(master, topics, is_sink, timeout, what="the sink to subscribe to every topic"):
    """Wait until a subscriber for which is_sink(subscriber node) holds is on every topic of `topics`."""
    from unexmin.scripting.launcher import wait_for

    def subscribed():
        state = master.getSystemState()[1]
        return sum(any(is_sink(n) for n in subs) for t, subs in state if t in topics) == len(topics)

    wait_for(subscribed, timeout, what)


def run_child(argv, label):
    """The JSON of the last stdout line of `python <argv>` (one measurement in a process of its own), or None
    (printed: `label`, failed and the end of its stderr) when it fails."""
    out = subprocess.run([sys.executable, *argv], capture_output=True, text=True)
    if out.returncode != 0:
        print(f"{label}: failed\n{out.stderr[-2000:]}", flush=True)
        return None
    return json.loads(out.stdout.strip().splitlines()[-1])


def counter_counts(counter, window_file, sim_t0, sim_t1):
    """{topic: messages} the running topic_counter received stamped in (sim_t0, sim_t1] [s]; stops it."""
    window_file.write_text(f"{sim_t0} {sim_t1}\n")
    counter.send_signal(signal.SIGINT)
    out = counter.communicate(timeout=30)[0]
    return dict((t, int(n)) for t, n in (line.split() for line in out.splitlines() if line.strip()))


def timed_window(sim, pids, window):
    """Run the paused simulator for `window` s of wall time: (sim time at start, at end [s], wall time [s],
    {node: CPU cores used}) of the processes `pids` ({node: pid})."""
    cpu0 = {n: cpu_seconds(p) for n, p in pids.items()}
    sim_t0 = sim.time
    sim.unpause()
    t0 = time.perf_counter()
    time.sleep(window)  # a benchmark window, not a test wait
    sim.pause()
    wall = time.perf_counter() - t0
    return sim_t0, sim.time, wall, {n: (cpu_seconds(p) - cpu0[n]) / wall for n, p in pids.items()}


def measure(sink_name, pace, window, workdir):
    from unexmin import Simulation
    from unexmin.scripting.launcher import free_port, wait_for

    cfg = SINKS[sink_name]
    topics = cfg["topics"]
    port = free_port()
    os.environ["ROS_MASTER_URI"] = f"http://127.0.0.1:{port}"
    bag = Path(workdir) / f"{sink_name}.bag"
    args = [
        "roslaunch",
        "--port",
        str(port),
        str(HERE / "sensors_bench.launch"),
        f"pace:={pace}",
        f"kvh_translator:={str(cfg['kvh_translator']).lower()}",
        f"bag:={bag if cfg['sink'] == 'rosbag' else ''}",
        "topics:=" + " ".join(topics),
    ]
    log = open(Path(workdir) / f"{sink_name}.log", "w")
    proc = subprocess.Popen(args, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
    counter = None
    window_file = Path(workdir) / "window"
    try:
        sim = Simulation(node_name="sensors_bench", timeout=60.0)
        import rospy

        for topic in ("/UX_1/dvl_water_track", "/UX_1/kvh/imu_raw"):
            wait_for(lambda topic=topic: any(t == topic for t, _ in rospy.get_published_topics()), 30.0, topic)
        nodes = ["/simulator", "/UX_1/dvl_translator"] + (["/UX_1/kvh_translator"] if cfg["kvh_translator"] else [])
        sink_node = None
        if cfg["sink"] == "counter":
            counter = subprocess.Popen(
                [str(build_counter(workdir)), str(window_file), str(COUNTER_QUEUE)] + topics,
                stdout=subprocess.PIPE,
                text=True,
            )
            sink_node = lambda n: n.startswith("/topic_counter")  # noqa: E731
        elif cfg["sink"] == "rosbag":
            nodes.append("/bag_record")
            sink_node = lambda n: n == "/bag_record"  # noqa: E731
        if sink_node:
            wait_for_sink(rosgraph.Master("/sensors_bench"), topics, sink_node, 30.0)
            time.sleep(1.0)  # connections are made after the master registration (benchmark set-up only)
        pids = node_pids("/sensors_bench", nodes)
        if counter:
            pids["topic_counter"] = counter.pid
        sim_t0, sim_t1, wall, cpu = timed_window(sim, pids, window)
        cpu = {n.split("/")[-1]: c for n, c in cpu.items()}
        result = {"sink": sink_name, "pace": pace, "rtf": (sim_t1 - sim_t0) / wall, "cpu": cpu, "delivered": {}}
        time.sleep(3.0)  # let the translators and the sink drain their queues (benchmark only)
        if counter:
            counts = counter_counts(counter, window_file, sim_t0, sim_t1)
            result["delivered"] = {t: counts.get(t, 0) / max(1, round(RATES[t] * (sim_t1 - sim_t0))) for t in topics}
        if cfg["sink"] == "rosbag":
            os.killpg(proc.pid, signal.SIGINT)
            proc.wait(30)
            result["delivered"] = count_bag(bag, sim_t0, sim_t1, topics)
        return result
    finally:
        stop_bench(counter, proc, log)


def count_bag(path, t0, t1, topics):
    """Fraction of the messages stamped in (t0, t1] of sim time that the bag holds, per topic."""
    from unexmin.bag import read_messages, stamp_to_sec

    counts = {t: 0 for t in topics}
    for topic, _, _, msg in read_messages(path, set(counts)):
        if t0 + 1e-9 < stamp_to_sec(msg.header.stamp) <= t1 + 1e-9:
            counts[topic] += 1
    return {t: counts[t] / max(1, round(RATES[t] * (t1 - t0))) for t in topics}


def core_cost():
    """Run the catkin-built bench/sensors_core_cost.cpp (devel/lib/unexmin/sensors_core_cost)."""
    repo, ws = HERE.parent, Path(os.environ.get("UNEXMIN_WS", HERE.parent.parent / "main_ws"))
    exe = ws / "devel" / "lib" / "unexmin" / "sensors_core_cost"
    if not exe.exists():
        sys.exit(f"{exe} is missing: build the workspace first (bash scripts/setup.sh)")
    with tempfile.TemporaryDirectory() as tmp:
        urdf = Path(tmp) / "ux1.urdf"
        xacro = shutil.which("xacro") or str(Path(sys.executable).parent / "xacro")
        urdf.write_text(
            subprocess.run(
                [xacro, str(repo / "urdf" / "ux1.urdf.xacro"), "name:=UX_1"], capture_output=True, text=True, check=True
            ).stdout
        )
        subprocess.run([str(exe), str(urdf), str(repo / "worlds" / "tank.world")], check=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--window", type=float, default=10.0, help="wall seconds per run")
    parser.add_argument(
        "--pace",
        type=float,
        nargs="+",
        default=[0, 100, 50, 25, 10],
        help="real-time factors to pace at (0 = free-running lockstep)",
    )
    parser.add_argument("--sinks", nargs="+", choices=list(SINKS), default=list(SINKS))
    parser.add_argument("--verbose", action="store_true", help="print every topic's delivered fraction")
    parser.add_argument("--core", action="store_true", help="only the models' cost in the core, without ROS")
    parser.add_argument("--one", nargs=2, metavar=("SINK", "PACE"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.core:
        core_cost()
        return
    if args.one:
        with tempfile.TemporaryDirectory() as tmp:
            os.environ.setdefault("ROS_LOG_DIR", tmp)
            print(json.dumps(measure(args.one[0], float(args.one[1]), args.window, tmp)))
        return
    print(f"tank, 1 robot, physics 500 Hz, {args.window:.0f} s of wall time per run")
    print(f"{'sink':>9} {'pace':>5} {'RTF':>6} {'delivered':>10}  CPU (share of one core)")
    for name in args.sinks:
        for pace in args.pace if SINKS[name]["sink"] else [0]:
            r = run_child([__file__, "--one", name, str(pace), "--window", str(args.window)], f"{name} pace {pace}")
            if r is None:
                continue
            d = r["delivered"]
            fast = min((f for t, f in d.items() if RATES[t] == 500), default=None)
            slow = min((f for t, f in d.items() if RATES[t] < 500), default=None)
            delivered = "-" if fast is None else f"{fast:.2f}|{slow:.2f}"
            cpu = ", ".join(f"{n} {100 * c:.0f} %" for n, c in r["cpu"].items())
            pace_txt = "free" if pace == 0 else f"{pace:.0f}"
            print(f"{name:>9} {pace_txt:>5} {r['rtf']:6.1f} {delivered:>10}  {cpu}", flush=True)
            if args.verbose:
                for topic, frac in d.items():
                    print(f"{'':>12}{topic:<26} {frac:5.2f}")


if __name__ == "__main__":
    main()

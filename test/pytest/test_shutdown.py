"""Clean shutdown (docs/reliability.md): SIGINT, as Ctrl-C sends it to the foreground process group,
at different moments of a roslaunch with record:=, of the mission (python -m unexmin.missions.tank, what
scripts/mission.sh runs after set-up), of the bag replay and of a Simulation script. Afterwards every process
the run started (its whole process tree, collected from /proc just before the signal, including roslaunch's
own session) has exited, and every bag it wrote opens with `rosbag info` without `rosbag reindex`.
Moments are conditions waited on (a file appears, a line is logged), never fixed sleeps."""

import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from unexmin.scripting.launcher import free_port, marked_processes, wait_for

REPO = Path(__file__).resolve().parents[2]
EXIT_TIMEOUT = 40.0  # [s] roslaunch: 15 s SIGINT grace per node, then SIGTERM


def tree(root):
    """PIDs of `root` and all its descendants now (from /proc)."""
    children = {}
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                ppid = int((d / "stat").read_text().rsplit(")", 1)[1].split()[1])
            except (OSError, IndexError, ValueError):
                continue
            children.setdefault(ppid, []).append(int(d.name))
    out, todo = [], [root]
    while todo:
        p = todo.pop()
        out.append(p)
        todo.extend(children.get(p, []))
    return out


def alive(pid):
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state != "Z"


def interrupt_and_check(runs, proc, bags=()):
    """SIGINT to `proc`'s process group (a terminal's Ctrl-C); every process of its tree gone (and every one
    that carries this run's UNEXMIN_RUN marker), bags indexed."""
    pids = tree(proc.pid)
    assert len(pids) > 1, "the run has not started its children yet"
    marker = runs.marker(proc)
    os.killpg(proc.pid, signal.SIGINT)
    proc.wait(EXIT_TIMEOUT)
    wait_for(lambda: not [p for p in pids if alive(p)], EXIT_TIMEOUT, "every child process to exit")
    # also those started after the snapshot (roslaunch starts its master and nodes in sessions of their own)
    wait_for(lambda: not marked_processes(marker), EXIT_TIMEOUT, "every process of the run to exit")
    for bag in bags:
        if Path(str(bag) + ".active").exists():
            pytest.fail(f"{bag} was left .active (not closed)")
        if Path(bag).exists():
            info = subprocess.run(
                ["rosbag", "info", "--yaml", "--key=indexed", str(bag)], capture_output=True, text=True, timeout=60
            )
            assert info.returncode == 0 and info.stdout.strip() == "True", info.stdout + info.stderr
    return pids


def test_roslaunch_with_record(tmp_path, runs):
    """roslaunch itself, running: (interrupted while still launching, roslaunch 1.15 can leave its master and
    nodes running; our launchers clean those up, test_mission_while_launching; docs/reliability.md)"""
    bag = tmp_path / "run.bag"
    port = free_port()
    proc, _ = runs.start(
        ["roslaunch", "--port", str(port), "unexmin", "tank_world.launch", "realtime:=false", f"record:={bag}"],
        tmp_path,
        ROS_MASTER_URI=f"http://127.0.0.1:{port}",
    )
    # lockstep running free, the simulator writing its bag
    wait_for(lambda: bag.exists() and bag.stat().st_size > 1_000_000, 120, "the simulator to write 1 MB of its bag")
    interrupt_and_check(runs, proc, [bag])
    assert bag.exists()


def test_mission(tmp_path, runs):
    out = tmp_path / "mission"
    proc, _ = runs.start([sys.executable, "-m", "unexmin.missions.tank", "--out", str(out)], tmp_path)
    wait_for(lambda: (out / "mission.bag.active").exists(), 120, "the mission's rosbag record to start")
    wait_for(lambda: "surge forward" in (tmp_path / "out.log").read_text(), 120, "the first leg to be driven")
    interrupt_and_check(runs, proc, [out / "mission.bag"])


def test_mission_while_launching(tmp_path, runs):
    out = tmp_path / "mission"
    proc, _ = runs.start([sys.executable, "-m", "unexmin.missions.tank", "--out", str(out)], tmp_path)
    wait_for(
        lambda: (out / "logs" / "roslaunch.log").exists() and len(tree(proc.pid)) > 3,
        60,
        "the mission to launch its world",
    )
    interrupt_and_check(runs, proc, [out / "mission.bag"])


def test_replay(tmp_path, runs):
    """The replay on the ROS back end (its world's roslaunch, master and nodes); the core back end runs no child."""
    proc, _ = runs.start(
        [
            sys.executable,
            "-m",
            "unexmin.replay",
            str(REPO / "worlds" / "bags" / "ux1_tank_perturbed.bag"),
            "--out",
            str(tmp_path / "replay"),
            "--pace",
            "1",
            "--backend",
            "ros",
        ],
        tmp_path,
    )
    wait_for(lambda: "%" in (tmp_path / "out.log").read_text() or len(tree(proc.pid)) > 6, 120, "the replay to run")
    interrupt_and_check(runs, proc)


SCRIPT = """
import sys
from unexmin import Simulation
sim = Simulation.launch("tank", log_dir=sys.argv[1])
print("connected", flush=True)
while True:
    sim.run_for(1.0)
"""


def test_simulation_script(tmp_path, runs):
    proc, _ = runs.start([sys.executable, "-c", SCRIPT, str(tmp_path / "log")], tmp_path)
    wait_for(lambda: "connected" in (tmp_path / "out.log").read_text(), 120, "the script to connect")
    interrupt_and_check(runs, proc)

"""Faults (docs/reliability.md): a killed allocator, translator or ESC driver is respawned by
roslaunch and its topic flows again; a killed simulator makes a Simulation script raise a clear error
within its timeout; a dead master makes every node exit. Processes are found by the UNEXMIN_RUN marker
every process of a run inherits; every wait is on a condition."""

import os
import signal
import socket
import sys
import time
from pathlib import Path

import pytest

from unexmin.scripting.launcher import ephemeral_ports, free_port, marked_processes, wait_for


def pids_of(marker, name):
    out = []
    for pid in marked_processes(marker):
        try:
            cmd = Path(f"/proc/{pid}/cmdline").read_bytes().split(b"\0")
        except OSError:
            continue
        if any(c.endswith(name.encode()) for c in cmd[:2]):
            out.append(pid)
    return out


def test_a_free_port_is_outside_the_ephemeral_range():
    """roslaunch's own server and every outgoing connection take ports from the kernel's ephemeral range, so a
    master port drawn from it can be handed out again before the master listens ("port already in use")."""
    low, high = ephemeral_ports()
    assert 1024 <= low < high <= 65535
    for _ in range(100):
        port = free_port()
        assert not low <= port <= high, (port, low, high)
        with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
            s.bind(("127.0.0.1", port))  # and free
    drawn = {free_port((20000, 60999)) for _ in range(100)}  # another machine's range
    assert all(10000 <= p < 20000 or 61000 <= p <= 65535 for p in drawn), sorted(drawn)
    with pytest.raises(RuntimeError, match="ephemeral range 1024-65000"):
        free_port((1024, 65000))


def world(runs, tmp, *args):
    port = free_port()
    uri = f"http://127.0.0.1:{port}"
    proc, marker = runs.start(
        ["roslaunch", "--port", str(port), "unexmin", "tank_world.launch", *args], tmp, ROS_MASTER_URI=uri
    )
    return proc, marker, uri


@pytest.mark.parametrize(
    "node,args", [("thruster_allocator", ()), ("kvh_translator", ("kvh_translator:=true",)), ("esc_driver", ())]
)
def test_killed_node_is_respawned(tmp_path, runs, node, args):
    proc, marker, uri = world(runs, tmp_path, "realtime:=true", *args)
    if node == "esc_driver":  # not in the world launch: its own control.launch on the world's master
        (tmp_path / "esc").mkdir()
        _, marker = runs.start(
            ["roslaunch", "unexmin", "control.launch", "robot:=UX_1", "allocator:=false", "esc_driver:=true"],
            tmp_path / "esc",
            ROS_MASTER_URI=uri,
        )
    first = wait_for(lambda: pids_of(marker, node), 90, f"{node} to start")
    os.kill(first[0], signal.SIGKILL)
    again = wait_for(lambda: [p for p in pids_of(marker, node) if p not in first], 60, f"{node} to be respawned")
    assert again
    # registered with the master again
    import rosgraph

    master = rosgraph.Master("/faults_test", master_uri=uri)
    wait_for(
        lambda: any(node in n for _, nodes in master.getSystemState()[0] for n in nodes), 60, f"{node} to publish again"
    )


SCRIPT = """
import sys, time
from unexmin import Simulation
sim = Simulation.launch("tank", log_dir=sys.argv[1], timeout=30.0)
print("connected", flush=True)
t0 = None
try:
    while True:
        sim.run_for(0.2)
        if t0 is None:
            print("stepping", flush=True)
            t0 = 0
except RuntimeError as e:
    print("ERROR:", e, flush=True)
    sys.exit(3)
"""


def test_killed_simulator_gives_a_clear_error(tmp_path, runs):
    proc, marker = runs.start([sys.executable, "-c", SCRIPT, str(tmp_path / "log")], tmp_path)
    log = tmp_path / "out.log"
    wait_for(lambda: "stepping" in log.read_text(), 120, "the script to step")
    sim = wait_for(lambda: pids_of(marker, "simulator_node"), 30, "the simulator process")
    t = time.monotonic()
    os.kill(sim[0], signal.SIGKILL)
    wait_for(lambda: "ERROR:" in log.read_text(), 30.0, "the script's error (within its 30 s timeout)")
    assert time.monotonic() - t < 30.0
    assert proc.wait(90) == 3, log.read_text()[-2000:]  # then it stops its world and exits
    text = log.read_text()
    assert "ERROR: /sim/step failed" in text and ("simulator world exited" in text or "not answering" in text), text
    wait_for(lambda: not marked_processes(marker), 60, "every process of the run to exit")


def test_dead_master_ends_every_node(tmp_path, runs):
    proc, marker, uri = world(runs, tmp_path, "realtime:=true")
    wait_for(lambda: pids_of(marker, "simulator_node") and pids_of(marker, "thruster_allocator"), 90, "the nodes")
    master = wait_for(lambda: pids_of(marker, "rosmaster"), 30, "the master")
    os.kill(master[0], signal.SIGKILL)
    wait_for(lambda: not marked_processes(marker), 90, "every node to exit after the master died")

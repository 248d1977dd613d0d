"""Safe by default (docs/reliability.md): with the project's environment (scripts/env.sh or the launcher: ROS_IP
127.0.0.1 unless the user sets ROS_IP/ROS_HOSTNAME), a world's master and every node listen on the loopback
only, except what roscpp cannot do: the XML-RPC server of a C++ node (xmlrpcpp) binds every interface
whatever ROS_IP says. Checked on the listening sockets of every process of a running world."""

import os
import re
import subprocess
from urllib.parse import urlparse

from unexmin.scripting.launcher import free_port, marked_processes, stop_process_group, wait_for


def listening(pids):
    """[(address, port, pid)] of the TCP sockets the processes `pids` listen on (from ss)."""
    out = subprocess.run(["ss", "-ltnpH"], capture_output=True, text=True, check=True).stdout
    found = []
    for line in out.splitlines():
        fields = line.split()
        m = re.search(r"pid=(\d+),", line)
        if m and int(m.group(1)) in pids:
            addr, port = fields[3].rsplit(":", 1)
            found.append((addr, int(port), int(m.group(1))))
    return found


def test_world_listens_on_loopback(tmp_path):
    import rosgraph

    port = free_port()
    marker = f"loopback-test-{os.getpid()}"
    env = {k: v for k, v in os.environ.items() if k not in ("ROS_IP", "ROS_HOSTNAME")}
    env.update(
        ROS_IP="127.0.0.1", ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOME=str(tmp_path), UNEXMIN_RUN=marker
    )
    proc = subprocess.Popen(
        ["roslaunch", "--port", str(port), "unexmin", "tank_world.launch"],
        env=env,
        stdout=open(tmp_path / "roslaunch.out", "w"),
        stderr=subprocess.STDOUT,
        start_new_session=True,
    )
    try:
        master = rosgraph.Master("/loopback_test", master_uri=env["ROS_MASTER_URI"])

        def nodes():
            try:
                state = master.getSystemState()
            except Exception:
                return set()
            return {n for group in state for _, ns in group for n in ns}

        wanted = {"/simulator", "/rosout", "/UX_1/thruster_allocator", "/UX_1/robot_state_publisher"}
        wait_for(lambda: wanted <= nodes(), 90, "the nodes to register")
        names = nodes()
        xmlrpc = {urlparse(master.lookupNode(n)).port: n for n in names}
        cpp = {"/simulator", "/rosout", "/UX_1/robot_state_publisher"}  # roscpp nodes
        sockets = listening(set(marked_processes(marker)))
        assert len(sockets) >= 2 * len(wanted), sockets
        wide = [(a, p) for a, p, _ in sockets if a not in ("127.0.0.1", "[::ffff:127.0.0.1]", "[::1]")]
        for addr, p in wide:
            assert xmlrpc.get(p) in cpp, f"{addr}:{p} listens beyond the loopback and is not a roscpp XML-RPC server"
        assert any(p == port and a == "127.0.0.1" for a, p, _ in sockets)  # the master
    finally:
        stop_process_group(proc, 15.0, marker)

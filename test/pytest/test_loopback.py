"""Safe by default (docs/reliability.md): a world started as the README says (scripts/env.sh, then roslaunch) or by
the launcher listens on 127.0.0.1 only, every process of it (roslaunch, the master, rosout, robot_state_publisher,
the simulator, the mapper, the rospy nodes), TCP and UDP, with no exemption. The network-namespace test shows it
from another host: the simulator's XML-RPC and TCPROS ports cannot be reached over a link by default, and can when
ROS_IP names the link's address (and then nothing of the world listens anywhere else)."""

import json
import os
import re
import subprocess
import sys
from contextlib import contextmanager
from pathlib import Path

import pytest

from unexmin.scripting.launcher import WorldProcess, free_port, marked_processes, stop_process_group, wait_for

REPO = Path(__file__).resolve().parents[2]
# Both ends of the test's veth pair: link-local addresses on a link that exists only between the test's own two
# network namespaces (nothing of it is seen from the machine's namespace).
SIM_ADDRESS, PEER_ADDRESS = "169.254.73.1", "169.254.73.2"
ENV_SH = 'source "$UNEXMIN_REPO/scripts/env.sh" && exec roslaunch "$@"'
# The nodes the checked worlds start (the tank with the mapper and a rospy translator on).
WORLD_ARGS = ["unexmin", "tank_world.launch", "mapping:=true", "kvh_translator:=true"]
NODES = {
    "/simulator",
    "/rosout",
    "/mapper",
    "/mesh_marker",
    "/UX_1/thruster_allocator",
    "/UX_1/kvh_translator",
    "/UX_1/robot_state_publisher",
}


def listening(pids, netns=None):
    """[(address, port, pid, protocol)] of the TCP and UDP sockets the processes `pids` listen on (from ss, run in
    the network namespace `netns` when given)."""
    command = ["ss", "-ltunpH"] if netns is None else ["ip", "netns", "exec", netns, "ss", "-ltunpH"]
    out = subprocess.run(command, capture_output=True, text=True, check=True, timeout=30).stdout
    found = []
    for line in out.splitlines():
        fields = line.split()
        for pid in re.findall(r"pid=(\d+),", line):
            if int(pid) in pids:
                address, port = fields[4].rsplit(":", 1)
                found.append((address.strip("[]"), int(port), int(pid), fields[0]))
    return found


def clean_environment(**extra):
    """os.environ without any choice of address or preload (as a fresh shell), plus `extra`."""
    env = {
        k: v
        for k, v in os.environ.items()
        if k not in ("ROS_IP", "ROS_HOSTNAME", "ROS_MASTER_URI", "LD_PRELOAD", "UNEXMIN_RUN")
    }
    wrappers = str(REPO / "scripts" / "bind_shim")  # scripts/env.sh puts it first on PATH
    env["PATH"] = ":".join(f for f in env["PATH"].split(":") if f != wrappers)
    env["UNEXMIN_REPO"] = str(REPO)
    env.update(extra)
    return env


def node_pids(master, names):
    """{node name: pid} of the nodes `names`, asked of each node's own XML-RPC server."""
    from xmlrpc.client import ServerProxy

    return {n: ServerProxy(master.lookupNode(n)).getPid("/loopback_test")[2] for n in names}


def registered(master):
    try:
        state = master.getSystemState()
    except Exception:  # the master is not up yet
        return set()
    return {n for group in state for _, ns in group for n in ns}


def check_world_listens_on(address, master, port, marker):
    """Every socket every process of the world `marker` listens on is on `address`; each node of NODES and the
    master listen there (its XML-RPC server, and its TCPROS server for every node but the mesh marker)."""
    sockets = listening(set(marked_processes(marker)))
    wide = [s for s in sockets if s[0] != address]
    assert not wide, f"listening beyond {address} (address, port, pid, protocol): {wide}"
    pids = node_pids(master, NODES)
    per_pid = {pid: {p for a, p, q, _ in sockets if q == pid} for pid in pids.values()}
    for name, pid in pids.items():
        assert len(per_pid[pid]) >= (1 if name == "/mesh_marker" else 2), f"{name} (pid {pid}): {per_pid[pid]}"
    assert any(p == port for _, p, _, _ in sockets), f"the master's port {port} is not among {sockets}"


def test_world_started_as_the_readme_says_listens_on_loopback_only(tmp_path):
    port = free_port()
    marker = f"loopback-test-{os.getpid()}"
    env = clean_environment(ROS_HOME=str(tmp_path), UNEXMIN_RUN=marker)
    proc = subprocess.Popen(
        ["bash", "-c", ENV_SH, "roslaunch", "--port", str(port), *WORLD_ARGS],
        env=env,
        stdout=open(tmp_path / "roslaunch.out", "w"),
        stderr=subprocess.STDOUT,
        start_new_session=True,
    )
    try:
        import rosgraph

        master = rosgraph.Master("/loopback_test", master_uri=f"http://127.0.0.1:{port}")
        wait_for(lambda: NODES <= registered(master) or proc.poll() is not None, 120, "the nodes to register")
        assert proc.poll() is None, (tmp_path / "roslaunch.out").read_text()[-3000:]
        check_world_listens_on("127.0.0.1", master, port, marker)
    finally:
        stop_process_group(proc, 15.0, marker)


def test_world_started_by_the_launcher_listens_on_loopback_only(tmp_path, monkeypatch):
    for name in ("ROS_IP", "ROS_HOSTNAME", "LD_PRELOAD"):  # the launcher alone, without scripts/env.sh's choices
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setenv("PATH", clean_environment()["PATH"])
    monkeypatch.setenv("ROS_MASTER_URI", "http://127.0.0.1:11311")  # WorldProcess changes them: restored after
    monkeypatch.setenv("ROS_HOME", str(tmp_path))
    world = WorldProcess("tank", realtime=True, paused=False, log_dir=str(tmp_path / "log"), extra_args=WORLD_ARGS[2:])
    try:
        import rosgraph

        master = rosgraph.Master("/loopback_test", master_uri=world.uri)
        wait_for(lambda: NODES <= registered(master) or not world.alive(), 120, "the nodes to register")
        assert world.alive(), Path(world.log_path).read_text()[-3000:]
        check_world_listens_on("127.0.0.1", master, world.port, world.marker)
    finally:
        world.close()


# ---------------------------------------------------------------- seen from another host (network namespaces)


@contextmanager
def two_hosts():
    """Two network namespaces (the simulator's host, a peer) joined by a veth pair with SIM_ADDRESS and
    PEER_ADDRESS; deleted on the way out, whatever happened."""
    if os.geteuid() != 0:
        pytest.skip("network namespaces need root")
    names = (f"unexmin-sim-{os.getpid()}", f"unexmin-peer-{os.getpid()}")

    def ip(*args):
        run = subprocess.run(["ip", *args], capture_output=True, text=True, timeout=30)
        assert run.returncode == 0, f"ip {' '.join(args)}: {run.stderr.strip()}"

    try:
        for name in names:
            ip("netns", "add", name)
        ip("link", "add", "ux-sim", "netns", names[0], "type", "veth", "peer", "name", "ux-peer", "netns", names[1])
        for name, device, address in zip(names, ("ux-sim", "ux-peer"), (SIM_ADDRESS, PEER_ADDRESS)):
            ip("-n", name, "addr", "add", f"{address}/30", "dev", device)
            ip("-n", name, "link", "set", device, "up")
            ip("-n", name, "link", "set", "lo", "up")
        yield names
    finally:
        for name in names:  # deleting a namespace deletes its end of the veth pair, and the pair with it
            subprocess.run(["ip", "netns", "delete", name], capture_output=True, timeout=30)


def in_namespace(netns, code, *args, timeout=30):
    """Run the Python `code` (argv[1:] = args) in the network namespace `netns`; its stdout parsed as JSON."""
    run = subprocess.run(
        ["ip", "netns", "exec", netns, sys.executable, "-c", code, *map(str, args)],
        capture_output=True,
        text=True,
        timeout=timeout,
        env=clean_environment(),
    )
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout)


# In the simulator's namespace: the simulator's pid, XML-RPC URI and one topic it publishes, once it has registered
# (null before).
SIMULATOR = """
import json, sys, rosgraph
from xmlrpc.client import ServerProxy
master = rosgraph.Master("/loopback_probe", master_uri=sys.argv[1])
try:
    uri = master.lookupNode("/simulator")
    topics = [t for t, nodes in master.getSystemState()[0] if "/simulator" in nodes]
    pid = ServerProxy(uri).getPid("/loopback_probe")[2]
except Exception:
    print("null")
else:
    print(json.dumps({"uri": uri, "topic": topics[0] if topics else None, "pid": pid}))
"""

# In the peer's namespace: for each "port" of argv[2:] at address argv[1]: "refused" (the host answered, nothing
# listens there), "timeout", or what the server there says: the pid an XML-RPC server gives to getPid, the type a
# TCPROS publisher gives for topic argv[2] (argv[3] the XML-RPC port, argv[4] the TCPROS port).
PEER = """
import json, socket, struct, sys
from xmlrpc.client import ServerProxy
address, topic, xmlrpc, tcpros = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
def reach(port):
    try:
        socket.create_connection((address, port), timeout=5).close()
        return "open"
    except ConnectionRefusedError:
        return "refused"
    except OSError as e:
        return type(e).__name__
result = {"xmlrpc": reach(xmlrpc), "tcpros": reach(tcpros), "master": reach(11311)}
if result["xmlrpc"] == "open":
    result["pid"] = ServerProxy(f"http://{address}:{xmlrpc}/").getPid("/loopback_peer")[2]
if result["tcpros"] == "open":
    fields = [b"callerid=/loopback_peer", b"topic=" + topic.encode(), b"md5sum=*", b"type=*", b"tcp_nodelay=1"]
    header = b"".join(struct.pack("<I", len(f)) + f for f in fields)
    with socket.create_connection((address, tcpros), timeout=5) as s:
        s.sendall(struct.pack("<I", len(header)) + header)
        data = b""
        while len(data) < 4 or len(data) < 4 + struct.unpack("<I", data[:4])[0]:
            chunk = s.recv(65536)
            if not chunk:
                break
            data += chunk
    body, reply = data[4:4 + struct.unpack("<I", data[:4])[0]], {}
    while body:
        n = struct.unpack("<I", body[:4])[0]
        key, _, value = body[4:4 + n].decode().partition("=")
        reply[key], body = value, body[4 + n:]
    result["type"] = reply.get("type")
print(json.dumps(result))
"""


def simulator_seen_from_the_peer(hosts, ros_ip, tmp_path):
    """Start the tank world in the simulator's namespace as the README says (env.sh, roslaunch; ROS_IP=`ros_ip`
    when given), and return (what the peer sees of the simulator's ports, the simulator's sockets, every
    listening socket of the world)."""
    sim, peer = hosts
    marker = f"loopback-netns-{os.getpid()}-{ros_ip}"
    env = clean_environment(ROS_HOME=str(tmp_path), UNEXMIN_RUN=marker, **({"ROS_IP": ros_ip} if ros_ip else {}))
    # A fresh namespace: the default master port 11311 is free, ROS_MASTER_URI is env.sh's default.
    proc = subprocess.Popen(
        ["ip", "netns", "exec", sim, "bash", "-c", ENV_SH, "roslaunch", "unexmin", "tank_world.launch"],
        env=env,
        stdout=open(tmp_path / "roslaunch.out", "w"),
        stderr=subprocess.STDOUT,
        start_new_session=True,
    )
    try:
        master_uri = f"http://{ros_ip or '127.0.0.1'}:11311"
        simulator = wait_for(
            lambda: proc.poll() is not None or in_namespace(sim, SIMULATOR, master_uri),
            120,
            "the simulator to register",
            poll=0.5,
        )
        assert proc.poll() is None, (tmp_path / "roslaunch.out").read_text()[-3000:]
        pid = simulator["pid"]
        own = listening({pid}, sim)
        tcp = {p for _, p, _, protocol in own if protocol == "tcp"}
        xmlrpc = int(simulator["uri"].rstrip("/").rsplit(":", 1)[1])
        assert xmlrpc in tcp and len(tcp) == 2, f"the simulator (pid {pid}) listens on {own}"
        tcpros = (tcp - {xmlrpc}).pop()
        seen = in_namespace(peer, PEER, SIM_ADDRESS, simulator["topic"], xmlrpc, tcpros)
        return seen, pid, own, listening(set(marked_processes(marker)), sim)
    finally:
        stop_process_group(proc, 15.0, marker)


def test_simulator_unreachable_from_another_host_by_default_reachable_on_the_address_asked(tmp_path):
    with two_hosts() as hosts:
        (tmp_path / "default").mkdir()
        seen, pid, own, _ = simulator_seen_from_the_peer(hosts, None, tmp_path / "default")
        # "refused", not a time-out: the peer's packets reached the simulator's host, and nothing listens there.
        assert seen == {"xmlrpc": "refused", "tcpros": "refused", "master": "refused"}, (seen, own)
        assert {a for a, _, _, _ in own} == {"127.0.0.1"}, own

        (tmp_path / "asked").mkdir()
        seen, pid, own, world = simulator_seen_from_the_peer(hosts, SIM_ADDRESS, tmp_path / "asked")
        assert seen["xmlrpc"] == seen["tcpros"] == seen["master"] == "open", (seen, own)
        assert seen["pid"] == pid, seen  # the simulator's own XML-RPC server answered across the link
        assert seen["type"], seen  # and its TCPROS server gave a connection header for its topic
        wide = [s for s in world if s[0] != SIM_ADDRESS]
        assert not wide, f"with ROS_IP={SIM_ADDRESS}, listening elsewhere (address, port, pid, protocol): {wide}"

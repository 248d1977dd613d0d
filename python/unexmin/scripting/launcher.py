"""Start and stop a headless simulator world (roslaunch) on a private ROS master port."""

import atexit
import os
import random
import re
import signal
import socket
import subprocess
import time
import uuid
from pathlib import Path

from unexmin.bind_shim import advertised_host, ros_environment


def ephemeral_ports(path="/proc/sys/net/ipv4/ip_local_port_range"):
    """The kernel's ephemeral port range (low, high): the ports it hands to bind(port 0) and to outgoing
    connections. (32768, 60999), Linux's default, when `path` cannot be read."""
    try:
        low, high = (int(v) for v in Path(path).read_text().split())
        return low, high
    except (OSError, ValueError):
        return 32768, 60999


# Ports must differ between processes, forked ones too, and no result depends on which is drawn: the
# system's generator, not a seeded one.
_port_choice = random.SystemRandom()


def free_port(ephemeral=None):
    """A TCP port on the loopback that nothing listens on now, outside the kernel's ephemeral range
    (`ephemeral`, default ephemeral_ports()). A port from bind(port 0) would be free only until the kernel
    hands it out again: to roslaunch's own server, say, started before the master asked to listen on it."""
    low, high = ephemeral or ephemeral_ports()
    candidates = [r for r in ((10000, min(low, 30000)), (max(high + 1, 1024), 65536)) if r[1] - r[0] >= 1000]
    if not candidates:
        raise RuntimeError(f"no port outside the ephemeral range {low}-{high} to choose from")
    for _ in range(200):
        start, stop = _port_choice.choice(candidates)
        port = _port_choice.randrange(start, stop)
        with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
            try:
                s.bind(("127.0.0.1", port))
            except OSError:
                continue
            return port
    raise RuntimeError(f"no free port outside the ephemeral range {low}-{high} after 200 tries")


def private_master_env(port, home, **extra):
    """This process's environment for a child of a private ROS master on 127.0.0.1:`port`: ROS_IP on the
    loopback, ROS logs in <home>/log, ROS_HOME = home, and the variables `extra`."""
    return dict(
        os.environ,
        ROS_MASTER_URI=f"http://127.0.0.1:{port}",
        ROS_IP="127.0.0.1",
        ROS_LOG_DIR=str(Path(home) / "log"),
        ROS_HOME=str(home),
        **extra,
    )


def start_private_master(port, home):
    """A rosmaster --core of its own on 127.0.0.1:`port` (a process group of its own, output discarded), online
    when this returns: (the process, private_master_env(port, home)). Stop it with stop_process_group."""
    import rosgraph

    env = private_master_env(port, home)
    proc = subprocess.Popen(
        ["rosmaster", "--core", "-p", str(port)],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    try:
        master = rosgraph.Master("/unexmin_probe", master_uri=env["ROS_MASTER_URI"])
        wait_for(master.is_online, 30.0, f"the private rosmaster on port {port}")
    except BaseException:
        stop_process_group(proc)
        raise
    return proc, env


def _process_table():
    """{pid: (parent pid, start time [clock ticks since boot])} of the live processes (Linux /proc)."""
    table = {}
    for entry in os.scandir("/proc"):
        if not entry.name.isdigit():
            continue
        try:
            with open(f"/proc/{entry.name}/stat") as f:
                stat = f.read()
        except OSError:
            continue
        fields = stat[stat.rindex(")") + 2 :].split()  # after "pid (comm) ": state ppid pgrp ...
        if fields[0] not in "ZX":
            table[int(entry.name)] = (int(fields[1]), int(fields[19]))
    return table


def descendants(pid):
    """{pid: start time} of the live processes below `pid` (children, grandchildren, ...)."""
    table = _process_table()
    found, frontier = {}, {pid}
    while frontier:
        frontier = {p for p, (ppid, _) in table.items() if ppid in frontier and p not in found}
        found.update({p: table[p][1] for p in frontier})
    return found


def marked_processes(marker):
    """PIDs of the live processes whose environment's UNEXMIN_RUN (markers joined by ':', a nested run adds
    its own) holds `marker` (readable environments only: our own processes)."""
    pids = []
    for d in os.listdir("/proc"):
        if not d.isdigit() or int(d) == os.getpid():
            continue
        try:
            with open(f"/proc/{d}/environ", "rb") as f:
                env = f.read().split(b"\0")
            with open(f"/proc/{d}/stat") as f:
                zombie = f.read().rsplit(")", 1)[1].split()[0] == "Z"
        except OSError:
            continue
        runs = [
            e[len(b"UNEXMIN_RUN=") :].decode(errors="replace").split(":") for e in env if e.startswith(b"UNEXMIN_RUN=")
        ]
        if runs and marker in runs[0] and not zombie:
            pids.append(int(d))
    return pids


def stop_process_group(proc, timeout=15.0, marker=None):
    """Stop `proc` (started with start_new_session=True) and everything it started.

    SIGINT to its process group, as Ctrl-C: ROS nodes close their bags and save their maps; SIGKILL
    if it has not exited after `timeout` s. Then SIGKILL to any process it had started that is still
    alive: roslaunch starts each node in a session of its own, and a rospy node interrupted while it
    starts can hang instead of exiting (roslaunch would wait 15 s for it, then leave it behind). With
    `marker` (the UNEXMIN_RUN value given in `proc`'s environment, which every descendant inherits), any
    process of the run still left (e.g. re-parented to init when roslaunch exited early) is sent SIGINT,
    then SIGTERM and SIGKILL after `timeout` s each."""
    if proc.poll() is None:
        below = descendants(proc.pid)
        os.killpg(proc.pid, signal.SIGINT)
        try:
            proc.wait(timeout)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()

        # The SIGINT reached them too: give them `timeout` s to finish (a rosbag recorder indexes and closes
        # its bag after its parent script has exited), then SIGKILL what is still there.
        def alive():
            table = _process_table()
            return [p for p, start in below.items() if p in table and table[p][1] == start]  # not a reused pid

        deadline = time.monotonic() + timeout
        while alive() and time.monotonic() < deadline:
            time.sleep(0.05)
        for pid in alive():
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
    if marker is None:
        return
    for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGKILL):
        left = marked_processes(marker)
        if not left:
            return
        for pid in left:
            try:
                os.kill(pid, sig)
            except ProcessLookupError:
                pass
        deadline = time.monotonic() + timeout
        while marked_processes(marker) and time.monotonic() < deadline:
            time.sleep(0.05)


def wait_for(condition, timeout, what, poll=0.05):
    """Poll `condition()` until it is truthy; raise TimeoutError naming `what` after `timeout` s."""
    deadline = time.monotonic() + timeout
    while True:
        value = condition()
        if value:
            return value
        if time.monotonic() > deadline:
            raise TimeoutError(f"timed out after {timeout:.0f} s waiting for {what}")
        time.sleep(poll)


class WorldProcess:
    """``roslaunch unexmin <world>_world.launch`` as a child process with its own master.

    The ROS_MASTER_URI of this process is set to the new master, so rospy nodes created
    afterwards in this process talk to it. The world is stopped by close(), and at the latest when
    this Python process exits (a roslaunch in its own session would otherwise outlive it).
    """

    def __init__(
        self,
        world="tank",
        robots=1,
        seed=0,
        realtime=False,
        paused=True,
        port=None,
        log_dir=None,
        extra_args=(),
        launch_file=None,
    ):
        """world: `<world>_world.launch` of the package, with robots, seed, realtime, paused and
        extra_args ("name:=value") as its arguments; launch_file: a launch file to run instead (no
        arguments); port: the master's port (default: a free one); log_dir: roslaunch.log and the
        nodes' logs (ROS_LOG_DIR)."""
        self.port = port or free_port()
        # Loopback unless the user chose an address (ROS_IP or ROS_HOSTNAME), every process of the world and those
        # this process starts later kept on it by the bind shim: docs/reliability.md "Safe by default".
        ros_environment(os.environ)
        self.uri = f"http://{advertised_host()}:{self.port}"
        os.environ["ROS_MASTER_URI"] = self.uri
        if log_dir:
            os.makedirs(log_dir, exist_ok=True)
            os.environ["ROS_LOG_DIR"] = log_dir
        if launch_file:
            args = ["roslaunch", "--port", str(self.port), str(launch_file)]
        else:
            args = [
                "roslaunch",
                "--port",
                str(self.port),
                "unexmin",
                f"{world}_world.launch",
                f"robots:={robots}",
                f"seed:={seed}",
                f"realtime:={str(realtime).lower()}",
                f"paused:={str(paused).lower()}",
                *extra_args,
            ]
        self.log_path = os.path.join(log_dir, "roslaunch.log") if log_dir else None
        log = open(self.log_path, "w") if log_dir else subprocess.DEVNULL
        # Every process of this world inherits the marker: close() finds any that roslaunch left behind.
        self.marker = uuid.uuid4().hex
        outer = os.environ.get("UNEXMIN_RUN")
        env = dict(os.environ, UNEXMIN_RUN=f"{outer}:{self.marker}" if outer else self.marker)
        self.proc = subprocess.Popen(args, stdout=log, stderr=subprocess.STDOUT, start_new_session=True, env=env)
        self._log = log
        atexit.register(self.close)

    def alive(self):
        return self.proc.poll() is None

    def _launch_processes(self, master):
        """(running, dead) process names of this world's roslaunch, e.g. "UX_1/thruster_allocator-4"."""
        from xmlrpc.client import ServerProxy

        running, dead = [], []
        for uri in (master.getParam("/roslaunch/uris") or {}).values():
            code, _, (up, down) = ServerProxy(uri).list_processes()
            if code == 1:
                running += [name for name, _ in up]
                dead += [name for name, _ in down]
        return running, dead

    def simulator_died(self, master):
        """True when roslaunch reports the simulator node dead (False while that cannot be asked yet)."""
        try:
            _, dead = self._launch_processes(master)
        except Exception:  # master or roslaunch not answering (yet, or any more)
            return False
        return any(re.match(r"simulator-\d+$", name) for name in dead)

    def nodes_up(self, master):
        """True when every node roslaunch has started is known to the master (`master`: a
        rosgraph.Master of this world), i.e. has finished its init_node."""
        running, _ = self._launch_processes(master)
        # node processes are named "<ns>/<name>-<n>"; the master is "master"
        active = ["/" + m.group(1) for m in (re.match(r"(.+)-\d+$", name) for name in running) if m]
        known = {n for table in master.getSystemState() for _, nodes in table for n in nodes}
        return bool(active) and all(n in known for n in active)

    def close(self, timeout=15.0):
        """SIGINT (as Ctrl-C: nodes close bags and save maps), then SIGKILL if it hangs; idempotent."""
        atexit.unregister(self.close)
        stop_process_group(self.proc, timeout, self.marker)
        if self._log not in (None, subprocess.DEVNULL):
            self._log.close()

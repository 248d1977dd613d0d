"""Start and stop a headless simulator world (roslaunch) on a private ROS master port."""

import os
import signal
import socket
import subprocess
import time
import uuid


def free_port():
    """A TCP port on the loopback that nothing listens on now."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


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
        runs = [e[len(b"UNEXMIN_RUN="):].decode(errors="replace").split(":") for e in env
                if e.startswith(b"UNEXMIN_RUN=")]
        if runs and marker in runs[0] and not zombie:
            pids.append(int(d))
    return pids


def stop_process_group(proc, timeout=15.0, marker=None):
    """SIGINT to the process group of `proc` (started with start_new_session=True), as Ctrl-C: ROS
    nodes close their bags and save their maps; SIGKILL if it has not exited after `timeout` s.

    roslaunch starts its master and nodes in sessions of their own and, interrupted while it is still
    launching, can exit leaving some running. With `marker` (the UNEXMIN_RUN value given in `proc`'s
    environment, which every descendant inherits), any such process left is sent SIGINT, then SIGTERM and
    SIGKILL after `timeout` s each."""
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGINT)
        try:
            proc.wait(timeout)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
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
    afterwards in this process talk to it.
    """

    def __init__(self, world="tank", robots=1, seed=0, realtime=False, paused=True, port=None,
                 log_dir=None, extra_args=()):
        self.port = port or free_port()
        self.uri = f"http://127.0.0.1:{self.port}"
        os.environ["ROS_MASTER_URI"] = self.uri
        # Loopback unless the user chose an address (ROS_IP or ROS_HOSTNAME): docs/reliability.md.
        if not os.environ.get("ROS_IP") and not os.environ.get("ROS_HOSTNAME"):
            os.environ["ROS_IP"] = "127.0.0.1"
        if log_dir:
            os.makedirs(log_dir, exist_ok=True)
            os.environ["ROS_LOG_DIR"] = log_dir
        args = [
            "roslaunch", "--port", str(self.port), "unexmin", f"{world}_world.launch",
            f"robots:={robots}", f"seed:={seed}", f"realtime:={str(realtime).lower()}",
            f"paused:={str(paused).lower()}", *extra_args,
        ]
        self.log_path = os.path.join(log_dir, "roslaunch.log") if log_dir else None
        log = open(self.log_path, "w") if log_dir else subprocess.DEVNULL
        # Every process of this world inherits the marker: close() finds any that roslaunch left behind.
        self.marker = uuid.uuid4().hex
        outer = os.environ.get("UNEXMIN_RUN")
        env = dict(os.environ, UNEXMIN_RUN=f"{outer}:{self.marker}" if outer else self.marker)
        self.proc = subprocess.Popen(args, stdout=log, stderr=subprocess.STDOUT, start_new_session=True, env=env)
        self._log = log

    def alive(self):
        return self.proc.poll() is None

    def close(self, timeout=15.0):
        """SIGINT (as Ctrl-C: nodes close bags and save maps), then SIGKILL if it hangs."""
        stop_process_group(self.proc, timeout, self.marker)
        if self._log not in (None, subprocess.DEVNULL):
            self._log.close()

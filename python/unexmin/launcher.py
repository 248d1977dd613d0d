"""Start and stop a headless simulator world (roslaunch) on a private ROS master port."""

import os
import signal
import socket
import subprocess
import time


def free_port():
    """A TCP port on the loopback that nothing listens on now."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def stop_process_group(proc, timeout=15.0):
    """SIGINT to the process group of `proc` (started with start_new_session=True), as Ctrl-C: ROS
    nodes close their bags and save their maps; SIGKILL if it has not exited after `timeout` s."""
    if proc.poll() is not None:
        return
    os.killpg(proc.pid, signal.SIGINT)
    try:
        proc.wait(timeout)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()


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
        os.environ.setdefault("ROS_IP", "127.0.0.1")
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
        self.proc = subprocess.Popen(args, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        self._log = log

    def alive(self):
        return self.proc.poll() is None

    def close(self, timeout=15.0):
        """SIGINT (as Ctrl-C: nodes close bags and save maps), then SIGKILL if it hangs."""
        stop_process_group(self.proc, timeout)
        if self._log not in (None, subprocess.DEVNULL):
            self._log.close()

"""Fixtures shared by the pytest suite."""

import os
import signal
import subprocess
import time

import pytest

from unexmin.scripting.launcher import stop_process_group

# The shutdown tests press a terminal's Ctrl-C (SIGINT to a run's process group). A test runner started in the
# background of a non-interactive shell (`cmd &`) or under nohup inherits SIGINT ignored, and so would every process
# it starts: Python then never raises KeyboardInterrupt and the runs would ignore the Ctrl-C that a terminal delivers.
# A handler of our own is reset to the default in every child at exec, as in a terminal.
if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)


def pytest_configure(config):
    config.addinivalue_line(
        "markers",
        "alone: asserts a wall-clock speed (a rate, faster than real time): scripts/test.sh runs it after the others,"
        " with no test beside it",
    )
    config.addinivalue_line(
        "markers", "long: takes minutes: its file is handed to a worker first, so that it does not finish the run alone"
    )


def pytest_collection_modifyitems(config, items):
    """Files holding a `long` test first (a stable sort: the order inside each file is kept)."""
    long_files = {item.path for item in items if item.get_closest_marker("long")}
    items.sort(key=lambda item: item.path not in long_files)


class MarkedRuns:
    """Processes a test starts, each in a session of its own with a fresh UNEXMIN_RUN marker in its
    environment: every process it starts inherits the marker, so the whole run can be found
    (unexmin.scripting.launcher.marked_processes) and stopped, even what left the process group."""

    def __init__(self):
        self._runs = []

    def start(self, args, tmp, **env):
        """Start `args` in folder `tmp` (its output in tmp/out.log, ROS_HOME and ROS_LOG_DIR inside tmp),
        with `env` added to the environment; returns (process, marker)."""
        marker = f"pytest-{os.getpid()}-{len(self._runs)}-{time.monotonic_ns()}"
        e = dict(
            os.environ, ROS_HOME=str(tmp / "ros_home"), ROS_LOG_DIR=str(tmp / "ros_log"), UNEXMIN_RUN=marker, **env
        )
        log = open(tmp / "out.log", "w")
        proc = subprocess.Popen(args, stdout=log, stderr=subprocess.STDOUT, env=e, start_new_session=True, cwd=tmp)
        self._runs.append((proc, marker, log))
        return proc, marker

    def marker(self, proc):
        return next(m for p, m, _ in self._runs if p is proc)

    def stop_all(self):
        while self._runs:
            proc, marker, log = self._runs.pop()
            stop_process_group(proc, 15.0, marker)
            log.close()


@pytest.fixture
def runs():
    """A MarkedRuns whose processes are stopped when the test ends, whatever its outcome."""
    r = MarkedRuns()
    yield r
    r.stop_all()

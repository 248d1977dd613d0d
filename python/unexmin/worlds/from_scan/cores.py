"""Local Dask workers bound to cores of their own (docs/world_from_scan.md#how, step 3)."""

import os

from distributed import WorkerPlugin


def cores_for(workers, available=None):
    """The cores each of `workers` local workers is bound to (a set per worker): the cores this process may
    use (os.sched_getaffinity) dealt out in turn, so that no two workers share one while there are at least
    as many cores as workers (one worker: every core); past that, one core each, in turn."""
    cores = sorted(os.sched_getaffinity(0) if available is None else available)
    if workers <= len(cores):
        return [set(cores[k::workers]) for k in range(workers)]
    return [{cores[k % len(cores)]} for k in range(workers)]


class BindToCores(WorkerPlugin):
    """A Dask worker plugin that binds every thread of a local worker's process, and so every thread it
    starts later, to its cores: `cores[name]` (a set) for the worker named `name` (an int, as LocalCluster
    names them; a worker with another name is left free). Open3D's Poisson starts and joins a short-lived
    thread per slice of its octree (tens of thousands per tile, whatever its n_threads); left free, such a
    thread may be queued behind the other worker on the other core while its own core idles, waiting for it
    to be joined."""

    name = "unexmin-bind-to-cores"

    def __init__(self, cores):
        self.cores = list(cores)

    def setup(self, worker):
        try:
            cores = self.cores[int(worker.name) % len(self.cores)]
        except (TypeError, ValueError):  # not one of the local cluster's workers: left as it is
            return
        for tid in os.listdir("/proc/self/task"):
            try:
                os.sched_setaffinity(int(tid), cores)
            except (ProcessLookupError, PermissionError):  # a thread that has just ended
                continue

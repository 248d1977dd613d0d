"""Missions for test_batch.py (given to the batch through the spec's python_path): a mission per way a
mission can fail, and one that reports which Dask worker process ran it."""

import os
import time

from unexmin.missions.batch import tank_survey


def flaky(sim, params):
    """Mission `params['index']` modulo 5: 0 ok (the tank survey), 1 raises, 2 returns NaN, 3 kills its own
    process, 4 never returns (the batch's timeout stops it)."""
    kind = params["index"] % 5
    sim.run_for(0.1)
    if kind == 1:
        raise RuntimeError(f"deliberate failure of mission {params['index']}")
    if kind == 2:
        return {"score": float("nan")}
    if kind == 3:
        os._exit(3)
    if kind == 4:
        while True:
            time.sleep(0.5)
    return tank_survey(sim, params)


def where(sim, params):
    """The tank survey, and the pid of the process that started this mission's process (the Dask worker)."""
    metrics = tank_survey(sim, params)
    metrics["runner_pid"] = os.getppid()
    return metrics

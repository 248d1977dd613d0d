"""Batches of lockstep missions on Dask distributed (docs/batch.md): `python -m unexmin.batch SPEC.yaml --out DIR`.

spec.py: read, check and expand a SPEC.yaml, write one mission's world, overrides and launch file;
task.py: one mission as a Dask task (a process with its own ROS master); run.py: the batch, its results
table and plots, the command line. The shipped mission functions (`mission: module:function`) are in
unexmin.missions.batch.
"""

from unexmin.batch.run import main, plot_summary, run_batch, run_sequential, write_results
from unexmin.batch.spec import SpecError, expand, load_spec

__all__ = ["SpecError", "expand", "load_spec", "main", "plot_summary", "run_batch", "run_sequential", "write_results"]

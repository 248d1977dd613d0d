"""Batches of lockstep missions on Dask distributed: Monte-Carlo runs and parameter sweeps (docs/batch.md).

    python -m unexmin.batch SPEC.yaml --out DIR [--workers N | --scheduler tcp://host:8786] [--limit N]

Expands the spec into missions (unexmin.batch.spec), submits each as an independent Dask task
(unexmin.batch.task.run_mission: a process of its own with its own ROS master and lockstep world), shows
a progress bar (done / failed / running) and the Dask dashboard's address, and writes in DIR:
results.parquet and results.csv (one row per mission: index, seed, parameters, metrics, status, error,
log, attempts, wall_time_s), summary_hist.png (a histogram per metric) and summary_vs_<param>.png (every
metric against each swept or sampled parameter), and missions/<index>/ (world, launch, logs).
Without --scheduler a local cluster of --workers processes (default: one per core) on 127.0.0.1 runs them.
"""

import argparse
import math
import os
import sys
import time

from unexmin.batch.spec import SpecError, expand, load_spec

#: Columns of every results table, after the parameters and metrics.
TAIL = ("status", "error", "log", "attempts", "wall_time_s")


def local_cluster(workers, config=None, **options):
    """A Dask LocalCluster of `workers` single-threaded worker processes on the loopback. Its scheduler
    (in this process) hands a worker a mission only when the worker is free (worker-saturation 1.0): a
    mission lasts seconds to minutes, so none waits behind another on a busy worker while one is idle.
    `config`: more Dask settings; `options`: more LocalCluster arguments (unexmin.worlds.from_scan's memory limit)."""
    import dask
    from dask.distributed import LocalCluster

    with dask.config.set({"distributed.scheduler.worker-saturation": 1.0, **(config or {})}):
        return LocalCluster(
            n_workers=workers,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address="127.0.0.1:0",
            scheduler_port=0,
            **options,
        )


def _executing(dask_worker):
    """Keys of the tasks a Dask worker is executing now (run on each worker by Client.run)."""
    return [str(ts.key) for ts in dask_worker.state.executing]


def _running(client, keys):
    """How many of `keys` the workers are executing now (None if they cannot be asked)."""
    try:
        executing = client.run(_executing)
    except Exception:  # a worker busy or gone: the bar shows "?"
        return None
    return sum(1 for tasks in executing.values() for k in tasks if k in keys)


def run_sequential(spec, out, limit=None):
    """The same missions one after the other in this process's children, without Dask (reference runs)."""
    from unexmin.batch.task import run_mission

    return table(spec, [run_mission(spec, m, out) for m in expand(spec, limit)])


def run_batch(spec, out, workers=None, scheduler=None, limit=None, progress=True, log=print):
    """Run the spec's missions on Dask and return the results table (a pandas DataFrame, index order).

    scheduler: address of a running Dask scheduler (tcp://host:port); otherwise a local cluster of
    `workers` processes (default: os.cpu_count()). progress: show a tqdm bar on stderr."""
    from dask.distributed import Client, as_completed
    from tqdm import tqdm

    from unexmin.batch.task import run_mission

    missions = expand(spec, limit)
    out = os.path.abspath(out)
    os.makedirs(out, exist_ok=True)
    cluster = None
    if scheduler:
        client = Client(scheduler, timeout=30)
    else:
        workers = workers or os.cpu_count() or 1
        cluster = local_cluster(workers)
        client = Client(cluster)
    try:
        log(
            f"[batch] {len(missions)} missions of {spec['mission']} on "
            f"{scheduler or f'a local cluster of {workers} workers'}"
            f"; Dask dashboard: {client.dashboard_link}"
        )
        t_submit = time.monotonic()
        futures = [
            client.submit(
                run_mission,
                spec,
                m,
                out,
                key=f"unexmin-mission-{m['index']:05d}-{os.getpid()}-{time.monotonic_ns()}",
                pure=False,
            )
            for m in missions
        ]
        keys = {f.key for f in futures}
        rows, failed = [], 0
        bar = tqdm(total=len(futures), desc="missions", unit="mission", disable=not progress, file=sys.stderr)
        pending = as_completed(futures)
        polled = 0.0
        while not pending.is_empty():
            batch = pending.next_batch(block=False)
            if time.monotonic() - polled > 1.0:  # the bar's running count, about once a second
                polled = time.monotonic()
                running = _running(client, keys)
                bar.set_postfix(done=len(rows) - failed, failed=failed, running="?" if running is None else running)
            if not batch:
                time.sleep(0.2)
            for future in batch:
                rows.append(_row(future, futures, missions))
                failed += rows[-1]["status"] != "ok"
                keys.discard(future.key)
                bar.update(1)
                polled = 0.0  # ask the workers again at once: the counts changed
        bar.close()
        running_s = time.monotonic() - t_submit
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    df = table(spec, rows)
    df.attrs["running_s"] = running_s  # [s] of wall time from the first submission to the last result
    return df


def _row(future, futures, missions):
    """The results row of a finished Dask task; a task that itself failed (a worker lost again and again)
    gives a failed row too."""
    try:
        return future.result()
    except Exception as e:
        m = missions[futures.index(future)]
        return dict(
            {"index": m["index"], "seed": m["seed"]},
            **m["params"],
            status="failed",
            error=f"Dask task failed: {type(e).__name__}: {e}",
            log="",
            attempts=0,
            wall_time_s=math.nan,
        )


def table(spec, rows):
    """The results DataFrame of `rows`: sorted by index; columns index, seed, parameters, metrics, TAIL."""
    import pandas as pd

    rows = sorted(rows, key=lambda r: r["index"])
    params = list(spec["params"]) + list(spec["sweep"]) + list(spec["sample"])
    metrics = []
    for r in rows:
        metrics += [
            k for k in r if k not in metrics and k not in params and k not in TAIL and k not in ("index", "seed")
        ]
    columns = ["index", "seed", *params, *metrics, *TAIL]
    return pd.DataFrame([{c: r.get(c) for c in columns} for r in rows], columns=columns)


def write_results(df, out):
    """results.parquet and results.csv in `out`; their paths."""
    paths = os.path.join(out, "results.parquet"), os.path.join(out, "results.csv")
    df.to_parquet(paths[0], index=False)
    df.to_csv(paths[1], index=False)
    return paths


def metric_columns(spec, df):
    """Numeric metric columns of the table (not parameters, not the bookkeeping of TAIL)."""
    import pandas as pd

    params = set(spec["params"]) | set(spec["sweep"]) | set(spec["sample"])
    return [
        c
        for c in df.columns
        if c not in params
        and c not in TAIL
        and c not in ("index", "seed")
        and pd.api.types.is_numeric_dtype(df[c])
        and not pd.api.types.is_bool_dtype(df[c])
    ]


def plot_summary(spec, df, out):
    """summary_hist.png (one histogram per metric of the ok missions) and summary_vs_<param>.png (each metric
    against each swept or sampled parameter); the paths written."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    ok = df[df["status"] == "ok"]
    metrics = metric_columns(spec, df)
    written = []
    if not metrics or ok.empty:
        return written
    cols = min(3, len(metrics))
    rows = math.ceil(len(metrics) / cols)

    def grid(title):
        fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.2 * rows), squeeze=False)
        for ax in axes.flat[len(metrics) :]:
            ax.set_visible(False)
        fig.suptitle(title)
        return fig, axes.flat

    fig, axes = grid(f"{spec['mission']}: {len(ok)} ok of {len(df)} missions")
    for ax, m in zip(axes, metrics):
        ax.hist(ok[m].astype(float), bins=min(20, max(5, len(ok) // 2)), color="tab:blue", edgecolor="white")
        ax.set(xlabel=m, ylabel="missions")
    fig.tight_layout()
    written.append(os.path.join(out, "summary_hist.png"))
    fig.savefig(written[-1], dpi=90)
    plt.close(fig)
    for p in list(spec["sweep"]) + list(spec["sample"]):
        values = ok[p]
        categorical = not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values)
        if categorical:
            labels = sorted({str(v) for v in values})
            x = np.array([labels.index(str(v)) for v in values], dtype=float)
        else:
            x = values.astype(float).to_numpy()
        fig, axes = grid(f"{spec['mission']}: metrics against {p}")
        for ax, m in zip(axes, metrics):
            ax.plot(x, ok[m].astype(float), "o", ms=4, alpha=0.7)
            ax.set(xlabel=p, ylabel=m)
            if categorical:
                ax.set_xticks(range(len(labels)), labels)
        fig.tight_layout()
        written.append(os.path.join(out, f"summary_vs_{p}.png"))
        fig.savefig(written[-1], dpi=90)
        plt.close(fig)
    return written


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m unexmin.batch", description=__doc__.splitlines()[0])
    parser.add_argument("spec", help="batch spec (YAML, docs/batch.md)")
    parser.add_argument("--out", required=True, help="output folder (created)")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, help="worker processes of the local cluster (default: one per core)")
    where.add_argument("--scheduler", help="address of a running Dask scheduler, e.g. tcp://10.0.0.5:8786")
    parser.add_argument("--limit", type=int, help="run only the first N missions of the spec")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    args = parser.parse_args(argv)
    if args.workers is not None and args.workers < 1:
        parser.error(f"--workers {args.workers}: expected at least 1")
    if args.limit is not None and args.limit < 1:
        parser.error(f"--limit {args.limit}: expected at least 1")
    try:
        spec = load_spec(args.spec)
    except SpecError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    t0 = time.monotonic()
    df = run_batch(
        spec, args.out, workers=args.workers, scheduler=args.scheduler, limit=args.limit, progress=not args.no_progress
    )
    wall = time.monotonic() - t0
    paths = write_results(df, os.path.abspath(args.out))
    plots = plot_summary(spec, df, os.path.abspath(args.out))
    failed = df[df["status"] != "ok"]
    print(
        f"[batch] {len(df) - len(failed)} ok, {len(failed)} failed of {len(df)} missions in {wall:.1f} s of wall "
        f"time ({len(df) / wall * 60:.1f} missions/min)"
    )
    for _, r in failed.iterrows():
        print(f"[batch] mission {r['index']} (seed {r['seed']}) failed: {r['error']} (log: {r['log']})")
    print(f"[batch] results: {paths[0]}, {paths[1]}" + (f"; plots: {', '.join(plots)}" if plots else ""))
    return 0

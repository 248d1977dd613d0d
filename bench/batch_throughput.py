#!/usr/bin/env python3
"""Batch throughput on Dask: the same missions with 1 and with 2 local workers (docs/benchmarks.md,
"Batch missions on Dask").

    source scripts/env.sh && python bench/batch_throughput.py [--spec examples/batch/tank_currents.yaml]
                                                              [--missions 8] [--workers 1 2 2 1] [--out DIR]
                                                              [--backend core|ros] [--seeds N]

For each worker count, a fresh local cluster runs the first --missions missions of the spec (by default the
shipped tank Monte-Carlo: the main job's tank mission, 30 s of sim time, every sensor, one ray-casting thread
per simulator). Reports the batch's wall time end to end (cluster start-up included) and from the first
submission to the last result (the steady state of a long batch), missions per minute of each,
the mean wall time per mission (start-up included), the load average before and after; then, per worker count
over its runs, missions per minute and the throughput ratio against the smallest count. The tables of the runs
must be equal but for wall times (checked).
"""

import argparse
import json
import os
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def main(argv=None):
    from unexmin.batch import run_batch
    from unexmin.batch.spec import load_spec

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--spec", default=os.path.join(HERE, "..", "examples", "batch", "tank_currents.yaml"))
    parser.add_argument("--missions", type=int, default=8)
    parser.add_argument(
        "--workers",
        type=int,
        nargs="+",
        default=[1, 2, 2, 1],
        help="worker counts, one batch each, in this order (default 1 2 2 1)",
    )
    parser.add_argument("--backend", choices=("core", "ros"), help="the spec's backend replaced by this one")
    parser.add_argument("--seeds", type=int, help="the spec's seeds replaced by 0..N-1 (one mission each)")
    parser.add_argument("--out", default=None, help="folder for the runs' outputs (default: a temporary one)")
    args = parser.parse_args(argv)
    spec = load_spec(args.spec)
    if args.backend:
        spec["backend"] = args.backend
    if args.seeds:
        spec["seeds"] = list(range(args.seeds))
    out = args.out or tempfile.mkdtemp(prefix="batch_bench_")
    results, tables = [], []
    print(
        f"spec {os.path.abspath(args.spec)}: {args.missions} missions of {spec['mission']}, {spec['duration']:g} s "
        f"of sim time each, sensors {spec['sensors']}, ray_caster_threads {spec['ray_caster_threads']}, backend "
        f"{spec['backend']}; "
        f"{os.cpu_count()} hardware threads"
    )
    for workers in args.workers:
        load0 = os.getloadavg()
        t0 = time.monotonic()
        df = run_batch(
            spec,
            os.path.join(out, f"run{len(results)}_workers{workers}"),
            workers=workers,
            limit=args.missions,
            progress=False,
            log=lambda _: None,
        )
        wall = time.monotonic() - t0
        ok = int((df["status"] == "ok").sum())
        running = df.attrs["running_s"]
        results.append(
            {
                "workers": workers,
                "missions": len(df),
                "ok": ok,
                "wall_s": round(wall, 1),
                "missions_per_min": round(len(df) / wall * 60.0, 2),
                "running_s": round(running, 1),
                "running_missions_per_min": round(len(df) / running * 60.0, 2),
                "mean_mission_wall_s": round(float(df["wall_time_s"].mean()), 1),
                "load_before": [round(v, 2) for v in load0],
                "load_after": [round(v, 2) for v in os.getloadavg()],
            }
        )
        tables.append(df.drop(columns=["wall_time_s", "log"]))
        r = results[-1]
        print(
            f"workers {workers}: {r['ok']}/{r['missions']} ok in {r['wall_s']:.1f} s = {r['missions_per_min']:.2f} "
            f"missions/min end to end; {r['running_s']:.1f} s = {r['running_missions_per_min']:.2f} missions/min "
            f"from the first submission to the last result (mean {r['mean_mission_wall_s']:.1f} s per mission); "
            f"load {r['load_before']} -> {r['load_after']}",
            flush=True,
        )
    # Per worker count, over its runs (give e.g. --workers 1 2 2 1 so that a load that drifts during the
    # benchmark weighs on both counts alike): missions / summed wall time.
    counts = sorted({r["workers"] for r in results})
    pooled = {}
    for w in counts:
        runs = [r for r in results if r["workers"] == w]
        missions = sum(r["missions"] for r in runs)
        pooled[w] = {
            "runs": len(runs),
            "missions_per_min": missions / sum(r["wall_s"] for r in runs) * 60.0,
            "running_missions_per_min": missions / sum(r["running_s"] for r in runs) * 60.0,
        }
        print(
            f"workers {w}, {len(runs)} run(s): {pooled[w]['running_missions_per_min']:.2f} missions/min from first "
            f"submission to last result, {pooled[w]['missions_per_min']:.2f} end to end"
        )
    for w in counts[1:]:
        ratio = pooled[w]["running_missions_per_min"] / pooled[counts[0]]["running_missions_per_min"]
        end_to_end = pooled[w]["missions_per_min"] / pooled[counts[0]]["missions_per_min"]
        pooled[w].update(throughput_ratio=round(ratio, 3), end_to_end_ratio=round(end_to_end, 3))
        print(
            f"throughput ratio {w} vs {counts[0]} workers: {ratio:.3f} (first submission to last result; end to "
            f"end, cluster start-up included: {end_to_end:.3f})"
        )
    same = all(t.equals(tables[0]) for t in tables[1:])
    print(f"tables equal but for wall times: {same}")
    print(json.dumps({"runs": results, "pooled": pooled}))
    return 0 if same and all(r["ok"] == r["missions"] for r in results) else 1


if __name__ == "__main__":
    sys.exit(main())

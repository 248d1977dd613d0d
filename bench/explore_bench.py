#!/usr/bin/env python3
"""Map F-score against sim time for the survey, one explorer and three explorers, and the explorers' RTF
(docs/benchmarks.md, docs/explore.md).

    source scripts/env.sh && python bench/explore_bench.py [--out DIR] [--time S] [--snapshot S] [--reuse]
                   [--visibility none|medium] [--skip-survey] [--world-file FILE --bounds X0 Y0 Z0 X1 Y1 Z1]

Runs, one after the other: the main job's survey in the shipped mine (python -m unexmin.missions.mine), then the
explorer (python -m unexmin.missions.explore) with UX_1 alone and with UX_1..UX_3, in the shipped mine or --world-file,
same budget and box, maps saved every --snapshot s and scored. Prints per run the F-score (precision and recall
of unexmin.map_quality against that run's own path) at each snapshot, the final coverage of the reachable
volume, the RTF while stepping and the load, and the three-robot speed-up: the one robot's sim time to explore --share
(0.9) of the reachable volume over the three robots'. Writes DIR/explore_bench.png and
DIR/explore_bench.json. --reuse reads runs already in DIR instead of running them.
"""

import argparse
import json
import os
import subprocess
import sys


def run(args, log):
    with open(log, "w") as f:
        proc = subprocess.run(args, stdout=f, stderr=subprocess.STDOUT)
    if proc.returncode not in (0, 3):  # 3: the explorer reported a contact or a robot not home (in its summary)
        raise RuntimeError(f"{' '.join(args)} failed (code {proc.returncode}): see {log}")


def f_scores(rows):
    return [(r["t"], 2 * r["precision"] * r["recall"] / max(r["precision"] + r["recall"], 1e-12)) for r in rows]


def explored_time(timeline, volume):
    """First sim time [s] at which the explored reachable volume reaches `volume` [m3] (inf if never)."""
    for r in timeline:
        if r["explored_reachable_m3"] >= volume:
            return r["t"]
    return float("inf")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", default="explore_bench")
    p.add_argument("--time", type=float, default=600.0, help="explorers' time budget [s of sim time]")
    p.add_argument("--snapshot", type=float, default=90.0, help="[s of sim time] between scored maps")
    p.add_argument("--visibility", default="none", choices=("none", "low", "medium", "high"))
    p.add_argument("--reuse", action="store_true", help="read the runs already in --out")
    p.add_argument("--skip-survey", action="store_true")
    p.add_argument("--share", type=float, default=0.9, help="explored share of the reachable volume for the speed-up")
    p.add_argument("--world-file", help="the explorers' world (default: the shipped mine; the survey always flies it)")
    p.add_argument("--bounds", nargs=6, help="the explorers' box [m] (python -m unexmin.missions.explore --bounds)")
    a = p.parse_args(argv)
    out = os.path.abspath(a.out)
    os.makedirs(out, exist_ok=True)
    py = sys.executable
    runs = {}
    if not a.skip_survey:
        runs["survey"] = [py, "-m", "unexmin.missions.mine", "--out", f"{out}/survey", "--visibility", a.visibility]
        runs["survey"] += ["--snapshot", str(a.snapshot)]
    for n in (1, 3):
        runs[f"explore_{n}"] = [py, "-m", "unexmin.missions.explore", "--out", f"{out}/explore_{n}", "--robots", str(n)]
        runs[f"explore_{n}"] += ["--time", str(a.time), "--visibility", a.visibility, "--snapshot", str(a.snapshot)]
        runs[f"explore_{n}"] += (["--world-file", a.world_file] if a.world_file else []) + (
            ["--bounds", *a.bounds] if a.bounds else []
        )
    load0 = os.getloadavg()[0]
    for name, args in runs.items():
        if not a.reuse:
            print(f"running {name}: {' '.join(args[1:])}", flush=True)
            os.makedirs(f"{out}/{name}", exist_ok=True)
            run(args, f"{out}/{name}.log")
    summaries = {name: json.load(open(f"{out}/{name}/summary.json")) for name in runs}
    curves = {}
    for name, s in summaries.items():
        rows = s["coverage"] if name == "survey" else s["f_score_over_time"]
        curves[name] = f_scores(rows)
        q = s["quality"]
        rtf = s.get("rtf_while_stepping")
        extra = "" if name == "survey" else f", coverage {s['coverage']:.3f} of {s['reachable_m3']:.0f} m3"
        print(
            f"{name:10s} F {q['f_score']:.3f} (precision {q['precision']:.3f}, recall {q['recall']:.3f}) at "
            f"{s['sim_time_s']:.0f} s; RTF {rtf} while stepping{extra}; load {s.get('load_average_1min')}"
        )
        print("           F over time: " + ", ".join(f"{t:.0f} s {f:.3f}" for t, f in curves[name]))
    e1, e3 = summaries["explore_1"], summaries["explore_3"]
    volume = a.share * e1["reachable_m3"]
    t1, t3 = explored_time(e1["timeline"], volume), explored_time(e3["timeline"], volume)
    speedup = t1 / t3 if t3 > 0 else float("nan")
    print(
        f"{100 * a.share:.0f} % of the reachable volume ({volume:.0f} m3): one robot at {t1:.0f} s, three robots at "
        f"{t3:.0f} s of sim time: speed-up {speedup:.2f} (load {load0:.1f} at the start, {os.getloadavg()[0]:.1f} at "
        "the end)"
    )
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
    for name, c in curves.items():
        ax[0].plot([t for t, _ in c], [f for _, f in c], "o-", label=name)
    ax[0].set(xlabel="sim time [s]", ylabel="map F-score", ylim=(0, 1), title="map F-score (own path)")
    for name in ("explore_1", "explore_3"):
        tl = summaries[name]["timeline"]
        ax[1].plot([r["t"] for r in tl], [r["explored_reachable_m3"] for r in tl], label=name)
    ax[1].set(xlabel="sim time [s]", ylabel="explored reachable volume [m³]", title=f"speed-up {speedup:.2f}")
    for x in ax:
        x.grid(alpha=0.3)
        x.legend()
    fig.savefig(f"{out}/explore_bench.png", dpi=90)
    json.dump(
        {
            "curves": curves,
            "speedup": speedup,
            "summaries": {k: {kk: v[kk] for kk in ("quality", "sim_time_s")} for k, v in summaries.items()},
        },
        open(f"{out}/explore_bench.json", "w"),
        indent=1,
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Stage write_report: the run's report (docs/world_from_scan.md, "Report"), kept as b.report and written as
OUT/NAME.json."""

import json
import resource
import time

import numpy as np


def _peak_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # [MB] this process's peak so far


def _points(b):
    results, s = b.results.values(), b.survey
    return {
        "scan": str(b.scan),
        "points_read": int(s["count"]),
        "points_finite": int(s["finite"]),
        "points_used": int(sum(r["points_used"] for r in results)),
        "normals": "read" if s["normals"] else "estimated",
        "orientation_samples_decided": round(float(np.mean([r["decided"] for r in results])), 3),
        "resolution": b.options.resolution,
        "point_spacing": round(b.spacing, 4),
        "poisson_depth": int(max(r["depth"] for r in results)),
        "max_gap": b.options.max_gap,
        "poisson_triangles": int(sum(r["poisson_triangles"] for r in results)),
    }


def _meshes(b):
    (v, t), (vv, vt), o = b.collision, b.visual, b.options
    return {
        "collision": {"file": b.collision_file, "triangles": int(len(t)), "vertices": int(len(v)), "edge": o.edge},
        "visual": {
            "file": b.visual_file,
            "triangles": int(len(vt)),
            "vertices": int(len(vv)),
            "edge": o.visual_edge,
            "colours": b.visual_colours is not None,
        },
        "world": b.world_path.name,
        "parts_world": b.parts_path.name,
    }


def _tiles(b):
    layout = b.layout
    built = [
        {
            "index": r["index"],
            "points_read": r["points_read"],
            "points_used": r["points_used"],
            "estimate": layout["tiles"][r["index"]]["estimate"],
            "peak_rss_mb": r["peak_rss_mb"],
            "seconds": r["seconds"],
            "cpu_seconds": r["cpu_seconds"],
        }
        for r in sorted(b.results.values(), key=lambda r: r["index"])
    ]
    return {
        "axis": "xyz"[layout["axis"]],
        "seams": [round(x, 3) for x in b.seams],
        "overlap": round(layout["overlap"], 3),
        "count": len(layout["tiles"]),
        "budget_points": b.budget,
        "zipped_loops": b.zipped,
        "open_loops": b.open_loops,
        "parts": b.parts,
        "built": built,
    }


def _surface(b):
    results, d, v = b.results.values(), b.distances, b.collision[0]
    return {
        "closed": b.closed,
        "volume": round(b.volume, 3) if b.closed else None,
        "flooded_volume": round(b.flooded, 3) if b.flooded is not None else None,
        "water_level": b.surface_z,
        "wall_area": round(sum(r["wall_area"] for r in results), 3),
        "bridged_area": round(sum(r["bridged_area"] for r in results), 3),
        "holes_closed": b.holes,
        "seam_folds": b.folds,
        "holes_area": round(b.hole_area, 3),
        "scan_to_mesh": {
            "mean": round(float(d.mean()), 4),
            "p95": round(float(np.percentile(d, 95)), 4),
            "max": round(float(d.max()), 4),
            "points": int(len(b.probe)),
        },
        "bbox_min": [round(x, 3) for x in v.min(axis=0)],
        "bbox_max": [round(x, 3) for x in v.max(axis=0)],
        "spawns": [{"xyz": [round(float(x), 3) for x in p], "clearance": round(c, 3)} for p, c in b.spawns],
    }


def _run(b):
    o, worker_peak = b.options, max(r["peak_rss_mb"] for r in b.results.values())
    return {
        "seconds": b.progress.times,
        "total_seconds": round(time.monotonic() - b.started, 2),
        "peak_rss_mb": round(_peak_mb(), 1),
        "workers_peak_rss_mb": round(worker_peak, 1),
        "peak_rss_bound_mb": round(max(b.driver_mb + b.local_workers * worker_peak, _peak_mb()), 1),
        "memory_gb": o.memory_gb,
        "workers": b.local_workers if not o.scheduler else None,
        "scheduler": o.scheduler,
    }


def write_report(b):
    """Fills b.report (dict) and writes it as OUT/NAME.json."""
    b.report = {**_points(b), **_meshes(b), "tiles": _tiles(b), "failed_tiles": b.failures, **_surface(b), **_run(b)}
    (b.out / f"{b.name}.json").write_text(json.dumps(b.report, indent=1) + "\n")
    return b

"""What the run is scored by while it flies (e: the Explorer): ground truth (the simulator's odometry and the
world's rock, truth.py) read only to score, and the explored share of the reachable volume over time; report.py
writes them at the end."""

import numpy as np


def track_truth(e, t, rows):
    """Each robot's true position (the simulator's odometry) at sim time `t` [s]: distance flown, clearance to the
    rock, a contact; a row of the track when `rows`."""
    for a in e.agents:
        p = a.handle.odom().pose.pose.position
        true = np.array([p.x, p.y, p.z])
        a.flown += float(np.linalg.norm(true - a.last_true))
        a.travelled_est += float(np.linalg.norm(a.nav.v_body)) * e.o.control_dt
        a.last_true = true
        clearance = float(e.truth.clearance(true)[0])
        touching = clearance < e.po.hull_radius + 0.02
        if touching and not a.touching:
            e.event(t, a.name, "contact", f"clearance {clearance:.3f} m at {true.round(2).tolist()}")
        a.touching = touching
        a.min_clearance = min(a.min_clearance, clearance)
        if rows:
            a.rows.append(
                {
                    "t": round(t, 2),
                    "true": true.round(3).tolist(),
                    "estimate": a.nav.p.round(3).tolist(),
                    "drift_m": round(float(np.linalg.norm(true - a.nav.p)), 3),
                    "flown_m": round(a.flown, 2),
                    "energy_j": round(a.energy, 1),
                    "clearance_m": round(clearance, 3),
                    "mode": a.mode,
                    "dvl_lock": a.nav.locked,
                }
            )


def record_coverage(e, t):
    """A row of the timeline: the volume the map knows, of it the reachable volume, and the share of the reachable."""
    known = e.grid.states != 0
    e.timeline.append(
        {
            "t": round(t, 2),
            "explored_m3": round(e.grid.known_volume(), 2),
            "explored_reachable_m3": round(float((known & e.reachable).sum()) * e.grid.cell**3, 2),
            "coverage": round(float((known & e.reachable).sum()) / max(1, int(e.reachable.sum())), 4),
        }
    )


def print_progress(e, t):
    """A line on the console: the timeline's last row and where each robot is and goes."""
    r = e.timeline[-1]
    robots = "  ".join(
        f"{a.name} {a.mode} at {np.round(a.nav.p, 1).tolist()}"
        + (f" -> {np.round(a.goal, 1).tolist()}" if a.goal is not None else "")
        for a in e.agents
    )
    print(
        f"[{t:7.1f} s] explored {r['explored_reachable_m3']:.0f} m3 ({100 * r['coverage']:.0f} %)  {robots}",
        flush=True,
    )

"""The science survey of a generated mine (docs/science_survey.md), in-process (unexmin.core, no ROS).

    python -m unexmin.missions.science --out DIR [--world mine] [--seed 0] [--gallery-end X]

UX_1 descends the entry shaft logging its water probe, fires its water sampler above and below the chemocline,
climbs back to the first level and flies its gallery close to the wall on the side of the magnetite lens, then
returns to the shaft and surfaces. It leaves in DIR:

- water_profile.csv / .png: every probe channel against depth on the descent, beside the world's own water there
  (World.water at the hull's centre at each sample);
- samples.csv: the sampler's laboratory results (position, time, the water averaged over each fill);
- magnetic_profile.png, magnetic_map.png: the total-field anomaly (|B| minus its median on the gallery) along the
  path and in plan view;
- gamma_profile.png, gamma_cloud.ply: the gamma counter's rates along the gallery, and the path's points offset to
  the wall coloured by the uranium window's rate;
- trajectory.csv, science_summary.json: the path and the scores against the world's geology: the magnetic peak's
  distance along the gallery from the magnetite lens's centre, the uranium zone's edges from the gamma profile
  against where the world's fracture zone crosses the path (each to pass within 1 m), the probe's errors.

The route follows the generator's layout of the mine of the world's seed (unexmin.worlds.generator), so the world
must be a generated mine whose geology names a `magnetite_lens` and a `uranium_fractures` body, as
`python -m unexmin.worlds.generator.science` writes them.
"""

import argparse
import csv
import json
import math
import sys
import time
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from unexmin.control.allocation import ThrusterAllocator
from unexmin.missions.waypoints import SPEED, controller

ROBOT = "UX_1"
SENSORS = "water_probe,water_sampler,magnetometer,gamma_counter"
CONTROL_DT = 0.02  # [s] between controller updates: the magnetometer's 50 Hz, so no sample is missed
TOLERANCE = 0.4  # [m] a waypoint is reached within this
GALLERY_SPEED = 0.25  # [m/s] along the wall: 4 gamma samples per metre (the counter integrates 1 s)
WALL_GAP = 0.3  # [m] planned water between the hull and the gallery's smooth wall
HULL_RADIUS = 0.3  # [m]
CHANNELS = ("temperature", "conductivity", "ph", "redox", "oxygen")


def _state_msgs(state):
    """The controller's pose and twist (message-like) from unexmin.core's state dict."""
    p, q = state["position"], state["orientation"]
    v, w = state["linear_velocity"], state["angular_velocity"]
    pose = SimpleNamespace(
        position=SimpleNamespace(x=p[0], y=p[1], z=p[2]), orientation=SimpleNamespace(x=q[0], y=q[1], z=q[2], w=q[3])
    )
    twist = SimpleNamespace(
        linear=SimpleNamespace(x=v[0], y=v[1], z=v[2]), angular=SimpleNamespace(x=w[0], y=w[1], z=w[2])
    )
    return pose, twist


def world_water(world):
    """The world file's water: (surface_z, rows sorted by depth) with every channel the profile gives."""
    water = world.get("water") or {}
    rows = water.get("profile") or []
    if not rows:
        raise ValueError("the world has no water.profile: the science survey measures a water column")
    return float(water.get("surface_z", 0.0)), rows


def slab_interval(body, y, z):
    """Where a vein (slab of `thickness` about a plane through `xyz` with normal `normal`) crosses the line of
    constant y, z: (x0, x1) [m], or None when the line runs parallel to it."""
    c, n = np.array(body["xyz"], float), np.array(body["normal"], float)
    n /= np.linalg.norm(n)
    if abs(n[0]) < 1e-9:
        return None
    half = 0.5 * float(body["thickness"])
    rest = (y - c[1]) * n[1] + (z - c[2]) * n[2]
    a, b = (c[0] + (-half - rest) / n[0]), (c[0] + (half - rest) / n[0])
    return (min(a, b), max(a, b))


def plan_route(world, layout, gallery_end=None):
    """The survey's legs: [(name, [(x, y, z), ...], action)] from the generator's layout and the world's geology."""
    from unexmin.worlds.generator.generator import point_on

    sx, sy = layout.shaft_xy
    gallery = next(t for t in layout.tunnels if t.kind == "gallery")
    bodies = {b["name"]: b for b in (world.get("geology") or {}).get("bodies", [])}
    for name in ("magnetite_lens", "uranium_fractures"):
        if name not in bodies:
            raise ValueError(f"the world's geology has no body '{name}' (python -m unexmin.worlds.generator.science)")
    surface, rows = world_water(world)
    # the chemocline: the middle of the first pair of rows less than 3 m apart (the generator's transition)
    cline = next(
        (
            0.5 * (rows[k]["depth"] + rows[k - 1]["depth"])
            for k in range(1, len(rows))
            if rows[k]["depth"] - rows[k - 1]["depth"] < 3.0
        ),
        0.5 * (rows[0]["depth"] + rows[-1]["depth"]),
    )
    level_z = float(gallery.points[0, 2])
    above, below = surface - min(cline - 3.0, surface - level_z - 3.0), surface - (cline + 5.0)
    lens = np.array(bodies["magnetite_lens"]["xyz"], float)
    side = 1.0 if lens[1] >= point_on(gallery.points, lens[0])[1] else -1.0
    end = gallery_end or max(float(bodies[n]["xyz"][0]) for n in ("magnetite_lens", "uranium_fractures")) + 12.0
    offset = gallery.a - HULL_RADIUS - WALL_GAP
    out = [(float(x), *point_on(gallery.points, x)[1:]) for x in np.arange(sx + 5.0, end + 1e-9, 2.0)]
    wall = [(x, y + side * offset, z) for x, y, z in out]
    back = [(x, y, z) for x, y, z in reversed(out)]
    return {
        "legs": [
            ("descent", [(sx, sy, surface - 3.0), (sx, sy, above)], "sample"),
            ("descent", [(sx, sy, below)], "sample"),
            ("climb", [(sx, sy, level_z)], None),
            ("gallery", [(sx + 4.0, sy, level_z)] + wall, None),
            ("return", back + [(sx, sy, level_z), (sx, sy, surface - 2.5)], None),
        ],
        "side": side,
        "offset": offset,
        "chemocline_depth": float(cline),
        "sample_depths": [surface - above, surface - below],
    }


class Log:
    """Every new sample of the science sensors, kept as it arrives (the counts checked against rate x time)."""

    def __init__(self, world, robot):
        self.world = world
        self.robot = robot
        self.counts = {s: 0 for s in robot.sensors}
        self.samples = {s: [] for s in robot.sensors}

    def poll(self, leg):
        for s in self.samples:
            n = self.robot.sample_count(s)
            if n != self.counts[s]:
                if n - self.counts[s] > 1 and s != "water_sampler":
                    raise RuntimeError(f"{s}: {n - self.counts[s]} samples between two polls: poll more often")
                self.counts[s] = n
                sample = self.robot.sample(s)
                sample["leg"] = leg
                sample["position"] = self.robot.state()["position"].copy()
                if s == "water_probe":  # the world's own water there and then (at the hull's centre)
                    sample["truth"] = self.world.water(sample["position"])
                self.samples[s].append(sample)


def fly(world, robot, route, log, max_time):
    """Flies the route's legs with the waypoint controller; fires the sampler where a leg says so. Returns the
    track [(t, x, y, z, leg)]."""
    allocator = ThrusterAllocator()
    steps = max(1, round(CONTROL_DT / world.dt))
    track = []
    for leg, points, action in route["legs"]:
        for target in points:
            while True:
                state = robot.state()
                pose, twist = _state_msgs(state)
                wrench, dist = controller(pose, twist, target, speed=GALLERY_SPEED if leg == "gallery" else SPEED)
                if dist < TOLERANCE:
                    break
                if state["time"] > max_time:
                    raise RuntimeError(f"the survey ran out of its {max_time:.0f} s of sim time on leg '{leg}'")
                robot.thrusts(allocator.allocate(wrench)[0])
                world.step(steps)
                log.poll(leg)
                track.append((state["time"], *state["position"], leg))
        if action == "sample":
            robot.fire("water_sampler")
            t_end = robot.state()["time"] + 4.0  # the fill (2 s) and the result at the next check
            while robot.state()["time"] < t_end:
                pose, twist = _state_msgs(robot.state())
                robot.thrusts(allocator.allocate(controller(pose, twist, points[-1])[0])[0])
                world.step(steps)
                log.poll(leg)
    robot.thrusts([0.0] * 8)
    return track


def _half_max_interval(x, rate, background):
    """The x-interval where `rate` exceeds half-way from `background` to its peak (the longest run), edges by linear
    interpolation; None when nothing rises above background."""
    peak = float(np.max(rate))
    if peak <= background:
        return None
    level = background + 0.5 * (peak - background)
    above = rate >= level
    k = int(np.argmax(rate))
    i0, i1 = k, k
    while i0 > 0 and above[i0 - 1]:
        i0 -= 1
    while i1 < len(rate) - 1 and above[i1 + 1]:
        i1 += 1

    def edge(i_in, i_out):
        if i_out < 0 or i_out >= len(rate):
            return float(x[i_in])
        f = (level - rate[i_out]) / (rate[i_in] - rate[i_out])
        return float(x[i_out] + f * (x[i_in] - x[i_out]))

    a, b = edge(i0, i0 - 1), edge(i1, i1 + 1)
    return (min(a, b), max(a, b))


def score(world, route, log, out):
    """Writes the outputs and returns the summary (dict)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    surface, _ = world_water(world)
    bodies = {b["name"]: b for b in world["geology"]["bodies"]}
    summary = {"route": {k: route[k] for k in ("side", "offset", "chemocline_depth", "sample_depths")}}
    # the water profile on the descent
    probe = [s for s in log.samples["water_probe"] if s["leg"] == "descent"]
    depth = np.array([surface - s["position"][2] for s in probe])
    with open(out / "water_profile.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time_s", "depth_m"] + [f"{c}" for c in CHANNELS] + [f"true_{c}" for c in CHANNELS])
        for s, d in zip(probe, depth):
            w.writerow([s["time"], d] + [s[c] for c in CHANNELS] + [s["truth"][c] for c in CHANNELS])
    fig, axes = plt.subplots(1, len(CHANNELS), figsize=(3.2 * len(CHANNELS), 5), sharey=True)
    errors = {}
    for ax, c in zip(axes, CHANNELS):
        truth = np.array([s["truth"][c] for s in probe])
        measured = np.array([s[c] for s in probe])
        errors[c] = {
            "rms": float(np.sqrt(np.mean((measured - truth) ** 2))),
            "max": float(np.max(np.abs(measured - truth))),
        }
        ax.plot(truth, depth, "k-", lw=1, label="world")
        ax.plot(measured, depth, "r.", ms=3, label="probe")
        ax.set_xlabel(c)
        ax.invert_yaxis() if ax is axes[0] else None
    axes[0].set_ylabel("depth [m]")
    axes[0].legend()
    fig.tight_layout()
    fig.savefig(out / "water_profile.png", dpi=90)
    plt.close(fig)
    summary["probe"] = {"samples": len(probe), "errors": errors}
    # the samples
    sampler = log.samples["water_sampler"][-1] if log.samples["water_sampler"] else None
    results = []
    if sampler is not None:
        for i in range(len(sampler["result_depth"])):
            results.append(
                {
                    "bottle": i + 1,
                    "start_time_s": float(sampler["result_start_time"][i]),
                    "end_time_s": float(sampler["result_end_time"][i]),
                    "x_m": float(sampler["result_position"][i][0]),
                    "y_m": float(sampler["result_position"][i][1]),
                    "z_m": float(sampler["result_position"][i][2]),
                    "depth_m": float(sampler["result_depth"][i]),
                    **{c: float(sampler[f"result_{c}"][i]) for c in CHANNELS + ("salinity", "turbidity", "density")},
                }
            )
    if results:
        with open(out / "samples.csv", "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(results[0]))
            w.writeheader()
            w.writerows(results)
    summary["samples"] = results
    # the gallery: magnetics and gamma along x
    mag = [s for s in log.samples["magnetometer"] if s["leg"] == "gallery"]
    mx = np.array([s["position"][0] for s in mag])
    total = np.array([s["total_field"] for s in mag])
    anomaly = total - np.median(total)
    kernel = np.ones(25) / 25  # 0.5 s at 50 Hz: the noise and the thrusters' ripple averaged out
    smooth = np.convolve(anomaly, kernel, mode="same")
    lens = bodies["magnetite_lens"]
    peak_x = float(mx[int(np.argmax(np.abs(smooth)))])
    summary["magnetics"] = {
        "samples": len(mag),
        "peak_anomaly_nT": float(smooth[int(np.argmax(np.abs(smooth)))]),
        "peak_x_m": peak_x,
        "lens_x_m": float(lens["xyz"][0]),
        "peak_error_m": abs(peak_x - float(lens["xyz"][0])),
    }
    fig, ax = plt.subplots(figsize=(9, 3.5))
    ax.plot(mx, anomaly, color="0.7", lw=0.5, label="50 Hz")
    ax.plot(mx, smooth, "b-", lw=1.2, label="0.5 s mean")
    ax.axvline(lens["xyz"][0], color="k", ls="--", lw=1, label="magnetite lens centre")
    ax.set_xlabel("x along the gallery [m]")
    ax.set_ylabel("total-field anomaly [nT]")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "magnetic_profile.png", dpi=90)
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(9, 3.5))
    my = np.array([s["position"][1] for s in mag])
    sc = ax.scatter(mx, my, c=smooth, cmap="coolwarm", s=4)
    ax.add_patch(
        matplotlib.patches.Ellipse(
            lens["xyz"][:2], 2 * lens["radii"][0], 2 * lens["radii"][1], angle=math.degrees(lens["rpy"][2]), fill=False
        )
    )
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    fig.colorbar(sc, label="anomaly [nT]")
    fig.tight_layout()
    fig.savefig(out / "magnetic_map.png", dpi=90)
    plt.close(fig)
    gamma = [s for s in log.samples["gamma_counter"] if s["leg"] == "gallery"]
    gx = np.array([s["position"][0] for s in gamma])
    gy, gz = np.array([s["position"][1] for s in gamma]), np.array([s["position"][2] for s in gamma])
    u = np.array([s["rate_uranium"] for s in gamma])
    u_mean = np.convolve(u, np.ones(3) / 3, mode="same")  # three samples (0.75 m): the Poisson noise of 1 s counts
    zone = bodies["uranium_fractures"]
    truth = slab_interval(zone, float(np.median(gy)), float(np.median(gz)))
    background = float(np.median(u))
    found = _half_max_interval(gx, u_mean, background)
    summary["gamma"] = {
        "samples": len(gamma),
        "uranium_background_cps": background,
        "uranium_peak_cps": float(np.max(u)) if len(u) else 0.0,
        "zone_true_m": list(truth) if truth else None,
        "zone_found_m": list(found) if found else None,
        "edge_errors_m": [abs(found[0] - truth[0]), abs(found[1] - truth[1])] if found and truth else None,
    }
    fig, ax = plt.subplots(figsize=(9, 3.5))
    for key, colour in (
        ("rate_potassium", "tab:purple"),
        ("rate_uranium", "tab:green"),
        ("rate_thorium", "tab:orange"),
    ):
        ax.plot(gx, [s[key] for s in gamma], ".-", color=colour, ms=3, lw=0.8, label=key[5:])
    if truth:
        ax.axvspan(*truth, color="tab:green", alpha=0.15, label="fracture zone (world)")
    ax.set_yscale("log")
    ax.set_xlabel("x along the gallery [m]")
    ax.set_ylabel("count rate [cps]")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "gamma_profile.png", dpi=90)
    plt.close(fig)
    # the path's points moved to the wall, coloured by the uranium window (log scale, green = high)
    wall = np.column_stack([gx, gy + route["side"] * (HULL_RADIUS + WALL_GAP), gz])
    level = np.log10(np.maximum(u, 1e-3))
    t = (level - level.min()) / max(1e-9, np.ptp(level))
    colours = np.column_stack([255 * (1 - t), 255 * np.ones_like(t) * 0.3 + 180 * t, 60 * np.ones_like(t)]).astype(int)
    with open(out / "gamma_cloud.ply", "w") as f:
        f.write(
            f"ply\nformat ascii 1.0\ncomment unexmin science survey: uranium window rate on the wall\n"
            f"element vertex {len(wall)}\nproperty float x\nproperty float y\nproperty float z\n"
            "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n"
        )
        for p, c in zip(wall, colours):
            f.write(f"{p[0]:.3f} {p[1]:.3f} {p[2]:.3f} {c[0]} {c[1]} {c[2]}\n")
    return summary


def run(out, world_name="mine", seed=0, gallery_end=None, max_time=3600.0):
    """The survey; returns its summary (also written as science_summary.json in `out`)."""
    from unexmin.core import World
    from unexmin.missions.survey import mine_layout
    from unexmin.worlds.files import world_path
    from unexmin.worlds.schema import read_world

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = world_path(world_name)
    world_file = read_world(path)
    layout, _ = mine_layout(path)  # the generator's report beside the mine's mesh
    route = plan_route(world_file, layout, gallery_end)
    wall0 = time.monotonic()
    world = World(path, robots=[ROBOT], seed=seed, sensors=SENSORS)
    robot = world.robot(ROBOT)
    log = Log(world, robot)
    track = fly(world, robot, route, log, max_time)
    sim_time = robot.state()["time"]
    wall = time.monotonic() - wall0
    with open(out / "trajectory.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time_s", "x_m", "y_m", "z_m", "leg"])
        w.writerows(track)
    summary = {"world": str(path), "seed": seed, "sim_time_s": sim_time, "wall_time_s": wall}
    summary["counts"] = dict(log.counts)
    summary.update(score(world_file, route, log, out))
    m, g = summary["magnetics"], summary["gamma"]
    summary["pass"] = {
        "magnetic_peak_within_1m": bool(m["peak_error_m"] <= 1.0),
        "uranium_zone_within_1m": bool(g["edge_errors_m"]) and bool(max(g["edge_errors_m"]) <= 1.0),
        "samples_above_and_below": len(summary["samples"]) >= 2,
    }
    (out / "science_summary.json").write_text(json.dumps(summary, indent=1) + "\n")
    return summary


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m unexmin.missions.science", description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, help="output folder (created)")
    ap.add_argument("--world", default="mine", help="a generated mine's world (name or file; default mine)")
    ap.add_argument("--seed", type=int, default=0, help="the sensors' noise seed (default 0)")
    ap.add_argument("--gallery-end", type=float, help="x [m] where the gallery leg turns back (default: past the ore)")
    args = ap.parse_args(argv)
    s = run(args.out, args.world, args.seed, args.gallery_end)
    m, g = s["magnetics"], s["gamma"]
    print(f"science survey: {s['sim_time_s']:.0f} s of sim time in {s['wall_time_s']:.1f} s of wall time")
    for r in s["samples"]:
        print(
            f"  bottle {r['bottle']}: {r['depth_m']:.1f} m, {r['temperature']:.2f} degC, "
            f"{r['conductivity']:.0f} uS/cm, pH {r['ph']:.2f}, redox {r['redox']:.0f} mV, O2 {r['oxygen']:.2f} mg/L"
        )
    print(
        f"  magnetic peak {m['peak_anomaly_nT']:.0f} nT at x = {m['peak_x_m']:.2f} m "
        f"(lens centre {m['lens_x_m']:.2f} m)"
    )
    print(f"  uranium zone found {g['zone_found_m']} m, in the world {g['zone_true_m']} m")
    print(f"  pass: {s['pass']}; outputs in {args.out}")
    return 0 if all(s["pass"].values()) else 1


if __name__ == "__main__":
    sys.exit(main())

"""Does the mapper keep up with lockstep? The mine world with the mapper on, UX_1 descending the shaft while
turning, stepped in 0.5 s chunks paced to a target real-time factor; each wall second, the clouds the
simulator has published (40 Hz M3 + 4 x 10 Hz SLS) against those the mapper has received and inserted, and
its pending queue. Not a test; docs/benchmarks.md "Mapping".

    python bench/mapper_rtf.py [--rtf 5] [--seconds 100]
"""

import argparse
import time

import rospy

from unexmin.control.allocation import ThrusterAllocator
from unexmin.msg import MapperStats
from unexmin.scripting.launcher import WorldProcess, wait_for
from unexmin.scripting.ros_backend import RosSimulation


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rtf", type=float, default=5.0)
    ap.add_argument("--seconds", type=float, default=100.0)
    args = ap.parse_args()
    world = WorldProcess(world="mine", robots=1, log_dir="/tmp/unexmin_mapper_rtf", extra_args=("mapping:=true",))
    sim = RosSimulation(world=world, timeout=120.0, node_name="mapper_rtf")
    stats = {}
    rospy.Subscriber("/mapper/stats", MapperStats, lambda m: stats.update(m=m), queue_size=10)
    wait_for(lambda: "m" in stats, 120.0, "/mapper/stats")
    ux = sim.robot("UX_1")
    ux.thrusts(ThrusterAllocator().allocate((0, 0, -4.0, 0, 0, 1.0))[0])
    sim.step(1)
    t0_sim, t0_wall = sim.time, time.monotonic()
    base = stats["m"].clouds_received
    worst_lag = worst_pending = 0
    rows = []
    next_report = t0_wall + 1.0
    while sim.time - t0_sim < args.seconds:
        sim.run_for(0.5)
        due = t0_wall + (sim.time - t0_sim) / args.rtf
        while time.monotonic() < due:  # pacing to the target RTF (wall clock on purpose: this measures it)
            time.sleep(0.005)
        if time.monotonic() >= next_report:
            next_report += 1.0
            m = stats["m"]
            published = round((sim.time - t0_sim) * 80)
            lag = published - (m.clouds_received - base)
            worst_lag, worst_pending = max(worst_lag, lag), max(worst_pending, m.pending)
            rows.append((sim.time - t0_sim, published, m.clouds_received - base, m.clouds_inserted - base, m.pending))
            print(
                f"sim {sim.time - t0_sim:6.1f} s  published {published:6d}  received {m.clouds_received - base:6d}  "
                f"inserted {m.clouds_inserted - base:6d}  pending {m.pending:4d}  dropped {m.clouds_dropped}",
                flush=True,
            )
    achieved = (sim.time - t0_sim) / (time.monotonic() - t0_wall)
    published = round((sim.time - t0_sim) * 80)
    wait_for(lambda: stats["m"].clouds_received - base >= published and stats["m"].pending == 0, 60.0, "the mapper")
    m = stats["m"]
    print(
        f"RTF {achieved:.2f} (target {args.rtf}); {published} clouds published, {m.clouds_received - base} received, "
        f"{m.clouds_dropped} dropped; worst lag behind the simulator {worst_lag} clouds "
        f"({worst_lag / 80:.2f} s of sim), worst pending {worst_pending}; insertion {m.insert_seconds:.2f} s of wall "
        f"for {m.points_inserted} points"
    )
    world.close()


if __name__ == "__main__":
    main()

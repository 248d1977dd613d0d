#!/usr/bin/env python3
"""Speed and memory of the Gymnasium environments (docs/gym.md, docs/benchmarks.md "Gymnasium environments").

    source scripts/env.sh && python bench/gym_speed.py [--steps 3000] [--repeat 3] [--vector-steps 2000]

1. Environment steps per second of one environment in this process (0.1 s of control per step, observation IMU +
   DVL + pressure + M3 sectors, random wrench actions, an episode reset whenever one ends, resets included):
   StationKeeping-v0 (the tank) and GalleryTransit-v0 (the mine); wall time and this process's CPU time, best of
   --repeat.
2. Gymnasium's AsyncVectorEnv of StationKeeping-v0 with 1 and with 2 worker processes (spawned): environment
   steps per second of wall time (a vector step of k environments counts k) and per second of the workers' CPU
   time, the ratio 2 against 1 (runs 1, 2, 2, 1 workers, so a drifting load weighs on both alike).
3. Memory per environment: resident set (RSS) and unique set (USS: what the process alone holds) of each
   AsyncVectorEnv worker (a spawned interpreter with one tank environment: Python, numpy, Gymnasium and the
   engine), after the steps.
The load average is printed before and after: the machine may be shared.
"""

import argparse
import os
import time

import gymnasium
import numpy as np

import unexmin.gym  # noqa: F401  (registers the environments)


def steps_per_second(env_id, steps, repeat):
    env = gymnasium.make(env_id)
    rng = np.random.default_rng(0)
    best = best_cpu = 0.0
    for r in range(repeat):
        env.reset(seed=r)
        t0, c0 = time.perf_counter(), time.process_time()
        for _ in range(steps):
            _, _, terminated, truncated, _ = env.step(rng.uniform(-0.3, 0.3, 4).astype(np.float32))
            if terminated or truncated:
                env.reset()
        best = max(best, steps / (time.perf_counter() - t0))
        best_cpu = max(best_cpu, steps / (time.process_time() - c0))
    env.close()
    return best, best_cpu


def vector(workers, steps):
    import psutil
    from gymnasium.vector import AsyncVectorEnv

    # "spawn": each worker a fresh interpreter, so its memory is what one environment's process holds
    vec = AsyncVectorEnv([make_station for _ in range(workers)], context="spawn")
    try:
        vec.reset(seed=list(range(workers)))
        actions = np.zeros((workers, 4), np.float32)
        vec.step(actions)  # the workers are up and stepping
        children = [psutil.Process(p.pid) for p in vec.processes]
        cpu0 = sum(sum(p.cpu_times()[:2]) for p in children)
        t0 = time.perf_counter()
        for _ in range(steps // workers):
            vec.step(actions)
        wall = time.perf_counter() - t0
        done = (steps // workers) * workers
        cpu = sum(sum(p.cpu_times()[:2]) for p in children) - cpu0
        memory = []
        for p in children:
            info = p.memory_full_info()
            memory.append((info.rss / 2**20, info.uss / 2**20))
    finally:
        vec.close()
    return done / wall, done / cpu, memory


def make_station():
    """StationKeeping-v0 (a spawned worker imports this module first: the environments are registered)."""
    return gymnasium.make("unexmin/StationKeeping-v0")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--steps", type=int, default=3000, help="environment steps per run (default 3000)")
    parser.add_argument("--repeat", type=int, default=3, help="runs per environment, the best counts")
    parser.add_argument("--vector-steps", type=int, default=2000, help="environment steps per vector run")
    parser.add_argument("--no-mine", action="store_true", help="skip the mine's environment")
    args = parser.parse_args()
    print(f"load average before: {os.getloadavg()}; {os.cpu_count()} hardware threads", flush=True)
    ids = ["unexmin/StationKeeping-v0"] + ([] if args.no_mine else ["unexmin/GalleryTransit-v0"])
    for env_id in ids:
        wall, cpu = steps_per_second(env_id, args.steps, args.repeat)
        print(f"{env_id}: {wall:.0f} env steps/s of wall time, {cpu:.0f} per second of CPU time", flush=True)
    rates = {}
    for workers in (1, 2, 2, 1):
        rate, per_cpu, memory = vector(workers, args.vector_steps)
        rates.setdefault(workers, []).append(rate)
        mem = ", ".join(f"RSS {rss:.0f} MB / USS {uss:.0f} MB" for rss, uss in memory)
        print(
            f"AsyncVectorEnv, {workers} worker(s): {rate:.0f} env steps/s of wall time, {per_cpu:.0f} per second of "
            f"the workers' CPU time (load {os.getloadavg()[0]:.1f}); per worker: {mem}",
            flush=True,
        )
    one, two = np.mean(rates[1]), np.mean(rates[2])
    print(f"AsyncVectorEnv 2 workers vs 1: {two / one:.2f}x ({two:.0f} vs {one:.0f} env steps/s, mean of 2 runs each)")
    print(f"load average after: {os.getloadavg()}")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Scores of the PID baselines (docs/gym.md, "Baselines"): each environment, seeds 0..N-1.

    source scripts/env.sh && python bench/gym_baselines.py [--seeds 5]

Per environment: the return (mean and standard deviation over the seeds), the episode length [s of sim time], and
a figure of merit: StationKeeping the largest distance from the station [m]; GalleryTransit whether the goal was
reached and the touches; WallFollowing the mean and largest |distance - set| [m] (from the ground truth).
"""

import argparse

import gymnasium
import numpy as np

import unexmin.gym  # noqa: F401  (registers the environments)
from unexmin.gym.baselines import baseline_for


def score(env_id, seeds):
    env = gymnasium.make(env_id)
    policy = baseline_for(env)
    returns, lengths, merit = [], [], []
    for seed in range(seeds):
        obs, info = env.reset(seed=seed)
        policy.reset()
        total, worst, errors, touched = 0.0, 0.0, [], False
        while True:
            obs, reward, terminated, truncated, info = env.step(policy(obs))
            total += reward
            worst = max(worst, info.get("distance", 0.0))
            errors.append(abs(info.get("distance_error", 0.0)))
            touched |= bool(info.get("touching", False))
            if terminated or truncated:
                break
        returns.append(total)
        lengths.append(info["time"])
        merit.append((worst, bool(info.get("reached", False)), touched, float(np.mean(errors)), max(errors)))
    env.close()
    return np.array(returns), np.array(lengths), merit


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seeds", type=int, default=5)
    args = parser.parse_args()
    for env_id in unexmin.gym.ENV_IDS:
        returns, lengths, merit = score(env_id, args.seeds)
        worst, reached, touched, mean_err, max_err = zip(*merit)
        print(
            f"{env_id}: return {returns.mean():.2f} +- {returns.std():.2f}; episode {lengths.mean():.1f} s "
            f"(min {lengths.min():.1f}); max distance from station {max(worst):.3f} m; reached {sum(reached)}/"
            f"{len(reached)}; touched {sum(touched)}/{len(touched)}; |distance error| mean {np.mean(mean_err):.3f} m, "
            f"max {max(max_err):.3f} m",
            flush=True,
        )


if __name__ == "__main__":
    main()

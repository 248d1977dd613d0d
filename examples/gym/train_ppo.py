#!/usr/bin/env python3
"""Train a PPO policy on a UX-1 environment with stable-baselines3, then score it against the PID baseline
(docs/gym.md, "Training").

    source scripts/env.sh && python examples/gym/train_ppo.py [--env unexmin/StationKeeping-v0] [--steps 200000]
                                                               [--workers 2] [--out ppo_station]

stable-baselines3 (and PyTorch, which it brings) is not a dependency of the project: install it in a venv of your
own (`pip install stable-baselines3`). The environments run in --workers processes (Gymnasium's AsyncVectorEnv
through stable-baselines3's SubprocVecEnv); the policy is saved to --out.zip and evaluated on 5 seeded episodes,
as is the PID baseline of unexmin.gym.baselines.
"""

import argparse
import sys

import gymnasium
import numpy as np

import unexmin.gym  # noqa: F401  (registers the environments)
from unexmin.gym.baselines import baseline_for, run_episode


def evaluate(env_id, act, episodes=5):
    """Mean and standard deviation of the return of policy `act(obs)` over seeded episodes 0..episodes-1."""
    env = gymnasium.make(env_id)
    returns = []
    for seed in range(episodes):
        obs, _ = env.reset(seed=seed)
        total, done = 0.0, False
        while not done:
            obs, reward, terminated, truncated, _ = env.step(act(obs))
            total += reward
            done = terminated or truncated
        returns.append(total)
    env.close()
    return float(np.mean(returns)), float(np.std(returns))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--env", default="unexmin/StationKeeping-v0", choices=sorted(unexmin.gym.ENV_IDS))
    parser.add_argument("--steps", type=int, default=200_000, help="environment steps of training")
    parser.add_argument("--workers", type=int, default=2, help="environment processes")
    parser.add_argument("--out", default="ppo_unexmin", help="the trained policy is saved to OUT.zip")
    args = parser.parse_args()
    try:
        from stable_baselines3 import PPO
        from stable_baselines3.common.env_util import make_vec_env
        from stable_baselines3.common.vec_env import SubprocVecEnv
    except ImportError:
        print("train_ppo: stable-baselines3 is not installed (pip install stable-baselines3)", file=sys.stderr)
        return 2
    envs = make_vec_env(args.env, n_envs=args.workers, seed=0, vec_env_cls=SubprocVecEnv)
    model = PPO("MlpPolicy", envs, verbose=1, seed=0)
    model.learn(total_timesteps=args.steps)
    model.save(args.out)
    envs.close()
    ppo = evaluate(args.env, lambda obs: model.predict(obs, deterministic=True)[0])
    env = gymnasium.make(args.env)
    pid = baseline_for(env)
    returns = [run_episode(env, pid, seed)[0] for seed in range(5)]
    env.close()
    print(f"{args.env}: PPO return {ppo[0]:.1f} +- {ppo[1]:.1f}; PID {np.mean(returns):.1f} +- {np.std(returns):.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

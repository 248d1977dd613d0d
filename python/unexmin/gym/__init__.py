"""Gymnasium environments of the UX-1's jobs on the engine in-process (docs/gym.md).

    import gymnasium, unexmin.gym
    env = gymnasium.make("unexmin/StationKeeping-v0")           # or GalleryTransit-v0, WallFollowing-v0
    obs, info = env.reset(seed=0)
    obs, reward, terminated, truncated, info = env.step(env.action_space.sample())

env.py: the common part (world, observations, actions, randomisation, seeding); tasks.py: the three jobs;
randomisation.py: the domain randomisation; baselines.py: a PID controller per job.
"""

import gymnasium

from unexmin.gym.tasks import GalleryTransitEnv, StationKeepingEnv, WallFollowingEnv

__all__ = ["ENV_IDS", "StationKeepingEnv", "GalleryTransitEnv", "WallFollowingEnv"]

#: Registered id -> entry point; each episode ends at its MAX_SECONDS of sim time (truncation by the env).
ENV_IDS = {
    "unexmin/StationKeeping-v0": "unexmin.gym.tasks:StationKeepingEnv",
    "unexmin/GalleryTransit-v0": "unexmin.gym.tasks:GalleryTransitEnv",
    "unexmin/WallFollowing-v0": "unexmin.gym.tasks:WallFollowingEnv",
}

for _id, _entry in ENV_IDS.items():
    if _id not in gymnasium.registry:
        gymnasium.register(id=_id, entry_point=_entry)

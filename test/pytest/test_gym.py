"""Gymnasium environments of the UX-1's jobs (python/unexmin/gym, docs/gym.md) on the engine in-process.

- Gymnasium's own checker passes on every registered environment (spaces, seeding, determinism).
- The PID baseline holds station within 0.2 m for 60 s in a 0.2 m/s current; the wall-following baseline keeps
  the distance it measures by sonar; the gallery baseline reaches its waypoint without touching the walls.
- Seeding as Gymnasium defines it: reset(seed=s) repeats an episode exactly, another seed draws another one.
- Domain randomisation against closed forms: the drawn current is the world's; a buoyancy offset of b kg makes
  the robot rise with the acceleration b g / (m - b + m_A) from rest.
- AsyncVectorEnv: two worker processes give the observations of two single environments with the same seeds.
- Bad arguments raise errors naming them.
"""

import math

import gymnasium
import numpy as np
import pytest

import unexmin.gym  # noqa: F401  (registers the environments)
from unexmin.gym.baselines import baseline_for, run_episode
from unexmin.gym.tasks import StationKeepingEnv

IDS = ("unexmin/StationKeeping-v0", "unexmin/GalleryTransit-v0", "unexmin/WallFollowing-v0")


@pytest.fixture(scope="module")
def envs():
    """One environment per id, made once (the mine's world takes seconds to load)."""
    made = {}
    yield lambda env_id: made.setdefault(env_id, gymnasium.make(env_id))
    for env in made.values():
        env.close()


@pytest.fixture(scope="module")
def station(envs):
    return envs(IDS[0]).unwrapped


@pytest.mark.parametrize("env_id", IDS)
def test_gymnasium_env_checker_passes(envs, env_id):
    from gymnasium.utils.env_checker import check_env

    env = envs(env_id)
    check_env(env.unwrapped, skip_render_check=True)
    obs, _ = env.reset(seed=1)
    assert obs.shape == env.observation_space.shape and np.all(np.isfinite(obs))


def test_pid_holds_station_within_20_cm_for_60_s_in_a_20_cm_per_s_current(station):
    obs, _ = station.reset(seed=0)
    np.testing.assert_allclose(station.world.current, [0.2, 0.0, 0.0], atol=1e-12)
    policy = baseline_for(station)
    policy.reset()
    worst, steps = 0.0, 0
    while True:
        obs, _, terminated, truncated, info = station.step(policy(obs))
        worst = max(worst, info["distance"])
        steps += 1
        if terminated or truncated:
            break
    assert truncated and not terminated and info["time"] == pytest.approx(60.0)
    assert steps == 600
    assert worst < 0.2, f"the robot drifted {worst:.3f} m from its station"
    # without control the same current carries it away: the test can fail
    station.reset(seed=0)
    for _ in range(100):
        _, _, terminated, _, info = station.step(np.zeros(4))
    assert info["distance"] > 0.2


def test_wall_following_baseline_keeps_its_sonar_distance(envs):
    env = envs(IDS[2]).unwrapped
    policy = baseline_for(env)
    obs, _ = env.reset(seed=0)
    policy.reset()
    errors = []
    while True:
        obs, _, terminated, truncated, info = env.step(policy(obs))
        errors.append(abs(info["distance_error"]))
        if terminated or truncated:
            break
    assert info["reached"] and not info["touching"] and not info["lost"], info
    assert max(errors) < 0.15, f"the distance to the wall was off by up to {max(errors):.3f} m"
    # without the sonar's distance the same surge drifts off: the test can fail
    obs, _ = env.reset(seed=0)
    for _ in range(100):
        obs, _, terminated, _, info = env.step([0.15, 0.05, 0.0, 0.0])
        if terminated:
            break
    assert info["lost"] or info["touching"] or abs(info["distance_error"]) > 0.15


def test_gallery_transit_baseline_reaches_its_waypoint_without_touching(envs):
    env = envs(IDS[1]).unwrapped
    total, steps, info = run_episode(env, baseline_for(env), seed=0)
    assert info["reached"] and not info["touching"], info
    assert info["time"] < env.MAX_SECONDS
    assert total > 10.0  # the route's length and the goal's bonus, less the effort


def test_reset_with_a_seed_repeats_the_episode(station):
    def episode(seed):
        obs, _ = station.reset(seed=seed)
        rng = np.random.default_rng(7)
        out = [obs]
        for _ in range(20):
            out.append(station.step(rng.uniform(-1, 1, 4))[0])
        return np.array(out)

    a, b, c = episode(3), episode(3), episode(4)
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c), "another seed gave the same sensor noise"


def test_randomised_current_is_the_worlds():
    env = StationKeepingEnv(randomise={"current_speed": [0.0, 0.3], "current_angle": [-math.pi, math.pi]})
    seen = []
    for seed in range(4):
        env.reset(seed=seed)
        p = env.parameters
        expected = p["current_speed"] * np.array([math.cos(p["current_angle"]), math.sin(p["current_angle"]), 0.0])
        np.testing.assert_allclose(env.world.current, expected, atol=1e-12)
        seen.append(p["current_speed"])
    assert len(set(seen)) == 4 and all(0.0 <= s <= 0.3 for s in seen)
    env.close()


def test_buoyancy_offset_lifts_the_robot_as_the_closed_form():
    from unexmin.description import parse
    from unexmin.gym.env import description

    env = StationKeepingEnv(randomise={"buoyancy_offset": 2.0, "current_speed": 0.0})
    env.reset(seed=0)
    z0 = env.robot.state()["position"][2]
    env.step(np.zeros(4))  # 0.1 s from rest: drag ~ v^2 is negligible
    z1 = env.robot.state()["position"][2]
    phys = parse(description())
    mass, added = phys.hydro.mass - 2.0, phys.hydro.added_mass[2, 2]
    a = 2.0 * 9.81 / (mass + added)
    assert z1 - z0 == pytest.approx(0.5 * a * 0.1**2, rel=0.05)
    env.close()


def test_async_vector_env_matches_single_envs():
    from gymnasium.vector import AsyncVectorEnv

    vec = AsyncVectorEnv([lambda: gymnasium.make(IDS[0]) for _ in range(2)])
    try:
        obs, _ = vec.reset(seed=[5, 6])
        actions = np.tile(np.array([[0.2, -0.1, 0.05, 0.1]], np.float32), (2, 1))
        for _ in range(5):
            obs, rewards, terminated, truncated, _ = vec.step(actions)
    finally:
        vec.close()
    for i, seed in enumerate((5, 6)):
        env = gymnasium.make(IDS[0])
        single, _ = env.reset(seed=seed)
        for _ in range(5):
            single, reward, *_ = env.step(actions[i])
        np.testing.assert_array_equal(obs[i], single)
        assert rewards[i] == reward
        env.close()


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"observation": "pixels"}, "observation = 'pixels'"),
        ({"action": "joystick"}, "action = 'joystick'"),
        ({"m3_sectors": 0}, "m3_sectors = 0"),
        ({"randomise": {"salinity": 1.0}}, "unknown parameter 'salinity'"),
        ({"randomise": {"current_speed": [0.3, 0.1]}}, "current_speed"),
        ({"randomise": {"visibility": "murky"}}, "visibility"),
        ({"randomise": {"damping_scale": 0.0}}, "damping_scale"),
    ],
)
def test_bad_arguments_are_named(kwargs, match):
    with pytest.raises(ValueError, match=match):
        StationKeepingEnv(**kwargs)


def test_bad_current_is_named(station):
    with pytest.raises(ValueError, match="speed"):
        station.world.set_current(-0.1)
    with pytest.raises(ValueError, match="horizontal_angle"):
        station.world.set_current(0.1, float("nan"))


def test_bad_action_is_named(station):
    station.reset(seed=0)
    with pytest.raises(ValueError, match="action"):
        station.step([float("nan")] * 4)
    with pytest.raises(ValueError):
        station.step([0.0] * 3)


def test_privileged_images_and_thrust_actions():
    from gymnasium.utils.env_checker import check_env

    env = StationKeepingEnv(observation="privileged", images=True, image_size=(32, 24), action="thrusts")
    check_env(env, skip_render_check=True)
    obs, _ = env.reset(seed=0)
    assert obs["image"].shape == (24, 32, 3) and obs["image"].dtype == np.uint8
    for _ in range(10):  # 1 s: the thrusters settle on their commands (first order, tau << 1 s)
        obs, *_ = env.step(np.full(8, 0.25))
    assert obs["image"].any(), "the camera rendered a black image: its lights and the tank are in view"
    s = env.robot.state()
    privileged = obs["vector"][-16:]
    np.testing.assert_allclose(privileged[:3], s["position"], atol=1e-6)
    np.testing.assert_allclose(privileged[3:7], s["orientation"], atol=1e-6)
    np.testing.assert_allclose(privileged[7:10], s["linear_velocity"], atol=1e-6)
    np.testing.assert_allclose(privileged[13:16], [0.2, 0.0, 0.0], atol=1e-6)
    np.testing.assert_allclose(env.robot.achieved_thrusts(), np.full(8, 0.25 * 40.0), rtol=1e-3)
    env.close()

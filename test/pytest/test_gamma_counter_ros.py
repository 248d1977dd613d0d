"""The gamma counter's topic (docs/gamma_counter.md): the ROS simulator publishes one unexmin/GammaCounts on
/UX_1/gamma per sample (1 Hz, stamped k s, frame UX_1/gamma_link), and its numbers are the in-process engine's samples
(unexmin.core, same world, seed and steps) bit for bit: the counts, the dead-time corrected rates, the dead-time
fraction and the integration time. 5 s of the tank with only the gamma counter on.
"""

import pytest
from lockstep_pairs import ros_environment_kept

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")  # rospy's own
SEED = 9
SECONDS = 5
KEYS = [
    "integration_time",
    "counts_total",
    "counts_potassium",
    "counts_uranium",
    "counts_thorium",
    "rate_total",
    "rate_potassium",
    "rate_uranium",
    "rate_thorium",
    "dead_time_fraction",
]


def run_ros(log_dir):
    from unexmin import Simulation

    with ros_environment_kept():
        with Simulation.launch("tank", robots=1, seed=SEED, sensors="gamma_counter", log_dir=log_dir) as sim:
            ux = sim.robot("UX_1", streams=["gamma"])
            with ux.collect("gamma") as gamma:
                sim.step(round(sim.physics_rate) * SECONDS)
            return list(gamma.messages)


def run_core():
    from unexmin.core import World

    w = World("tank", robots=1, seed=SEED, sensors="gamma_counter")
    ux = w.robot("UX_1")
    samples = []
    for _ in range(SECONDS):
        w.run_for(1.0)
        samples.append(ux.sample("gamma_counter"))
    return samples


def test_every_sample_is_published_with_the_in_process_numbers(tmp_path):
    messages = run_ros(str(tmp_path))
    samples = run_core()
    assert len(messages) == SECONDS, [m.header.stamp.to_sec() for m in messages]
    for k, (m, s) in enumerate(zip(messages, samples), start=1):
        assert m._type == "unexmin/GammaCounts"
        assert m.header.stamp.to_sec() == pytest.approx(float(k), abs=1e-9) and s["time"] == pytest.approx(float(k))
        assert m.header.frame_id == "UX_1/gamma_link"
        for key in KEYS:
            assert getattr(m, key) == s[key], f"sample {k}: {key} ROS {getattr(m, key)!r} vs core {s[key]!r}"
    assert sum(m.counts_total for m in messages) > 0  # the background counts (about 6 cps in total)

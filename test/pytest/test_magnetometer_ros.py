"""The magnetometer over ROS (cpp/unexmin/ros_layer/magnetometer_publisher.h, docs/magnetometer.md): the UX-1 in the
tank, 1 s of lockstep through `unexmin.Simulation`, every /UX_1/magnetometer message (sensor_msgs/MagneticField)
against the same samples in-process (`unexmin.core`): one message per sample at k / 50 Hz, the field in tesla equal
to the in-process nT x 1e-9 bit for bit, its covariance the white noise's and the quantisation's variance in T^2.
"""

import numpy as np
import pytest
from lockstep_pairs import ros_environment_kept

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")  # rospy's own
SEED = 4
CHUNK = 10  # physics steps per step call
RATE = 50.0  # [Hz] urdf/properties.xacro magnetometer_rate
NOISE, RESOLUTION = 0.1, 0.01  # [nT] urdf/properties.xacro magnetometer_noise, magnetometer_resolution


def run_ros(log_dir):
    from unexmin import Simulation

    with ros_environment_kept():
        with Simulation.launch("tank", seed=SEED, sensors="magnetometer", log_dir=log_dir) as sim:
            ux = sim.robot("UX_1", streams=[])
            steps = round(sim.physics_rate)
            with ux.collect("magnetometer") as mag:
                for _ in range(steps // CHUNK):
                    sim.step(CHUNK)
            return list(mag.messages)


def run_core():
    from unexmin.core import World

    w = World("tank", seed=SEED, sensors="magnetometer")
    ux = w.robot("UX_1")
    out = []
    for _ in range(round(1.0 / w.dt)):
        w.step(1)
        s = ux.sample("magnetometer")
        if s["count"] > len(out):
            out.append((s["time"], s["magnetic_field"].copy()))
    return out


def test_every_sample_is_published_in_tesla_bit_for_bit(tmp_path):
    ros, core = run_ros(str(tmp_path)), run_core()
    assert len(ros) == len(core) == int(RATE)
    for k, (m, (t, b)) in enumerate(zip(ros, core)):
        assert m.header.stamp.to_sec() == pytest.approx((k + 1) / RATE, abs=1e-9) == pytest.approx(t, abs=1e-9)
        assert m.header.frame_id == "UX_1/magnetometer_link"
        assert [m.magnetic_field.x, m.magnetic_field.y, m.magnetic_field.z] == [v * 1e-9 for v in b]
    variance = (NOISE**2 + RESOLUTION**2 / 12) * 1e-18
    assert np.allclose(np.reshape(ros[0].magnetic_field_covariance, (3, 3)), np.eye(3) * variance, rtol=1e-12, atol=0)
    last = ros[-1].magnetic_field
    assert 40e-6 < np.linalg.norm([last.x, last.y, last.z]) < 60e-6  # [T] the Earth's field, about 52 uT

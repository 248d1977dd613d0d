"""The fluxgate magnetometer (docs/magnetometer.md) through unexmin.core, without ROS: its sample's fields and units,
and the reading against the closed form R_m^T (S R^T F + h) of the UX-1's description (urdf/properties.xacro: the
hard and soft iron, thrusters at rest) in the tank world (the default Earth field, no geology), within the sensor's
turn-on bias and noise.

Run: python -m pytest test/pytest/test_magnetometer_core.py (workspace built and sourced)."""

import numpy as np
import pytest

from unexmin import description
from unexmin.core import World

F_MG = np.array([24.0, 134.0, -508.0])  # [mG] the world's default field (cpp/unexmin/sim/world_config.h)


def quaternion_matrix(x, y, z, w):
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


@pytest.fixture(scope="module")
def ux1():
    urdf = description.expand(description.ROBOT_FILE, "UX_1")
    return urdf, description.parse(urdf)


def test_the_sample_gives_the_field_in_nanotesla(ux1):
    urdf, robot = ux1
    w = World("tank", seed=5, sensors="magnetometer", descriptions={"UX_1": urdf})
    ux = w.robot("UX_1")
    assert [f[:3] for f in ux.sample_fields("magnetometer")] == [
        ("time", "s", "float64"),
        ("count", "", "uint64"),
        ("magnetic_field", "nT", "float64"),
        ("total_field", "nT", "float64"),
    ]
    ux.set_pose((0.0, 0.0, -1.0), (0.0, 0.0, np.sin(0.35), np.cos(0.35)))  # yawed 0.7 rad
    w.step(10)  # 50 Hz at 500 Hz physics: one sample
    s = ux.sample("magnetometer")
    assert s["count"] == 1 and s["time"] == pytest.approx(0.02)
    assert s["magnetic_field"].shape == (3,)
    st = ux.state()
    R = quaternion_matrix(*st["orientation"])
    mag = robot.magnetics
    sensor = next(x for x in robot.sensors if x.type == "magnetometer")
    expected = sensor.rotation.T @ (mag.soft_iron @ R.T @ (F_MG * 100.0) + mag.hard_iron)
    bias = sensor.params["field_bias"][0]
    assert np.abs(s["magnetic_field"] - expected).max() < 5 * bias  # the turn-on bias, 1 sigma 5 nT
    assert np.linalg.norm(mag.hard_iron) > 10 * 5 * bias  # so the robot's own field shows
    assert s["total_field"] == pytest.approx(np.linalg.norm(s["magnetic_field"]), rel=1e-12)

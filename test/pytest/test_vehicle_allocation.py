"""The allocation from a vehicle's own description (unexmin.control.vehicle_allocation, docs/thruster_allocator.md
"Any vehicle"): the BlueROV2 Heavy's commanded wrench is produced exactly, the REMUS 100's propeller and rudders
against closed forms from Prestero's numbers. No roscore.

Run: /work/main_ws/venv/bin/python -m pytest test/pytest/test_vehicle_allocation.py
"""

import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from test_vehicle_descriptions import description

from unexmin.control.allocation import AllocationError
from unexmin.control.vehicle_allocation import VehicleAllocator

# The published layout [vB22], written here by hand: horizontal thrusters at x = +-0.156, y = +-0.111 m, thrust at
# 45 deg (0 front left and 3 rear right turned to starboard), vertical ones at x = +-0.12, y = +-0.218 m, thrust up.
C = math.sqrt(0.5)
ROV_POSITIONS = [(0.156, 0.111, 0), (0.156, -0.111, 0), (-0.156, 0.111, 0), (-0.156, -0.111, 0)] + [
    (0.12, 0.218, 0),
    (0.12, -0.218, 0),
    (-0.12, 0.218, 0),
    (-0.12, -0.218, 0),
]
ROV_AXES = [(C, -C, 0), (C, C, 0), (C, C, 0), (C, -C, 0)] + [(0, 0, 1)] * 4
ROV_B = np.array([np.concatenate([a, np.cross(p, a)]) for p, a in zip(ROV_POSITIONS, ROV_AXES)]).T
# T200 table of the description: pulse width offset [us] -> thrust [N]
T200_IN = [-400, -300, -200, -100, -24, 24, 100, 200, 300, 400]
T200_OUT = [-40.2, -27.5, -15.4, -5.4, 0, 0, 7.5, 21.5, 35.5, 51.5]

# Prestero 2001: fin area [m^2], lift slope [1/rad], fin position [m]; propeller thrust 3.86 N at 1500 rpm
S_FIN, CLA, X_FIN, GAIN = 0.00665, 3.12, -0.638, 3.86 / 1500.0**2


def xml_of(name):
    return ET.tostring(description(name), encoding="unicode")


@pytest.fixture(scope="module")
def rov():
    return VehicleAllocator(xml_of("ROV_1"))


@pytest.fixture(scope="module")
def auv():
    return VehicleAllocator(xml_of("AUV_1"), dofs="X K M N", rho=1000.0, fin_min_speed=0.2)


def thrust_of(commands):
    return np.interp(commands, T200_IN, T200_OUT)


def test_rov_configuration_is_the_published_layout(rov):
    np.testing.assert_allclose(rov.matrix(), ROV_B, atol=1e-12)


def test_rov_commanded_wrench_is_produced_by_the_allocated_thrusts(rov):
    rng = np.random.default_rng(26)
    for _ in range(50):
        tau = rng.uniform(-1, 1, 6) * [20, 20, 30, 2, 2, 3]  # [N], [N m]: within the thrusters' reach
        commands, fins, scale = rov.allocate(tau)
        assert scale == 1.0 and fins == []
        assert all(-400 <= c <= 400 for c in commands)
        np.testing.assert_allclose(ROV_B @ thrust_of(commands), tau, atol=1e-9)


def test_rov_surge_is_shared_by_the_four_horizontal_thrusters(rov):
    commands, _, _ = rov.allocate([10, 0, 0, 0, 0, 0])
    thrusts = thrust_of(commands)
    np.testing.assert_allclose(thrusts, [10 / (4 * C)] * 4 + [0] * 4, atol=1e-9)
    # 3.536 N lies between 24 us (0 N) and 100 us (7.5 N) of the table
    assert commands[0] == pytest.approx(24 + 76 * (10 / (4 * C)) / 7.5, abs=1e-9)
    assert commands[4:] == [0.0] * 4, "no vertical thrust: the neutral pulse"


def test_rov_saturation_keeps_the_wrench_direction(rov):
    tau = np.array([400.0, 0, 0, 0, 0, 30.0])
    commands, _, scale = rov.allocate(tau)
    thrusts = thrust_of(commands)
    assert 0 < scale < 1
    assert max(thrusts) == pytest.approx(51.5, abs=1e-9)
    np.testing.assert_allclose(ROV_B @ thrusts, scale * tau, atol=1e-9)


def test_auv_propeller_rpm_and_rudders_against_prestero(auv):
    u, rho, n_cmd, x_cmd = 1.5, 1000.0, 0.5, 2.0
    commands, fins, scale = auv.allocate([x_cmd, 0, 0, 0, 0, n_cmd], surge_speed=u)
    assert scale == 1.0
    assert commands == [pytest.approx(math.sqrt(x_cmd / GAIN), rel=1e-9)]  # 1080 rpm
    # two rudders at x_fin: N = 2 (1/2 rho u^2 S C_L' delta) x_fin  ->  delta = N / (rho u^2 S C_L' x_fin)
    rudder = n_cmd / (rho * u**2 * S_FIN * CLA * X_FIN)
    assert fins[:2] == [pytest.approx(rudder, rel=1e-9)] * 2
    assert fins[2:] == [pytest.approx(0.0, abs=1e-12)] * 4, "no pitch command, fixed surfaces at 0"
    # elevators (span +y): lift -z per radian, M = 2 x_fin (1/2 rho u^2 S C_L' delta); nose up is M < 0
    m_cmd = -0.3
    _, fins_pitch, _ = auv.allocate([0, 0, 0, 0, m_cmd, 0], surge_speed=u)
    assert fins_pitch[2:4] == [pytest.approx(m_cmd / (rho * u**2 * S_FIN * CLA * X_FIN), rel=1e-9)] * 2
    assert fins_pitch[:2] == [pytest.approx(0.0, abs=1e-12)] * 2


def test_auv_fins_within_limits_and_idle_below_the_minimum_speed(auv):
    limit = math.radians(13.6)
    _, fins, _ = auv.allocate([0, 0, 0, 0, 0, 50.0], surge_speed=1.0)
    assert fins[:2] == [pytest.approx(-limit)] * 2
    commands, fins, _ = auv.allocate([100.0, 0, 0, 0, 0, 0.5], surge_speed=0.1)
    assert fins == [0.0] * 6
    assert commands == [pytest.approx(1500.0)], "the propeller saturates at its rpm limit"


@pytest.mark.parametrize(
    "change, words",
    [
        (('type="table"', 'type="fancy"'), "conversion 'fancy' has no inverse"),
        (("-40.2 -27.5", "-20.0 -27.5"), "cannot be inverted"),
    ],
)
def test_descriptions_it_cannot_invert_are_refused(change, words):
    xml = xml_of("ROV_1").replace(*change)
    with pytest.raises(AllocationError, match=words):
        VehicleAllocator(xml, source="ROV_1.urdf")


@pytest.mark.parametrize("dofs", ["", "X X", "X Q"])
def test_bad_degrees_of_freedom_are_refused(dofs):
    with pytest.raises(AllocationError, match="expected distinct names among X Y Z K M N"):
        VehicleAllocator(xml_of("ROV_1"), dofs=dofs)

"""Thruster allocation (python/unexmin/control/allocation.py): the thesis matrix, m = A^T tau, saturation.

Pure maths: no roscore. Expected values are written out from the thesis (eq. 5.12) and computed
here from the definition, never taken from a previous run. The last test checks the allocation
against the thruster geometry of the shipped robot description (expanded with xacro).

Run: /work/main_ws/venv/bin/python -m pytest test/pytest/test_allocation.py
"""

import math
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from unexmin.control.allocation import (
    DEFAULT_MAX_THRUST,
    DOF,
    THESIS_MATRIX,
    AllocationError,
    ThrusterAllocator,
    validate_matrix,
    validate_max_thrust,
    validate_wrench,
)
from unexmin.geometry import rpy_matrix

REPO = Path(__file__).resolve().parents[2]

# Thesis eq. 5.12, typed in again: rows X Y Z K M N, columns M0..M7.
A = np.array(
    [
        [0.5, 0.0, -0.50, 0.0, 0.50, 0.0, -0.50, 0.0],
        [-0.25, -0.25, -0.25, 0.25, 0.25, -0.25, 0.25, -0.25],
        [0.0, -0.50, 0.0, -0.5, 0.0, 0.50, 0.0, -0.50],
        [0, 0, 0, 0, 0, 0, 0, 0],
        [0, 0, 0, 0, 0, 0, 0, 0],
        [-0.25, 0.0, 0.25, 0.0, 0.25, 0.0, -0.25, 0.0],
    ]
)


def test_default_matrix_is_the_thesis_matrix():
    assert np.array(THESIS_MATRIX).shape == (6, 8)
    np.testing.assert_array_equal(np.array(THESIS_MATRIX), A)
    np.testing.assert_array_equal(ThrusterAllocator().matrix, A)
    assert ThrusterAllocator().max_thrust == DEFAULT_MAX_THRUST == 40.0


@pytest.mark.parametrize("axis", ["X", "Y", "Z", "N"])
def test_unit_wrench_gives_the_matrix_row_of_that_axis(axis):
    tau = np.zeros(6)
    tau[DOF.index(axis)] = 1.0
    thrusts, scale = ThrusterAllocator().allocate(tau)
    assert scale == 1.0
    np.testing.assert_allclose(thrusts, A[DOF.index(axis)], atol=1e-15)


def test_allocation_is_the_sum_over_wrench_components():
    rng = np.random.default_rng(1234)
    alloc = ThrusterAllocator(max_thrust=1e9)
    for _ in range(50):
        tau = rng.uniform(-20, 20, 6)
        expected = [sum(A[j][i] * tau[j] for j in range(6)) for i in range(8)]
        thrusts, scale = alloc.allocate(tau)
        assert scale == 1.0
        np.testing.assert_allclose(thrusts, expected, rtol=1e-12, atol=1e-12)


def test_roll_and_pitch_commands_give_no_thrust():
    thrusts, _ = ThrusterAllocator().allocate([0, 0, 0, 7.0, -3.0, 0])
    np.testing.assert_array_equal(thrusts, np.zeros(8))


def test_saturation_scales_the_whole_vector_and_keeps_the_direction():
    rng = np.random.default_rng(99)
    alloc = ThrusterAllocator(max_thrust=40.0)
    for _ in range(50):
        tau = rng.uniform(-300, 300, 6)
        raw = A.T @ tau
        peak = np.max(np.abs(raw))
        thrusts, scale = alloc.allocate(tau)
        if peak <= 40.0:
            assert scale == 1.0
            continue
        assert scale == pytest.approx(40.0 / peak, rel=1e-12)
        assert np.max(np.abs(thrusts)) == pytest.approx(40.0, rel=1e-12)
        # Same direction: thrusts is a positive multiple of the unsaturated vector, so the wrench
        # it produces (any linear map of it) is a positive multiple of the commanded one.
        np.testing.assert_allclose(thrusts, raw * (40.0 / peak), rtol=1e-12, atol=1e-12)
        cos = thrusts @ raw / (np.linalg.norm(thrusts) * np.linalg.norm(raw))
        assert cos == pytest.approx(1.0, abs=1e-12)


def test_saturation_boundary_is_not_scaled():
    # Forward 80: every horizontal thruster gets exactly 0.5 * 80 = 40 N, the limit itself.
    thrusts, scale = ThrusterAllocator(max_thrust=40.0).allocate([80, 0, 0, 0, 0, 0])
    assert scale == 1.0
    np.testing.assert_allclose(np.abs(thrusts[[0, 2, 4, 6]]), 40.0)


def test_flat_row_major_matrix_is_accepted():
    np.testing.assert_array_equal(validate_matrix(A.reshape(-1).tolist()), A)


@pytest.mark.parametrize(
    "matrix, words",
    [
        ([[1, 2], [3, 4]], ["allocation_matrix", "6 x n", "2 x 2"]),
        ([1.0] * 13, ["allocation_matrix", "6 x n", "13"]),
        ([[0.5] * 8] * 5 + [[float("nan")] + [0.5] * 7], ["allocation_matrix", "[N][M0]", "not a finite"]),
        ([[0.5, 0.0]] + [[0.2, 0.0]] * 5, ["allocation_matrix", "M1", "all zero"]),
        ("not a matrix", ["allocation_matrix"]),
    ],
)
def test_bad_matrix_is_rejected_with_the_parameter_name(matrix, words):
    with pytest.raises(AllocationError) as e:
        validate_matrix(matrix)
    for w in words:
        assert w in str(e.value)


@pytest.mark.parametrize("value", [0, -1, float("nan"), float("inf"), "x", None])
def test_bad_max_thrust_is_rejected(value):
    with pytest.raises(AllocationError, match="max_thrust"):
        validate_max_thrust(value)
    with pytest.raises(AllocationError, match="max_thrust"):
        ThrusterAllocator(max_thrust=value)


@pytest.mark.parametrize(
    "wrench, words",
    [
        ([1, 2, 3], ["6 numbers", "3"]),
        ([0, 0, float("nan"), 0, 0, float("inf")], ["Z", "N", "not finite"]),
    ],
)
def test_bad_wrench_is_rejected(wrench, words):
    with pytest.raises(AllocationError) as e:
        validate_wrench(wrench)
    for w in words:
        assert w in str(e.value)
    with pytest.raises(AllocationError):
        ThrusterAllocator().allocate(wrench)


# ---------------------------------------------------------------------------------------------
# The allocation against the shipped robot's thruster geometry (urdf/)
# ---------------------------------------------------------------------------------------------
def _xacro():
    local = Path(sys.executable).parent / "xacro"
    return str(local) if local.exists() else shutil.which("xacro")


def geometry_matrix():
    """B (6 x 8): body force and moment about the hull centre per newton of each thruster."""
    exe = _xacro()
    if not exe:
        pytest.skip("xacro not installed")
    urdf = subprocess.run(
        [exe, str(REPO / "urdf" / "ux1.urdf.xacro"), "name:=UX_1"], check=True, capture_output=True, text=True
    ).stdout
    joints = {j.get("name"): j for j in ET.fromstring(urdf).iter("joint")}
    B = np.zeros((6, 8))
    for i in range(8):
        j = joints[f"UX_1/thruster_{i}_joint"]
        o = j.find("origin")
        r = np.array([float(v) for v in o.get("xyz").split()])
        axis = np.array([float(v) for v in j.find("axis").get("xyz").split()])
        d = rpy_matrix([float(v) for v in o.get("rpy").split()]) @ axis
        B[:3, i], B[3:, i] = d, np.cross(r, d)
    return B


def test_robot_geometry_produces_the_commanded_axis_only():
    """With the shipped geometry B, the wrench produced by m = A^T tau is B A^T tau: diagonal, positive
    on X, Y, Z, N (sqrt 2, sqrt 2, sqrt 2 and r_t = 0.3 m), so a command on one axis moves on that
    axis only (the rostest checks the same in the simulator)."""
    B = geometry_matrix()
    G = B @ A.T
    expected = np.diag([math.sqrt(2), math.sqrt(2), math.sqrt(2), 0.0, 0.0, 0.3])
    np.testing.assert_allclose(G, expected, atol=1e-9)

"""Rotation maths (python/unexmin/geometry.py) against closed forms: elementary rotations typed in
here, known quaternions, and round trips on seeded random angles."""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from unexmin.geometry import quaternion_to_rpy, rpy_matrix, rpy_of, rpy_quaternion, wrap_angle, yaw_of


def quat_matrix(q):
    """Rotation matrix of the unit quaternion (x, y, z, w), textbook formula."""
    x, y, z, w = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def elementary(r, p, y):
    rx = np.array([[1, 0, 0], [0, math.cos(r), -math.sin(r)], [0, math.sin(r), math.cos(r)]])
    ry = np.array([[math.cos(p), 0, math.sin(p)], [0, 1, 0], [-math.sin(p), 0, math.cos(p)]])
    rz = np.array([[math.cos(y), -math.sin(y), 0], [math.sin(y), math.cos(y), 0], [0, 0, 1]])
    return rz @ ry @ rx


def test_rpy_matrix_is_rz_ry_rx_and_the_quaternion_agrees():
    rng = np.random.default_rng(4)
    for rpy in rng.uniform(-math.pi, math.pi, (20, 3)):
        np.testing.assert_allclose(rpy_matrix(rpy), elementary(*rpy), atol=1e-12)
        q = rpy_quaternion(rpy)
        assert np.linalg.norm(q) == pytest.approx(1.0)
        np.testing.assert_allclose(quat_matrix(q), elementary(*rpy), atol=1e-12)
    np.testing.assert_allclose(rpy_quaternion((0, 0, math.pi / 2)), (0, 0, math.sqrt(0.5), math.sqrt(0.5)))


def test_quaternion_to_rpy_known_rotations():
    h = math.sqrt(0.5)
    assert quaternion_to_rpy(0, 0, h, h) == pytest.approx((0, 0, math.pi / 2))
    assert quaternion_to_rpy(h, 0, 0, h) == pytest.approx((math.pi / 2, 0, 0))
    assert quaternion_to_rpy(0, math.sin(math.pi / 6), 0, math.cos(math.pi / 6)) == pytest.approx((0, math.pi / 3, 0))
    # ZYX: yaw 30 deg, pitch 14 deg, roll 8 deg, quaternion typed in from the half-angle formula
    r, p, y = math.radians(8), math.radians(14), math.radians(30)
    cr, sr, cp, sp, cy, sy = (
        math.cos(r / 2),
        math.sin(r / 2),
        math.cos(p / 2),
        math.sin(p / 2),
        math.cos(y / 2),
        math.sin(y / 2),
    )
    q = (
        sr * cp * cy - cr * sp * sy,
        cr * sp * cy + sr * cp * sy,
        cr * cp * sy - sr * sp * cy,
        cr * cp * cy + sr * sp * sy,
    )
    assert quaternion_to_rpy(*q) == pytest.approx((r, p, y))


def test_round_trip_rpy_quaternion_rpy():
    rng = np.random.default_rng(11)
    for r, p, y in zip(rng.uniform(-3.1, 3.1, 50), rng.uniform(-1.5, 1.5, 50), rng.uniform(-3.1, 3.1, 50)):
        x, qy, z, w = rpy_quaternion((r, p, y))
        assert quaternion_to_rpy(x, qy, z, w) == pytest.approx((r, p, y), abs=1e-9)
        msg = SimpleNamespace(x=x, y=qy, z=z, w=w)  # a geometry_msgs/Quaternion's fields
        assert rpy_of(msg) == pytest.approx((r, p, y), abs=1e-9)
        assert yaw_of(msg) == pytest.approx(y, abs=1e-9)


def test_wrap_angle():
    np.testing.assert_allclose(
        wrap_angle([0, math.pi / 2, 3 * math.pi / 2, -3 * math.pi / 2, 2 * math.pi]),
        [0, math.pi / 2, -math.pi / 2, math.pi / 2, 0],
        atol=1e-12,
    )
    assert float(wrap_angle(math.pi)) == pytest.approx(-math.pi)  # [-pi, pi)

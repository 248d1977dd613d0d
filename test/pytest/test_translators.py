"""KVH and DVL translators (python/unexmin/translators/{kvh,dvl}.py): unit conversions against their
definitions, round trips (message in -> translated -> back: the same numbers), invalid markers and the
real robot's type names. Pure functions: no ROS master needed.

Run: /work/main_ws/venv/bin/python -m pytest test/pytest/test_translators.py (workspace sourced).
"""

import math

import numpy as np
import pytest

pytest.importorskip("kvh_1775.msg", reason="source the workspace (scripts/env.sh) to import the messages")

from dvl_nortek.msg import DvlBottomWaterTrack  # noqa: E402
from kvh_1775.msg import ImuRawKvh  # noqa: E402

from unexmin.msg import Dvl, ImuRaw  # noqa: E402
from unexmin.translators.dvl import dvl_to_water_track, water_track_to_dvl  # noqa: E402
from unexmin.translators.kvh import kvh_to_raw, raw_to_kvh  # noqa: E402

BEAM_ANGLE = math.radians(25.0)
AZIMUTHS = [0.0, math.pi / 2, math.pi, 3 * math.pi / 2]


def test_type_names_are_the_real_robots():
    assert ImuRawKvh._type == "kvh_1775/ImuRawKvh"
    assert DvlBottomWaterTrack._type == "dvl_nortek/DvlBottomWaterTrack"


# ------------------------------------------------------------------------------------------------ KVH
def random_raw(rng):
    m = ImuRaw()
    m.header.seq = int(rng.integers(0, 1 << 31))
    m.header.stamp.secs, m.header.stamp.nsecs = int(rng.integers(0, 1 << 20)), int(rng.integers(0, 10**9))
    m.header.frame_id = "UX_1/imu_link"
    m.linear_acceleration.x, m.linear_acceleration.y, m.linear_acceleration.z = rng.normal(0, 5, 3)
    m.angular_velocity.x, m.angular_velocity.y, m.angular_velocity.z = rng.normal(0, 1, 3)
    m.magnetic_field.x, m.magnetic_field.y, m.magnetic_field.z = rng.normal(0, 5e-5, 3)  # [T], ~500 mG
    m.temperature = rng.uniform(-5, 60)
    m.pressure = rng.uniform(1e5, 5e6)  # [Pa]
    m.pressure_temperature = rng.uniform(0, 30)
    return m


def test_kvh_units_are_milligauss_and_bar():
    raw = ImuRaw()
    raw.magnetic_field.x = 5.0e-5  # 0.5 G
    raw.pressure = 201325.0  # [Pa]
    raw.linear_acceleration.z = 9.81
    kvh = raw_to_kvh(raw)
    assert kvh.magnetometer.x == pytest.approx(500.0, rel=1e-12)  # [mG]
    assert kvh.pressure == pytest.approx(2.01325, rel=1e-12)  # [bar]
    assert kvh.accelerometer.z == 9.81


def test_kvh_round_trip_keeps_every_number():
    rng = np.random.default_rng(1)
    for _ in range(200):
        raw = random_raw(rng)
        back = kvh_to_raw(raw_to_kvh(raw))
        assert back.header == raw.header
        for field in ("linear_acceleration", "angular_velocity", "magnetic_field"):
            a, b = getattr(raw, field), getattr(back, field)
            assert (b.x, b.y, b.z) == pytest.approx((a.x, a.y, a.z), rel=1e-12, abs=0.0), field
        for field in ("temperature", "pressure", "pressure_temperature"):
            assert getattr(back, field) == pytest.approx(getattr(raw, field), rel=1e-12), field
        # and the other way round
        kvh = raw_to_kvh(raw)
        again = raw_to_kvh(kvh_to_raw(kvh))
        assert again.magnetometer.y == pytest.approx(kvh.magnetometer.y, rel=1e-12)
        assert again.pressure == pytest.approx(kvh.pressure, rel=1e-12)


# ------------------------------------------------------------------------------------------------ DVL
def beams():
    s, c = math.sin(BEAM_ANGLE), math.cos(BEAM_ANGLE)
    return np.array([[s * math.cos(a), s * math.sin(a), c] for a in AZIMUTHS])


def ping(v, altitude, sigma, valid=(True, True, True, True), sound_speed=1446.6, pressure=1.2e5):
    """A Dvl message as the simulator's model builds it for DVL velocity v [m/s] over a flat bottom
    at `altitude` [m] along z (formulas of cpp/unexmin/sensors/dvl_sensor.h)."""
    B = beams()
    m = Dvl()
    m.header.stamp.secs, m.header.stamp.nsecs = 12, 125000000
    m.header.frame_id = "UX_1/dvl_link"
    m.beam_angle = BEAM_ANGLE
    m.beam_azimuth = AZIMUTHS
    m.sound_speed, m.temperature, m.pressure = sound_speed, 9.8, pressure
    m.beam_valid = list(valid)
    u = B @ v
    slant = altitude / math.cos(BEAM_ANGLE)
    m.range = [slant + 0.01 * i if ok else math.inf for i, ok in enumerate(valid)]
    m.beam_velocity = [u[i] if ok else math.nan for i, ok in enumerate(valid)]
    m.beam_velocity_std = [sigma] * 4
    used = [i for i in range(4) if valid[i]]
    m.bottom_lock = len(used) >= 3
    if m.bottom_lock:
        Bv = B[used]
        m.velocity.x, m.velocity.y, m.velocity.z = np.linalg.lstsq(Bv, u[used], rcond=None)[0]
        m.velocity_covariance = list((sigma**2 * np.linalg.inv(Bv.T @ Bv)).ravel())
        c = math.cos(BEAM_ANGLE)
        m.velocity_z1 = (u[0] + u[2]) / (2 * c) if valid[0] and valid[2] else math.nan
        m.velocity_z2 = (u[1] + u[3]) / (2 * c) if valid[1] and valid[3] else math.nan
        m.altitude = float(np.mean([m.range[i] * c for i in used]))
    else:
        m.velocity.x = m.velocity.y = m.velocity.z = math.nan
        m.velocity_covariance = [-1.0] * 9
        m.velocity_z1 = m.velocity_z2 = m.altitude = math.nan
    return m


def test_water_track_fields_follow_their_definitions():
    v = np.array([0.3, -0.1, 0.05])
    sigma = 0.003
    m = ping(v, altitude=1.7, sigma=sigma)
    t = dvl_to_water_track(m)
    c, s = math.cos(BEAM_ANGLE), math.sin(BEAM_ANGLE)
    assert t.header == m.header
    assert t.sound_speed == m.sound_speed and t.temperature == m.temperature
    assert t.pressure == pytest.approx(12.0)  # 1.2e5 Pa = 12 dbar
    for i in range(4):
        assert t.range[i] == pytest.approx(m.range[i] * c)  # vertical distance
        assert t.velocity_beam[i] == pytest.approx(beams()[i] @ v)
        assert t.fom_beam[i] == sigma
        assert t.dt1_beam[i] == pytest.approx(2 * m.range[i] / m.sound_speed)
        assert t.time_beam[i] == pytest.approx(m.range[i] / m.sound_speed)
    assert max(t.dt2_beam) == pytest.approx(t.dt1_beam[3] - t.dt1_beam[0])  # beam 3 is the last echo
    assert min(t.dt2_beam) == 0.0
    # Janus pairs: x, z1 from beams 0 and 2; y, z2 from 1 and 3.
    assert t.velocity_xyzz == pytest.approx([v[0], v[1], v[2], v[2]], abs=1e-12)
    assert t.fom_xyzz[0] == pytest.approx(sigma / (math.sqrt(2) * s))
    assert t.fom_xyzz[2] == pytest.approx(sigma / (math.sqrt(2) * c))
    assert t.dt1_xyzz[0] == pytest.approx((t.dt1_beam[0] + t.dt1_beam[2]) / 2)
    assert t.dt1_xyzz[3] == pytest.approx((t.dt1_beam[1] + t.dt1_beam[3]) / 2)


def test_dvl_round_trip_keeps_every_number():
    rng = np.random.default_rng(2)
    for _ in range(200):
        v = rng.normal(0, 0.5, 3)
        m = ping(
            v,
            altitude=rng.uniform(0.2, 70),
            sigma=rng.uniform(1e-3, 1e-2),
            sound_speed=rng.uniform(1420, 1540),
            pressure=rng.uniform(1e5, 5e6),
        )
        back = water_track_to_dvl(dvl_to_water_track(m), BEAM_ANGLE, AZIMUTHS)
        assert back.header == m.header
        assert back.bottom_lock
        assert (back.velocity.x, back.velocity.y, back.velocity.z) == pytest.approx(tuple(v), abs=1e-12)
        assert back.velocity_z1 == pytest.approx(m.velocity_z1, abs=1e-12)
        assert back.range == pytest.approx(m.range, rel=1e-12)
        assert back.beam_velocity == pytest.approx(m.beam_velocity, abs=1e-12)
        assert back.beam_velocity_std == pytest.approx(m.beam_velocity_std)
        assert back.altitude == pytest.approx(m.altitude, rel=1e-12)
        assert back.pressure == pytest.approx(m.pressure, rel=1e-12)
        assert (back.sound_speed, back.temperature) == (m.sound_speed, m.temperature)
        for k in (0, 4, 8):  # variances of x, y, z
            assert back.velocity_covariance[k] == pytest.approx(m.velocity_covariance[k], rel=1e-9), k


def test_three_beams_keep_the_lock_and_mark_the_lost_beam_invalid():
    v = np.array([0.2, 0.1, -0.05])
    m = ping(v, altitude=2.0, sigma=0.003, valid=(True, True, False, True))
    t = dvl_to_water_track(m)
    assert t.velocity_beam[2] == DvlBottomWaterTrack.INVALID_VELOCITY
    assert t.fom_beam[2] == DvlBottomWaterTrack.INVALID_FOM
    assert t.range[2] == DvlBottomWaterTrack.INVALID_RANGE
    assert t.velocity_xyzz[:3] == pytest.approx([v[0], v[1], DvlBottomWaterTrack.INVALID_VELOCITY], abs=1e-12)
    assert t.velocity_xyzz[3] == pytest.approx(v[2], abs=1e-12)  # z2 still has beams 1 and 3
    back = water_track_to_dvl(t, BEAM_ANGLE, AZIMUTHS)
    assert back.bottom_lock and back.beam_valid == [True, True, False, True]
    assert (back.velocity.x, back.velocity.y, back.velocity.z) == pytest.approx(tuple(v), abs=1e-12)


def test_no_bottom_lock_gives_invalid_markers_both_ways():
    m = ping(np.zeros(3), altitude=80.0, sigma=0.003, valid=(False, False, False, False))
    t = dvl_to_water_track(m)
    assert list(t.velocity_beam) == [DvlBottomWaterTrack.INVALID_VELOCITY] * 4
    assert list(t.velocity_xyzz) == [DvlBottomWaterTrack.INVALID_VELOCITY] * 4
    assert list(t.fom_xyzz) == [DvlBottomWaterTrack.INVALID_FOM] * 4
    assert list(t.range) == [DvlBottomWaterTrack.INVALID_RANGE] * 4
    back = water_track_to_dvl(t, BEAM_ANGLE, AZIMUTHS)
    assert not back.bottom_lock
    assert not any(back.beam_valid)
    assert all(math.isinf(r) for r in back.range)
    assert math.isnan(back.velocity.x) and math.isnan(back.altitude)


def test_translated_messages_serialize():
    """Both outputs go on the wire: NaN-free, fixed-size arrays of the right length."""
    from io import BytesIO

    for msg in (dvl_to_water_track(ping(np.array([0.1, 0, 0]), 1.0, 0.003)), raw_to_kvh(ImuRaw())):
        buf = BytesIO()
        msg.serialize(buf)
        clone = type(msg)()
        clone.deserialize(buf.getvalue())
        assert clone == msg

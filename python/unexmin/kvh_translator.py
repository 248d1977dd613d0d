"""KVH 1775 translator (the thesis's "KVH_msg" node): simulated raw IMU -> the real robot's message.

Subscribes /<robot>/kvh/raw (unexmin/ImuRaw: SI units, from the simulator's IMU model) and publishes
/<robot>/kvh/imu_raw (kvh_1775/ImuRawKvh: the UX-1 driver's fields and units: magnetometer in mG,
pressure in bar). The conversions are pure functions (no ROS master needed) with their inverses,
so a round trip is testable and real bags can be turned into simulator form.

At 500 Hz this rospy node keeps up only at modest real-time factors; by default the simulator
publishes kvh/imu_raw itself with the same conversion (see docs/translators.md for the figures and
the ~kvh_from_simulator switch). Parameters: docs/translators.md.
"""

from unexmin.translator_node import run
from kvh_1775.msg import ImuRawKvh

from unexmin.msg import ImuRaw

MILLIGAUSS_PER_TESLA = 1e7   # 1 G = 1e-4 T, 1 mG = 1e-7 T
PASCAL_PER_BAR = 1e5


def _copy_vector(dst, src, scale=1.0):
    dst.x, dst.y, dst.z = scale * src.x, scale * src.y, scale * src.z
    return dst


def raw_to_kvh(raw):
    """unexmin/ImuRaw (SI) -> kvh_1775/ImuRawKvh (mG, bar); header, axes and temperatures unchanged."""
    out = ImuRawKvh()
    out.header = raw.header
    _copy_vector(out.accelerometer, raw.linear_acceleration)
    _copy_vector(out.gyroscope, raw.angular_velocity)
    _copy_vector(out.magnetometer, raw.magnetic_field, MILLIGAUSS_PER_TESLA)
    out.temperature_imu = raw.temperature
    out.pressure = raw.pressure / PASCAL_PER_BAR
    out.temperature_pressure = raw.pressure_temperature
    return out


def kvh_to_raw(kvh):
    """The inverse of raw_to_kvh: kvh_1775/ImuRawKvh (mG, bar) -> unexmin/ImuRaw (SI)."""
    out = ImuRaw()
    out.header = kvh.header
    _copy_vector(out.linear_acceleration, kvh.accelerometer)
    _copy_vector(out.angular_velocity, kvh.gyroscope)
    _copy_vector(out.magnetic_field, kvh.magnetometer, 1.0 / MILLIGAUSS_PER_TESLA)
    out.temperature = kvh.temperature_imu
    out.pressure = kvh.pressure * PASCAL_PER_BAR
    out.pressure_temperature = kvh.temperature_pressure
    return out


def main():
    run("kvh_translator", ImuRaw, ImuRawKvh, raw_to_kvh, input_topic="kvh/raw", output_topic="kvh/imu_raw", queue_size=1000)

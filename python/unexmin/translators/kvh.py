"""KVH 1775 translator (the thesis's "KVH_msg" node): simulated raw IMU -> the real robot's message.

Subscribes /<robot>/kvh/raw (unexmin/ImuRaw: SI units, from the simulator's IMU model) and publishes
/<robot>/kvh/imu_raw (kvh_1775/ImuRawKvh: the UX-1 driver's fields and units: magnetometer in mG,
pressure in bar). The conversions are pure functions (no ROS master needed) with their inverses,
so a round trip is testable and real bags can be turned into simulator form.

At 500 Hz this rospy node keeps up only at modest real-time factors; by default the simulator
publishes kvh/imu_raw itself with the same conversion (see docs/translators.md for the figures and
the ~kvh_from_simulator switch). Parameters: docs/translators.md.
"""

from kvh_1775.msg import ImuRawKvh

from unexmin.msg import ImuRaw
from unexmin.translators.node import run

MILLIGAUSS_PER_TESLA = 1e7  # 1 G = 1e-4 T, 1 mG = 1e-7 T
PASCAL_PER_BAR = 1e5


# (kvh_1775/ImuRawKvh field, unexmin/ImuRaw field, a Vector3?, (multiply, divide) SI -> KVH, (multiply, divide)
# KVH -> SI): each value becomes value * multiply / divide.
FIELDS = (
    ("accelerometer", "linear_acceleration", True, (1.0, 1.0), (1.0, 1.0)),
    ("gyroscope", "angular_velocity", True, (1.0, 1.0), (1.0, 1.0)),
    ("magnetometer", "magnetic_field", True, (MILLIGAUSS_PER_TESLA, 1.0), (1.0 / MILLIGAUSS_PER_TESLA, 1.0)),
    ("temperature_imu", "temperature", False, (1.0, 1.0), (1.0, 1.0)),
    ("pressure", "pressure", False, (1.0, PASCAL_PER_BAR), (PASCAL_PER_BAR, 1.0)),
    ("temperature_pressure", "pressure_temperature", False, (1.0, 1.0), (1.0, 1.0)),
)


def _convert(src, out, to_kvh):
    """Copy every field of FIELDS from src to out (ImuRaw -> ImuRawKvh if to_kvh, else back), header unchanged."""
    out.header = src.header
    for kvh_name, raw_name, vector, si_to_kvh, kvh_to_si in FIELDS:
        source, target = (raw_name, kvh_name) if to_kvh else (kvh_name, raw_name)
        multiply, divide = si_to_kvh if to_kvh else kvh_to_si
        value = getattr(src, source)
        if vector:
            dst = getattr(out, target)
            dst.x, dst.y, dst.z = value.x * multiply / divide, value.y * multiply / divide, value.z * multiply / divide
        else:
            setattr(out, target, value * multiply / divide)
    return out


def raw_to_kvh(raw):
    """unexmin/ImuRaw (SI) -> kvh_1775/ImuRawKvh (mG, bar); header, axes and temperatures unchanged."""
    return _convert(raw, ImuRawKvh(), to_kvh=True)


def kvh_to_raw(kvh):
    """The inverse of raw_to_kvh: kvh_1775/ImuRawKvh (mG, bar) -> unexmin/ImuRaw (SI)."""
    return _convert(kvh, ImuRaw(), to_kvh=False)


def main():
    run(
        "kvh_translator",
        ImuRaw,
        ImuRawKvh,
        raw_to_kvh,
        input_topic="kvh/raw",
        output_topic="kvh/imu_raw",
        queue_size=1000,
    )

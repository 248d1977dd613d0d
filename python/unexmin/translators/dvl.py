"""DVL translator (the thesis's "DVL_msg" node): simulated DVL ping -> the real robot's message.

Subscribes /<robot>/dvl (unexmin/Dvl, one ping of the simulator's Nortek DVL1000 model) and publishes
/<robot>/dvl_water_track (dvl_nortek/DvlBottomWaterTrack, the UX-1 driver's bottom-track record) at
the ping rate (8 Hz). The conversions are pure functions (no ROS master needed) with their inverse,
so a round trip is testable. Field meanings and units: docs/translators.md; parameters likewise.

Conventions (ours, where Nortek's own definitions were not available; see docs/translators.md):
  range[i]      vertical distance seen by beam i: slant range * cos(beam angle) [m]
  dt1           two-way travel time from the ping to the echo centre: 2 * slant range / sound speed [s]
  dt2           from the echo centre to the record's output, taken as the last valid beam's echo:
                max(dt1) - dt1 [s]
  time          time of the velocity estimate from the ping, the one-way travel time: dt1 / 2 [s]
  fom           one standard deviation of the estimate [m/s]
  xyzz          x and z1 from beams 0 and 2, y and z2 from beams 1 and 3 (their dt1/dt2/time are the
                pair's means; with one beam of a pair invalid, the means of the valid beams)
Invalid values use the message's INVALID_* markers (0 for the times).
"""

import math

from dvl_nortek.msg import DvlBottomWaterTrack

from unexmin.msg import Dvl
from unexmin.translators.node import run

PASCAL_PER_DBAR = 1e4
PAIRS = ((0, 2), (1, 3), (0, 2), (1, 3))  # beams behind x, y, z1, z2


def _valid(dvl, i):
    return bool(dvl.beam_valid[i]) and math.isfinite(dvl.range[i]) and math.isfinite(dvl.beam_velocity[i])


def _mean(values):
    return sum(values) / len(values) if values else 0.0


def dvl_to_water_track(dvl):
    """unexmin/Dvl -> dvl_nortek/DvlBottomWaterTrack (header kept; pressure Pa -> dbar)."""
    out = DvlBottomWaterTrack()
    out.header = dvl.header
    out.sound_speed = dvl.sound_speed
    out.temperature = dvl.temperature
    out.pressure = dvl.pressure / PASCAL_PER_DBAR
    cos_a = math.cos(dvl.beam_angle)
    valid = [_valid(dvl, i) for i in range(4)]
    dt1 = [2.0 * dvl.range[i] / dvl.sound_speed if valid[i] else 0.0 for i in range(4)]
    last_echo = max((dt1[i] for i in range(4) if valid[i]), default=0.0)
    for i in range(4):
        if valid[i]:
            out.range[i] = dvl.range[i] * cos_a
            out.velocity_beam[i] = dvl.beam_velocity[i]
            out.fom_beam[i] = dvl.beam_velocity_std[i]
            out.dt1_beam[i] = dt1[i]
            out.dt2_beam[i] = last_echo - dt1[i]
            out.time_beam[i] = dt1[i] / 2.0
        else:
            out.range[i] = DvlBottomWaterTrack.INVALID_RANGE
            out.velocity_beam[i] = DvlBottomWaterTrack.INVALID_VELOCITY
            out.fom_beam[i] = DvlBottomWaterTrack.INVALID_FOM
            out.dt1_beam[i] = out.dt2_beam[i] = out.time_beam[i] = 0.0

    cov = dvl.velocity_covariance
    values = [dvl.velocity.x, dvl.velocity.y, dvl.velocity_z1, dvl.velocity_z2]
    # z1, z2 = (u_i + u_j) / (2 cos a): the std of a pair's mean over 2 cos a.
    foms = [math.sqrt(max(cov[0], 0.0)), math.sqrt(max(cov[4], 0.0))]
    for i, j in PAIRS[2:]:
        foms.append(math.hypot(dvl.beam_velocity_std[i], dvl.beam_velocity_std[j]) / (2.0 * cos_a))
    for k in range(4):
        if dvl.bottom_lock and math.isfinite(values[k]):
            used = [b for b in PAIRS[k] if valid[b]]
            used = used if len(used) == 2 else [b for b in range(4) if valid[b]]
            out.velocity_xyzz[k] = values[k]
            out.fom_xyzz[k] = foms[k]
            out.dt1_xyzz[k] = _mean([out.dt1_beam[b] for b in used])
            out.dt2_xyzz[k] = _mean([out.dt2_beam[b] for b in used])
            out.time_xyzz[k] = _mean([out.time_beam[b] for b in used])
        else:
            out.velocity_xyzz[k] = DvlBottomWaterTrack.INVALID_VELOCITY
            out.fom_xyzz[k] = DvlBottomWaterTrack.INVALID_FOM
            out.dt1_xyzz[k] = out.dt2_xyzz[k] = out.time_xyzz[k] = 0.0
    return out


def water_track_to_dvl(track, beam_angle, beam_azimuth=(0.0, math.pi / 2, math.pi, 3 * math.pi / 2)):
    """The inverse of dvl_to_water_track for the fields the record carries: ranges, beam velocities and
    their std, velocity x, y, z1, z2 with x/y variances, sound speed, temperature, pressure. The record
    has no beam geometry: give the DVL's beam angle [rad] and azimuths [rad]. velocity.z is the mean of
    z1 and z2, altitude the mean vertical range of the valid beams."""
    out = Dvl()
    out.header = track.header
    out.sound_speed = track.sound_speed
    out.temperature = track.temperature
    out.pressure = track.pressure * PASCAL_PER_DBAR
    out.beam_angle = beam_angle
    out.beam_azimuth = list(beam_azimuth)
    cos_a = math.cos(beam_angle)
    nan, inf = float("nan"), float("inf")
    valid, vertical = [], []
    for i in range(4):
        ok = track.velocity_beam[i] != DvlBottomWaterTrack.INVALID_VELOCITY and track.range[i] > 0.0
        valid.append(ok)
        out.range[i] = track.range[i] / cos_a if ok else inf
        out.beam_velocity[i] = track.velocity_beam[i] if ok else nan
        out.beam_velocity_std[i] = track.fom_beam[i] if ok else 0.0
        if ok:
            vertical.append(track.range[i])
    out.beam_valid = valid
    xyzz = [v if v != DvlBottomWaterTrack.INVALID_VELOCITY else nan for v in track.velocity_xyzz]
    out.bottom_lock = sum(valid) >= 3 and math.isfinite(xyzz[0]) and math.isfinite(xyzz[1])
    out.velocity_z1, out.velocity_z2 = xyzz[2], xyzz[3]
    if out.bottom_lock:
        z = [v for v in xyzz[2:] if math.isfinite(v)]
        out.velocity.x, out.velocity.y = xyzz[0], xyzz[1]
        out.velocity.z = _mean(z) if z else nan
        cov = [0.0] * 9
        cov[0], cov[4] = track.fom_xyzz[0] ** 2, track.fom_xyzz[1] ** 2
        zf = [track.fom_xyzz[k] for k in (2, 3) if math.isfinite(xyzz[k])]
        cov[8] = _mean([f * f for f in zf]) / max(len(zf), 1)
        out.velocity_covariance = cov
        out.altitude = _mean(vertical)
    else:
        out.velocity.x = out.velocity.y = out.velocity.z = nan
        out.velocity_covariance = [-1.0] * 9
        out.altitude = nan
    return out


def main():
    run(
        "dvl_translator",
        Dvl,
        DvlBottomWaterTrack,
        dvl_to_water_track,
        input_topic="dvl",
        output_topic="dvl_water_track",
        queue_size=100,
    )

#!/usr/bin/env python3
"""rostest: the navigation sensors and translators through ROS (test/rostest/sensors.test).

The records are made with the scripting API's collectors (Robot.collect) on a simulator this test
joins: complete after each step for the simulator's topics; the translators' outputs, which are
not synchronised with the steps, are waited for up to their last sample's stamp."""

import math
import unittest

import rospy
import rostest
from dvl_nortek.msg import DvlBottomWaterTrack
from geometry_msgs.msg import TwistWithCovarianceStamped
from kvh_1775.msg import ImuRawKvh
from sensor_msgs.msg import FluidPressure, Imu, MagneticField, Range

from unexmin import Simulation
from unexmin.msg import Dvl, ImuRaw

NS = "/UX_1/"
TOPICS = {
    "imu": Imu,
    "imu/mag": MagneticField,
    "kvh/raw": ImuRaw,
    "kvh/imu_raw": ImuRawKvh,
    "kvh/imu_raw_translated": ImuRawKvh,
    "pressure": FluidPressure,
    "dvl": Dvl,
    "dvl_sonar0": Range,
    "dvl_sonar1": Range,
    "dvl_sonar2": Range,
    "dvl_sonar3": Range,
    "dvl_twist": TwistWithCovarianceStamped,
    "dvl_water_track": DvlBottomWaterTrack,
}
TYPE_NAMES = {t: c._type for t, c in TOPICS.items()}
TRANSLATED = {"kvh/imu_raw_translated", "dvl_water_track"}  # published by translator nodes, not the simulator
SECONDS = 2.0  # [s] of sim time per record
G = 9.81  # [m/s^2] tank.world gravity
SPAWN_Z = -1.0  # [m] UX_1 in tank.world
FLOOR_Z = -3.0  # [m]
HULL_R = 0.3  # [m]


class Sensors(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sim = Simulation(node_name="sensors_test", timeout=60.0)
        cls.ux = cls.sim.robot("UX_1")  # subscribes every topic the simulator publishes under /UX_1/

    def record(self):
        """Reset to t = 0 (seed 1), step SECONDS of sim time, return every message of the record.

        Every sensor samples at exactly t = SECONDS (2 s is a multiple of 1/500, 1/10 and 1/8 s), and a
        topic's messages arrive in order: once each translated topic has its t = SECONDS message, the
        record is complete and nothing of it can arrive after the next record's start."""
        self.drain_translators()
        self.sim.reset(seed=1)
        collectors = {t: self.ux.collect(t, c) for t, c in TOPICS.items()}
        self.sim.run_for(SECONDS)
        got = {t: c.wait_until(SECONDS) if t in TRANSLATED else c.messages for t, c in collectors.items()}
        for c in collectors.values():
            c.stop()
        return got

    def drain_translators(self):
        """Wait until each translator has published its translation of the last message the simulator
        sent it (translators are not synchronised with the steps: a test that steps without waiting
        for them leaves translations in flight, which would land in the next record)."""
        for out, source in (("kvh/imu_raw_translated", "kvh/raw"), ("dvl_water_track", "dvl")):
            try:
                last = self.ux.latest(source).header.stamp.to_sec()
            except LookupError:  # nothing stepped since the start or the last reset
                continue
            self.ux.latest(out, TOPICS[out], min_stamp=last, timeout=30.0)

    def test_latest_is_the_newest_sample_at_sim_time(self):
        # joined simulator, topics subscribed at setUpClass: asked first after the steps, exact at once
        self.sim.reset(seed=1)
        self.sim.run_for(0.7)
        self.sim.step(300)  # t = 1.3 s
        for topic, rate in (("kvh/imu_raw", 500), ("imu", 500), ("pressure", 10), ("dvl", 8), ("dvl_sonar1", 8)):
            expected = math.floor(1.3 * rate + 1e-9) / rate  # 1.3, 1.3, 1.3, 1.25, 1.25: all on the 2 ms grid
            self.assertAlmostEqual(self.ux.latest(topic).header.stamp.to_sec(), expected, delta=1e-9, msg=topic)

    def test_type_names(self):
        published = dict(rospy.get_published_topics())
        for topic, name in TYPE_NAMES.items():
            self.assertEqual(published.get(NS + topic), name, topic)
        self.assertEqual(published[NS + "kvh/imu_raw"], "kvh_1775/ImuRawKvh")
        self.assertEqual(published[NS + "dvl_water_track"], "dvl_nortek/DvlBottomWaterTrack")

    def test_rates_in_simulation_time(self):
        got = self.record()
        for topic, rate in (
            ("imu", 500),
            ("kvh/imu_raw", 500),
            ("kvh/imu_raw_translated", 500),
            ("kvh/raw", 500),
            ("pressure", 10),
            ("dvl", 8),
            ("dvl_water_track", 8),
            ("dvl_sonar2", 8),
        ):
            stamps = [m.header.stamp.to_sec() for m in got[topic]]
            self.assertEqual(len(stamps), round(rate * SECONDS), topic)
            # Sample k at the first 2 ms physics step at or after k / rate.
            for k, t in enumerate(stamps, start=1):
                self.assertGreaterEqual(t, k / rate - 1e-9, topic)
                self.assertLess(t, k / rate + 0.002 - 1e-9, topic)

    def test_kvh_translator_matches_the_simulators_own_message(self):
        got = self.record()
        direct = {m.header.stamp.to_nsec(): m for m in got["kvh/imu_raw"]}
        translated = got["kvh/imu_raw_translated"]
        self.assertEqual(len(translated), 1000)
        for t in translated:
            d = direct[t.header.stamp.to_nsec()]
            for f in ("accelerometer", "gyroscope", "magnetometer"):
                a, b = getattr(d, f), getattr(t, f)
                for ax in "xyz":
                    self.assertAlmostEqual(getattr(a, ax), getattr(b, ax), delta=1e-9 * max(1.0, abs(getattr(a, ax))))
            self.assertAlmostEqual(d.pressure, t.pressure, delta=1e-12)
            self.assertEqual((d.temperature_imu, d.temperature_pressure), (t.temperature_imu, t.temperature_pressure))

    def test_readings_at_rest_in_the_tank(self):
        got = self.record()
        # IMU: gravity up within 3 sigma of the mean of 1000 samples (+ turn-on bias of 1 mg).
        acc = [m.linear_acceleration.z for m in got["imu"]]
        sigma = math.sqrt(got["imu"][-1].linear_acceleration_covariance[8])
        self.assertAlmostEqual(sum(acc) / len(acc), G, delta=3.0 * math.hypot(sigma / math.sqrt(len(acc)), 9.8e-3))
        # KVH message: pressure in bar at 1 m depth: 1.01325 + 1000 * 9.81 * 1.0 / 1e5.
        kvh = got["kvh/imu_raw"][-1]
        self.assertAlmostEqual(kvh.pressure, 1.01325 + 0.0981, delta=0.005)
        # DVL at rest 1.7 m above the floor: vertical ranges 1.7 m, velocity 0 within 3 fom.
        altitude = SPAWN_Z - HULL_R - FLOOR_Z
        for track in got["dvl_water_track"]:
            for i in range(4):
                self.assertAlmostEqual(track.range[i], altitude, delta=0.05)
            for k in range(4):
                self.assertLess(abs(track.velocity_xyzz[k]), 3.0 * track.fom_xyzz[k] + 1e-3)
            self.assertAlmostEqual(track.pressure, (101325.0 + 1000 * G * (-SPAWN_Z + HULL_R)) / 1e4, delta=0.05)
        for r in got["dvl_sonar0"]:
            self.assertAlmostEqual(r.range, altitude / math.cos(math.radians(25.0)), delta=0.05)
        self.assertEqual(len(got["dvl_twist"]), round(8 * SECONDS))
        # Pressure sensor (rear, el -45 deg on the hull): 1 m + 0.3 sin 45 deg deep.
        depth = -SPAWN_Z + HULL_R * math.sin(math.radians(45.0))
        for p in got["pressure"]:
            self.assertAlmostEqual(p.fluid_pressure, 101325.0 + 1000 * G * depth, delta=5 * math.sqrt(p.variance))


if __name__ == "__main__":
    rostest.rosrun("unexmin", "sensors", Sensors)

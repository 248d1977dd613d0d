"""Lossless recording in lockstep (docs/recording.md).

1. The simulator's own recorder (record:=<bag>): 60 s of sim time stepped at full lockstep speed; every topic
   of the default set holds rate x 60 messages (+-1) in the bag, the thruster commands the client sent are all
   there, bag times are sim times, and the bag is closed and indexed (rosbag info reads it without reindex).
2. lockstep_wait_subscribers:=true: a stock `rosbag record` of the same topics gets the same counts over
   STOCK_SECONDS of sim time (without the wait it loses messages within seconds at full lockstep speed).

Every run is a subprocess (clients/record_run.py): one rospy node and one master per world."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
SECONDS = 60.0
# [s] of sim time the stock recorder gets: every message of it counts (none missing, +-1), as over SECONDS; the stock
# recorder (--lz4) sets the pace of that run
STOCK_SECONDS = 20.0
COMMANDS = 50  # thruster commands the client sends (one per step)
# Nominal rates [Hz of sim time] of the default recorded set, from SPEC / docs/sensors.md (not from a run).
RATES = {
    "/UX_1/imu": 500,
    "/UX_1/imu/mag": 500,
    "/UX_1/kvh/imu_raw": 500,
    "/UX_1/pressure": 10,
    "/UX_1/dvl": 8,
    "/UX_1/dvl_twist": 8,
    "/UX_1/dvl_water_track": 8,
    **{f"/UX_1/dvl_sonar{i}": 8 for i in range(4)},
    "/UX_1/m3/scan": 40,
    "/UX_1/m3/points": 40,
    "/UX_1/tritech_micron/scan": 25,
    "/UX_1/msis/msis_r": 25,
    **{f"/UX_1/sls_{i}/points": 10 for i in range(4)},
    **{f"/UX_1/sls_{i}/scan": 10 for i in range(4)},
    "/UX_1/odom": 50,
    "/UX_1/contacts": 50,
    **{f"/UX_1/thrusters/{i}/thrust": 50 for i in range(8)},
    "/current": 10,
}
SIM_PUBLISHED = set(RATES)  # the M3 and DVL translations included: the simulator makes them (C++)
LOCKED_ONLY = {"/UX_1/dvl_twist"}  # published only with bottom lock: one per locked /UX_1/dvl message


def run(tmp, *args, launch=(), timeout=300, seconds=SECONDS):
    out = subprocess.run(
        [
            sys.executable,
            str(HERE / "clients" / "record_run.py"),
            str(tmp / "log"),
            str(seconds),
            str(COMMANDS),
            *args,
            "--",
            *launch,
        ],
        capture_output=True,
        text=True,
        timeout=timeout,
        env=dict(os.environ, ROS_HOME=str(tmp)),
    )
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    return json.loads(out.stdout.strip().splitlines()[-1])


def bag_stamps(path, locks=None):
    """topic -> list of (bag time, header stamp or None) [s], read with the rosbags library; `locks` (a
    list) gets the header stamp of every /UX_1/dvl message with bottom lock."""
    from rosbags.highlevel import AnyReader
    from rosbags.typesys import Stores, get_typestore

    out = {}
    with AnyReader([Path(path)], default_typestore=get_typestore(Stores.ROS1_NOETIC)) as reader:
        for conn, t, raw in reader.messages():
            msg = reader.deserialize(raw, conn.msgtype)
            header = getattr(msg, "header", None)
            stamp = header.stamp.sec + 1e-9 * header.stamp.nanosec if header is not None else None
            out.setdefault(conn.topic, []).append((t * 1e-9, stamp))
            if locks is not None and conn.topic == "/UX_1/dvl" and msg.bottom_lock:
                locks.append(stamp)
    return out


def assert_indexed(path):
    info = subprocess.run(["rosbag", "info", "--yaml", "--key=indexed", str(path)], capture_output=True, text=True)
    assert info.returncode == 0 and info.stdout.strip() == "True", info.stdout + info.stderr


def counts_until(stamps, end):
    """Messages per topic with a bag time in (0, end] (+ a tolerance of a tenth of a physics step)."""
    return {t: sum(1 for bt, _ in v if 0.0 < bt <= end + 2e-4) for t, v in stamps.items()}


@pytest.fixture(scope="module")
def own_recording(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("own")
    bag = tmp / "own.bag"
    res = run(tmp, launch=[f"record:={bag}"])
    return bag, res


@pytest.mark.alone
def test_own_recorder_keeps_every_message_at_full_lockstep_speed(own_recording):
    bag, res = own_recording
    assert_indexed(bag)
    locks = []
    stamps = bag_stamps(bag, locks)
    missing = SIM_PUBLISHED - set(stamps)
    assert not missing, f"topics not recorded: {sorted(missing)}"
    assert "/clock" not in stamps and "/UX_1/joint_states" not in stamps  # wall-rate limited: not recorded
    counts = counts_until(stamps, SECONDS)
    for topic in SIM_PUBLISHED - LOCKED_ONLY:
        assert abs(counts[topic] - RATES[topic] * SECONDS) <= 1, (topic, counts[topic], RATES[topic] * SECONDS)
    assert [s for _, s in stamps["/UX_1/dvl_twist"]] == locks and len(locks) > 0
    # Bag time = sim time of the step that made the message; a sensor's header stamp is its sample time.
    for bt, stamp in stamps["/UX_1/kvh/imu_raw"]:
        assert stamp == pytest.approx(bt, abs=1e-6)
    for i in range(8):
        assert len(stamps[f"/UX_1/thrusters/{i}/input"]) == COMMANDS
    # The whole stepping (60 s of sim time) ran at lockstep speed, recorder on: faster than real time.
    assert res["wall"] < SECONDS, res


@pytest.mark.alone
def test_record_service_starts_and_stops_a_bag(own_recording):
    """The recorder started by record:= and stopped through /sim/record (an empty path) at t = SECONDS + 1 s: its
    bag closed and indexed (the same run as the test above)."""
    bag, res = own_recording
    assert res["sim"] == pytest.approx(SECONDS + 1.0)
    assert "closed" in res["record"]
    assert_indexed(bag)


@pytest.mark.long
def test_stock_rosbag_record_gets_everything_with_lockstep_wait_subscribers(tmp_path):
    topics = sorted(SIM_PUBLISHED)
    stock = tmp_path / "stock.bag"
    run(tmp_path, "--rosbag", str(stock), *topics, launch=["lockstep_wait_subscribers:=true"], seconds=STOCK_SECONDS)
    assert_indexed(stock)
    locks = []
    got = bag_stamps(stock, locks)
    # Header stamps (the bag times of a stock recorder are wall times): every topic has a message after
    # STOCK_SECONDS, so all of its earlier messages went through (TCP keeps a topic's order).
    headerless = {t for t in topics if got.get(t) and got[t][0][1] is None}
    assert headerless == {"/UX_1/msis/msis_r", *(f"/UX_1/thrusters/{i}/thrust" for i in range(8))}
    for topic in topics:
        stamps = [s for _, s in got.get(topic, [])]
        if topic in LOCKED_ONLY:
            assert stamps == locks and len(locks) > 0, topic
        elif topic in headerless:
            # No stamp: all of the STOCK_SECONDS + 1 s stepped; the last step's message may still be in flight
            # when rosbag record is stopped.
            assert abs(len(stamps) - RATES[topic] * (STOCK_SECONDS + 1.0)) <= 1, (topic, len(stamps))
        else:
            assert stamps and max(stamps) > STOCK_SECONDS, topic
            n = sum(1 for s in stamps if 0.0 < s <= STOCK_SECONDS + 2e-4)
            assert abs(n - RATES[topic] * STOCK_SECONDS) <= 1, (topic, n, RATES[topic] * STOCK_SECONDS)

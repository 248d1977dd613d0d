"""The simulator's C++ M3 and DVL translations (cpp/unexmin/ros_layer/m3_cloud.cpp, dvl_water_track.cpp) against the
rospy translators they replace in simulation (python/unexmin/translators/m3.py scan_to_cloud,
dvl.py dvl_to_water_track): the simulator records its own m3/scan, m3/points, dvl and
dvl_water_track while the robot moves (record:=, every message kept); each C++ output must equal the Python
translation of the input message of the same stamp, field by field, and the rospy nodes do not run."""

import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
SECONDS = 10.0
TOPICS = "/UX_1/m3/scan /UX_1/m3/points /UX_1/dvl /UX_1/dvl_water_track"


@pytest.fixture(scope="module", params=["tank"])
def bag(tmp_path_factory, request):
    tmp = tmp_path_factory.mktemp("cpp_translations")
    path = tmp / "translations.bag"
    out = subprocess.run(
        [
            sys.executable,
            str(HERE / "clients" / "record_run.py"),
            str(tmp / "log"),
            str(SECONDS),
            "200",
            "--world",
            request.param,
            "--",
            f"record:={path}",
            f"record_topics:={TOPICS}",
        ],
        capture_output=True,
        text=True,
        timeout=300,
        env=dict(os.environ, ROS_HOME=str(tmp)),
    )
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    import rosbag

    got = {}
    with rosbag.Bag(str(path)) as b:
        for topic, msg, _ in b.read_messages():
            got.setdefault(topic, {})[msg.header.stamp.to_nsec()] = msg
    log = (tmp / "log" / "roslaunch.log").read_text()
    return got, log, request.param


def same(a, b, what):
    if isinstance(a, float) and math.isnan(a):
        assert isinstance(b, float) and math.isnan(b), what
    else:
        assert a == pytest.approx(b, rel=1e-12, abs=1e-12), what


def test_rospy_translators_do_not_run_by_default(bag):
    _, log, _ = bag
    assert "m3_translator (unexmin/m3_translator)" not in log and "dvl_translator (unexmin/dvl_translator)" not in log


def test_m3_cloud_equals_the_python_translation(bag):
    from unexmin.translators.m3 import scan_to_cloud

    got, _, _ = bag
    scans, clouds = got["/UX_1/m3/scan"], got["/UX_1/m3/points"]
    assert len(scans) == len(clouds) == round(40 * (SECONDS + 1.0))
    widths = set()
    for stamp, scan in scans.items():
        cpp, py = clouds[stamp], scan_to_cloud(scan)
        assert cpp.header.frame_id == py.header.frame_id
        assert (cpp.height, cpp.width, cpp.point_step, cpp.row_step, cpp.is_dense, cpp.is_bigendian) == (
            py.height,
            py.width,
            py.point_step,
            py.row_step,
            py.is_dense,
            py.is_bigendian,
        )
        assert [(f.name, f.offset, f.datatype, f.count) for f in cpp.fields] == [
            (f.name, f.offset, f.datatype, f.count) for f in py.fields
        ]
        # the same doubles rounded to float32 by the same rule: the same bytes
        assert bytes(cpp.data) == bytes(py.data), stamp
        widths.add(cpp.width)
    # Every beam sees a wall in the tank (and in the mine at its spawn): the leaving out of beams without an
    # echo is compared on the Python side only (test_m3_translator.py).
    assert max(widths) > 50


def test_dvl_water_track_equals_the_python_translation(bag):
    from unexmin.translators.dvl import dvl_to_water_track

    got, _, _ = bag
    pings, tracks = got["/UX_1/dvl"], got["/UX_1/dvl_water_track"]
    assert len(pings) == len(tracks) == round(8 * (SECONDS + 1.0))
    fields = [f for f in tracks[next(iter(tracks))].__slots__ if f != "header"]
    locks = set()
    for stamp, ping in pings.items():
        cpp, py = tracks[stamp], dvl_to_water_track(ping)
        assert cpp.header.frame_id == py.header.frame_id
        for f in fields:
            a, b = getattr(cpp, f), getattr(py, f)
            if isinstance(b, (list, tuple)):
                assert len(a) == len(b), f
                for k, (x, y) in enumerate(zip(a, b)):
                    same(x, y, f"{f}[{k}] at {stamp}")
            else:
                same(a, b, f"{f} at {stamp}")
        locks.add(ping.bottom_lock)
    assert True in locks  # the translation of a locked ping was compared

"""The replay, the identification's validation replay and the batch on the engine in-process (backend core, their
default), against the same tools on the ROS simulator (docs/replay.md, identification.md, batch.md):

- the sample bag replayed both ways gives the same trajectory, bit for bit (both step the same C++ engine with the
  same thrusts from the same ESC tables);
- replayed on the core with the overrides of the robot that made the bag (urdf/ux1_perturbed.xacro, what the
  identification writes), the final error drops below 0.15 m from more than 0.5 m with the nominal robot;
- three tank missions of a batch give the same metrics on both back ends, and the core's need no ROS master.

Simulator runs are subprocesses, so this process never initialises rospy.
"""

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
SAMPLE_BAG = REPO / "worlds" / "bags" / "ux1_tank_perturbed.bag"
pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


def replay(tmp_path, out, *args):
    env = dict(os.environ, ROS_HOME=str(tmp_path / "ros_home"), ROS_LOG_DIR=str(tmp_path / "ros_log"))
    res = subprocess.run(
        [sys.executable, "-m", "unexmin.replay", str(SAMPLE_BAG), "--out", str(out), "--quiet", *args],
        capture_output=True,
        text=True,
        timeout=300,
        env=env,
        cwd=tmp_path,
    )
    assert res.returncode == 0, res.stdout + res.stderr[-3000:]
    return json.loads((out / "report.json").read_text())


@pytest.mark.skipif(not SAMPLE_BAG.exists(), reason="sample bag not made yet")
def test_replay_on_the_core_is_the_ros_replay_bit_for_bit(tmp_path):
    core = replay(tmp_path, tmp_path / "core")
    ros = replay(tmp_path, tmp_path / "ros", "--backend", "ros")
    assert core["backend"] == "core" and ros["backend"] == "ros"
    a = np.genfromtxt(tmp_path / "core" / "trajectory.csv", delimiter=",", names=True)
    b = np.genfromtxt(tmp_path / "ros" / "trajectory.csv", delimiter=",", names=True)
    assert len(a) == len(b) > 100
    for name in a.dtype.names:
        np.testing.assert_array_equal(a[name], b[name], err_msg=name)
    assert core["errors"] == ros["errors"]


@pytest.mark.skipif(not SAMPLE_BAG.exists(), reason="sample bag not made yet")
def test_identified_overrides_replay_on_the_core(tmp_path):
    report = replay(tmp_path, tmp_path / "out", "--overrides", str(REPO / "urdf" / "ux1_perturbed.xacro"))
    assert report["backend"] == "core"
    assert report["errors_before"]["position_error_m"]["final"] > 0.5
    assert report["errors"]["position_error_m"]["final"] < 0.15


def test_batch_on_the_core_gives_the_ros_table(tmp_path, monkeypatch):
    import yaml

    from unexmin.batch import run_sequential
    from unexmin.batch.spec import check_spec

    monkeypatch.setenv("ROS_HOME", str(tmp_path / "ros_home"))
    tables = {}
    for backend in ("core", "ros"):
        path = tmp_path / backend / "spec.yaml"
        path.parent.mkdir()
        path.write_text(
            textwrap.dedent(f"""
            world: tank
            mission: unexmin.missions.batch:tank_survey
            duration: 3.0
            timeout: 90
            sensors: none
            control: false
            backend: {backend}
            seeds: 1
            sweep: {{current_speed: [0.0, 0.2, 0.4]}}
            params: {{buoyancy_offset: 0.3}}
        """)
        )
        spec = check_spec(yaml.safe_load(path.read_text()), str(path))
        tables[backend] = run_sequential(spec, str(tmp_path / backend / "out"))
    core, ros = tables["core"], tables["ros"]
    assert list(core["status"]) == ["ok"] * 3, core[["error", "log"]].to_string()
    assert list(ros["status"]) == ["ok"] * 3, ros[["error", "log"]].to_string()
    for column in ("end_x_m", "end_y_m", "end_z_m", "path_length_m", "yaw_change_deg", "sim_time_s"):
        np.testing.assert_array_equal(core[column].to_numpy(), ros[column].to_numpy(), err_msg=column)
    assert len(set(core["end_x_m"])) == 3, "the swept current did not change where the robot ended"
    # the core's missions started no ROS master: their folders hold no roslaunch log
    assert not any((tmp_path / "core" / "out" / "missions").glob("*/logs/roslaunch.log"))
    assert any((tmp_path / "ros" / "out" / "missions").glob("*/logs/roslaunch.log"))

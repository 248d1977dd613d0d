"""Batches of missions on Dask distributed (python/unexmin/batch/, docs/batch.md).

- A spec expands the same way every time: seeds outermost, then the sweep's cartesian product; sampled
  values come from (sample_seed, index) and follow their distribution; --limit keeps the first N; a bad
  spec stops with an error naming the key and what was expected.
- A mission's files: the world file carries the mission's current and visibility, the overrides scale
  the robot description's noise figures and shift its mass by the buoyancy offset (xacro expanded here).
- 6 tank missions on a local cluster of 2 worker processes give the same table as the same missions run
  one after the other (timings aside), and results.parquet/results.csv hold it.
- Failures are data: a mission that raises, returns NaN, kills its process or never returns is recorded
  (status failed, its error, its log) after one retry, and the batch completes with the good ones.
- A real deployment on the loopback: `dask scheduler` and two `dask worker` processes, the CLI pointed at
  the scheduler with --limit; both workers ran missions; the dashboard's address is printed.
"""

import math
import os
import re
import subprocess
import sys
import textwrap
import threading

import numpy as np
import pytest

from unexmin.batch.spec import SpecError, check_spec, expand, write_launch
from unexmin.scripting.launcher import free_port, stop_process_group, wait_for

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))
pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


@pytest.fixture(autouse=True)
def ros_home(tmp_path, monkeypatch):
    monkeypatch.setenv("ROS_HOME", str(tmp_path / "ros_home"))


def spec_of(text, folder):
    path = folder / "spec.yaml"
    path.write_text(textwrap.dedent(text))
    return check_spec(__import__("yaml").safe_load(path.read_text()), str(path))


def test_expansion_is_a_function_of_the_spec(tmp_path):
    text = """
        mission: unexmin.missions.batch:tank_survey
        seeds: {start: 5, count: 3}
        sweep: {visibility: [none, high], current_angle: [0.0, 1.0]}
        sample: {current_speed: {uniform: [0.1, 0.3]}, sensor_noise_scale: {choice: [0.5, 2.0]}}
        params: {gain: 2.0}
    """
    spec = spec_of(text, tmp_path)
    missions = expand(spec)
    assert len(missions) == 3 * 2 * 2
    assert [m["seed"] for m in missions] == [5] * 4 + [6] * 4 + [7] * 4
    assert [(m["params"]["visibility"], m["params"]["current_angle"]) for m in missions[:4]] == [
        ("none", 0.0),
        ("none", 1.0),
        ("high", 0.0),
        ("high", 1.0),
    ]
    assert all(m["params"]["gain"] == 2.0 for m in missions)
    speeds = [m["params"]["current_speed"] for m in missions]
    assert all(0.1 <= s <= 0.3 for s in speeds) and len(set(speeds)) == len(speeds)
    assert {m["params"]["sensor_noise_scale"] for m in missions} <= {0.5, 2.0}
    assert expand(spec_of(text, tmp_path)) == missions  # the same spec, the same missions
    assert expand(spec, limit=5) == missions[:5]
    # A mission's draws depend on (sample_seed, index) only: numpy's generator seeded with that pair.
    rng = np.random.default_rng([0, 7])
    assert missions[7]["params"]["current_speed"] == rng.uniform(0.1, 0.3)


def test_sampled_values_follow_their_distribution(tmp_path):
    spec = spec_of(
        """
        mission: unexmin.missions.batch:tank_survey
        seeds: 2000
        sample: {buoyancy_offset: {normal: [0.2, 0.5]}, n: {integers: [1, 3]}, v: {loguniform: [0.01, 1.0]}}
    """,
        tmp_path,
    )
    params = [m["params"] for m in expand(spec)]
    b = np.array([p["buoyancy_offset"] for p in params])
    se = 0.5 / math.sqrt(len(b))  # standard error of the mean
    assert abs(b.mean() - 0.2) < 4 * se and abs(b.std() - 0.5) < 0.05
    assert {p["n"] for p in params} == {1, 2, 3}
    logv = np.log10([p["v"] for p in params])  # log-uniform: uniform in [-2, 0]
    assert abs(logv.mean() + 1.0) < 0.05 and logv.min() >= -2.0 and logv.max() <= 0.0


@pytest.mark.parametrize(
    "text, message",
    [
        ("mission: tank_survey", "mission: expected 'module:function'"),
        ("mission: a:b\nworld: moon", "world: 'moon' is neither"),
        ("mission: a:b\nsweep: {current_speed: 0.1}", "sweep.current_speed: expected a non-empty list"),
        ("mission: a:b\nsweep: {visibility: [murky]}", "visibility 'murky': expected one of none, low, medium, high"),
        ("mission: a:b\nsample: {current_speed: {uniform: [0.3, 0.1]}}", "expected low <= high"),
        ("mission: a:b\nsample: {x: {poisson: [1]}}", "sample.x: expected one of"),
        ("mission: a:b\nsweep: {x: [1]}\nsample: {x: {uniform: [0, 1]}}", "parameter 'x' is given both in sweep"),
        ("mission: a:b\nseeds: -3", "seeds: -3 is outside"),
        ("mission: a:b\nduraton: 3", "unknown key(s) duraton"),
    ],
)
def test_bad_specs_name_the_key(tmp_path, text, message):
    with pytest.raises(SpecError, match=re.escape(message)):
        spec_of(text, tmp_path)


def test_mission_files_carry_the_parameters(tmp_path):
    import yaml

    spec = spec_of(
        """
        mission: unexmin.missions.batch:tank_survey
        params: {current_speed: 0.7, current_angle: 1.2, visibility: low, buoyancy_offset: 0.5,
                 sensor_noise_scale: 2.0}
    """,
        tmp_path,
    )
    mission = expand(spec)[0]
    launch = write_launch(spec, mission, str(tmp_path / "m"))
    world = yaml.safe_load((tmp_path / "m" / "mission.world").read_text())
    assert world["current"]["speed"]["mean"] == 0.7 and world["current"]["speed"]["max"] >= 0.7
    assert world["current"]["horizontal_angle"]["mean"] == 1.2
    assert world["visibility"]["level"] == "low"
    # meshes linked beside the mission's world file: a world file reads only files in its folder
    assert all(not os.path.isabs(m["file"]) and os.path.exists(tmp_path / "m" / m["file"]) for m in world["meshes"])
    assert 'name="ray_caster_threads" value="1"' in open(launch).read()

    def expand_xacro(*args):
        return subprocess.run(
            ["xacro", os.path.join(REPO, "urdf", "ux1.urdf.xacro"), "name:=UX_1", *args],
            check=True,
            capture_output=True,
            text=True,
        ).stdout

    base = expand_xacro()
    mine = expand_xacro(f"overrides:={tmp_path / 'm' / 'overrides.xacro'}")
    masses = [[float(v) for v in re.findall(r'<mass value="([^"]+)"', text)] for text in (base, mine)]
    # buoyancy offset 0.5 kg: the vehicle (hull, and the dynamics' total dry mass) 0.5 kg lighter than
    # neutral (rho V = 1000 kg/m^3 x 4/3 pi 0.3^3 m^3); the pendulum unchanged
    neutral = 1000.0 * 4.0 / 3.0 * math.pi * 0.3**3
    assert masses[1] == pytest.approx([neutral - 10.0 - 0.5, 10.0, neutral - 0.5], abs=1e-9)
    assert masses[0] == pytest.approx([neutral - 10.0, 10.0, neutral], abs=1e-9)
    for name in ("pressure_noise", "gyro_noise_density", "range_noise"):
        ref = float(re.search(rf'name="{name}" value="([^"]+)"', base).group(1))
        new = float(re.search(rf'name="{name}" value="([^"]+)"', mine).group(1))
        assert new == pytest.approx(2.0 * ref, rel=1e-12), name


def six_missions(folder, mission="unexmin.missions.batch:tank_survey", extra=""):
    return spec_of(
        f"""
        world: tank
        mission: {mission}
        duration: 2.0
        timeout: 60
        sensors: none
        control: false
        seeds: 3
        sweep: {{current_speed: [0.0, 0.25]}}
        sample: {{current_angle: {{uniform: [-3.14, 3.14]}}}}
        python_path: [{HERE}]
    """
        + textwrap.dedent(extra),
        folder,
    )


def comparable(df):
    return df.drop(columns=["wall_time_s", "log"]).reset_index(drop=True)


def test_local_cluster_gives_the_sequential_table(tmp_path):
    import pandas as pd

    from unexmin.batch import run_batch, run_sequential, write_results

    spec = six_missions(tmp_path)
    lines, reference = [], {}
    # The sequential reference runs its missions one after the other, at the same time as the cluster's
    # (the machine's cores are shared all the same: the results must not care).
    thread = threading.Thread(target=lambda: reference.update(df=run_sequential(spec, str(tmp_path / "seq"))))
    thread.start()
    try:
        parallel = run_batch(spec, str(tmp_path / "dask"), workers=2, progress=False, log=lines.append)
    finally:
        thread.join()
    assert re.search(r"Dask dashboard: http://127\.0\.0\.1:\d+/status", lines[0]), lines
    assert list(parallel["status"]) == ["ok"] * 6, parallel[["index", "error", "log"]].to_string()
    sequential = reference["df"]
    assert all(p.startswith(str(tmp_path / "seq" / "missions")) for p in sequential["log"])
    pd.testing.assert_frame_equal(comparable(parallel), comparable(sequential))
    # the sweep's current pushes the robot: same seed, 0.25 m/s against still water ends elsewhere
    ends = parallel.set_index(["seed", "current_speed"])["end_x_m"]
    assert all(abs(ends[(s, 0.25)] - ends[(s, 0.0)]) > 1e-3 for s in range(3))
    parquet, csv = write_results(parallel, str(tmp_path / "dask"))
    pd.testing.assert_frame_equal(pd.read_parquet(parquet), parallel)
    back = pd.read_csv(csv, keep_default_na=False)
    assert list(back["index"]) == list(range(6)) and np.allclose(back["end_x_m"], parallel["end_x_m"], rtol=0, atol=0)


def test_failures_are_recorded_and_the_batch_completes(tmp_path):
    from unexmin.batch import run_batch

    spec = spec_of(
        f"""
        world: tank
        mission: batch_test_missions:flaky
        duration: 1.0
        timeout: 5
        sensors: none
        control: false
        seeds: 5
        python_path: [{HERE}]
    """,
        tmp_path,
    )
    # 3 workers: the hanging mission holds one for two timeouts while it uses no CPU; a good mission takes about 1 s
    # from its process's start to its result (0.5 s of it the engine's launch)
    df = run_batch(spec, str(tmp_path / "out"), workers=3, progress=False, log=lambda _: None).set_index("index")
    assert list(df["status"]) == ["ok", "failed", "failed", "failed", "failed"]
    assert df.loc[0, "attempts"] == 1 and df.loc[0, "net_displacement_m"] > 0
    assert (df.loc[1:, "attempts"] == 2).all()  # each failure was retried once
    assert "RuntimeError: deliberate failure of mission 1" in df.loc[1, "error"]
    assert "metric score is nan" in df.loc[2, "error"]
    assert "exited with code 3 without a result" in df.loc[3, "error"]
    assert "timed out after 5 s" in df.loc[4, "error"]
    assert "deliberate failure" in open(df.loc[1, "log"]).read()  # the log holds the traceback
    assert all(os.path.exists(p) for p in df["log"])


def test_scheduler_and_two_workers_on_loopback(tmp_path):
    import pandas as pd
    from dask.distributed import Client

    spec_path = tmp_path / "spec.yaml"
    six_missions(tmp_path, "batch_test_missions:where")  # checks it; the CLI reads the file
    port, dash = free_port(), free_port()
    address = f"tcp://127.0.0.1:{port}"
    logs = [open(tmp_path / name, "w") for name in ("scheduler.log", "worker1.log", "worker2.log")]
    procs = []
    try:
        procs.append(
            subprocess.Popen(
                [
                    "dask",
                    "scheduler",
                    "--host",
                    "127.0.0.1",
                    "--port",
                    str(port),
                    "--dashboard-address",
                    f"127.0.0.1:{dash}",
                ],
                stdout=logs[0],
                stderr=subprocess.STDOUT,
                start_new_session=True,
            )
        )
        for log in logs[1:]:
            procs.append(
                subprocess.Popen(
                    [
                        "dask",
                        "worker",
                        address,
                        "--host",
                        "127.0.0.1",
                        "--nthreads",
                        "1",
                        "--no-nanny",
                        "--no-dashboard",
                    ],
                    stdout=log,
                    stderr=subprocess.STDOUT,
                    start_new_session=True,
                )
            )
        with Client(address, timeout=30) as client:
            wait_for(lambda: len(client.scheduler_info()["workers"]) == 2, 60, "two Dask workers to join")
        out = tmp_path / "out"
        run = subprocess.run(
            [
                sys.executable,
                "-m",
                "unexmin.batch",
                str(spec_path),
                "--out",
                str(out),
                "--scheduler",
                address,
                "--limit",
                "4",
                "--no-progress",
            ],
            capture_output=True,
            text=True,
            timeout=300,
        )
        assert run.returncode == 0, run.stdout + run.stderr
        assert f"Dask dashboard: http://127.0.0.1:{dash}/status" in run.stdout
        assert "4 ok, 0 failed of 4 missions" in run.stdout
        df = pd.read_parquet(out / "results.parquet")
        assert list(df["index"]) == [0, 1, 2, 3] and (df["status"] == "ok").all()
        assert set(df["runner_pid"]) == {procs[1].pid, procs[2].pid}  # both workers ran missions
        assert (out / "results.csv").exists() and (out / "summary_hist.png").exists()
        assert (out / "summary_vs_current_speed.png").exists() and (out / "summary_vs_current_angle.png").exists()
    finally:
        for p in reversed(procs):
            stop_process_group(p, 10.0)
        for log in logs:
            log.close()

"""One mission of a batch (docs/batch.md), in a process of its own.

    python -m unexmin.batch.task TASK.json      # what run_mission() starts; writes result.json beside TASK.json

run_mission(task) is the Dask task: it writes the mission's files, starts this module as a child process
(backend core: the engine in-process, with the robot descriptions the worker expanded once per overrides;
backend ros: its own rospy node, its own ROS master on a free loopback port, a lockstep world), waits for it
with a wall-time limit, and returns one row of the results table. A crash, a timeout, a missing or non-finite
metric is a failed attempt: it is retried (spec `retries`, default once) and, failing again, recorded with
its error and log path; run_mission itself never raises for a mission's failure.
"""

import json
import math
import os
import signal
import subprocess
import sys
import threading
import time
import traceback
import uuid

from unexmin.scripting.launcher import stop_process_group

RESULT = "result.json"


def mission_folder(out, index):
    return os.path.join(out, "missions", f"{index:05d}")


def _watch_parent():
    """Interrupt this process (as Ctrl-C: the mission's world closes) when the Dask worker that started it
    is gone, e.g. a batch stopped with Ctrl-C: a mission process is in a session of its own and would
    otherwise run on with its world."""
    parent = os.getppid()

    def watch():
        while os.getppid() == parent:
            time.sleep(1.0)
        os.kill(os.getpid(), signal.SIGINT)

    threading.Thread(target=watch, daemon=True, name="watch_parent").start()


def _child(task_path):
    """The child process: launch the mission's world, run the mission function, write result.json."""
    _watch_parent()
    with open(task_path) as f:
        task = json.load(f)
    spec, mission = task["spec"], task["mission"]
    folder = os.path.dirname(os.path.abspath(task_path))
    result = {"status": "failed", "error": "", "metrics": {}, "timings": {}}
    t0 = time.monotonic()
    try:
        sys.path[:0] = spec["python_path"]
        from unexmin.batch.spec import load_mission_function
        from unexmin.scripting.simulation import Simulation

        fn = load_mission_function(spec["mission"])
        params = dict(
            mission["params"],
            seed=mission["seed"],
            index=mission["index"],
            duration=spec["duration"],
            robots=spec["robots"],
        )
        os.environ.setdefault("ROS_HOME", os.path.join(folder, "ros_home"))
        if spec.get("backend", "core") == "core":
            descriptions = {}
            for name, path in task["descriptions"].items():
                with open(path) as f:
                    descriptions[name] = f.read()
            world = Simulation.launch(
                task["world_file"],
                robots=spec["robots"],
                seed=mission["seed"],
                backend="core",
                mode=spec["mode"],
                sensors=spec["sensors"],
                descriptions=descriptions,
                ray_caster_threads=spec["ray_caster_threads"],
            )
        else:
            world = Simulation.launch(
                launch_file=task["launch_file"],
                log_dir=os.path.join(folder, "logs"),
                timeout=min(120.0, spec["timeout"]),
                node_name="unexmin_batch",
            )
        with world as sim:
            result["timings"]["launch_s"] = round(time.monotonic() - t0, 3)
            metrics = fn(sim, params)
            result["timings"]["mission_s"] = round(time.monotonic() - t0 - result["timings"]["launch_s"], 3)
        result["timings"]["total_s"] = round(time.monotonic() - t0, 3)
        result["metrics"] = check_metrics(spec["mission"], metrics)
        result["status"] = "ok"
    except Exception as e:  # the parent records it: failures are data
        result["error"] = f"{type(e).__name__}: {e}"
        traceback.print_exc()
    with open(os.path.join(folder, RESULT + ".part"), "w") as f:
        json.dump(result, f)
    os.replace(os.path.join(folder, RESULT + ".part"), os.path.join(folder, RESULT))
    return 0 if result["status"] == "ok" else 1


def check_metrics(name, metrics):
    """`metrics` as {name: float|int|str|bool}; ValueError naming the mission and the bad metric otherwise."""
    if not isinstance(metrics, dict) or not metrics:
        raise ValueError(
            f"mission {name} returned {type(metrics).__name__} {metrics!r}: expected a non-empty dict of metrics"
        )
    clean = {}
    for key, value in metrics.items():
        if not isinstance(key, str) or not key.isidentifier():
            raise ValueError(f"mission {name}: metric name {key!r} is not an identifier")
        if hasattr(value, "item"):  # numpy scalars
            value = value.item()
        if isinstance(value, float) and not math.isfinite(value):
            raise ValueError(f"mission {name}: metric {key} is {value} (not finite)")
        if not isinstance(value, (int, float, str, bool)):
            raise ValueError(f"mission {name}: metric {key} = {value!r}: expected a number, a bool or a text")
        clean[key] = value
    return clean


def _attempt(task_path, folder, timeout, attempt):
    """Run the child once; (status, error, metrics)."""
    log_path = os.path.join(folder, f"attempt{attempt}.log")
    result_path = os.path.join(folder, RESULT)
    if os.path.exists(result_path):
        os.remove(result_path)
    marker = uuid.uuid4().hex  # every process of the attempt (child, roslaunch, nodes) inherits it
    outer = os.environ.get("UNEXMIN_RUN")
    env = dict(
        os.environ, UNEXMIN_RUN=f"{outer}:{marker}" if outer else marker, ROS_LOG_DIR=os.path.join(folder, "logs")
    )
    with open(log_path, "w") as log:
        proc = subprocess.Popen(
            [sys.executable, "-m", "unexmin.batch.task", task_path],
            stdout=log,
            stderr=subprocess.STDOUT,
            start_new_session=True,
            env=env,
        )
        try:
            proc.wait(timeout)
            timed_out = False
        except subprocess.TimeoutExpired:
            timed_out = True
        finally:  # SIGINT to the child (its world closes), then whatever of the attempt is left
            stop_process_group(proc, 15.0, marker)
    if timed_out:
        return "failed", f"timed out after {timeout:.0f} s of wall time", {}
    if not os.path.exists(result_path):
        return "failed", f"the mission process exited with code {proc.returncode} without a result", {}
    with open(result_path) as f:
        result = json.load(f)
    return result["status"], result["error"], result["metrics"]


_descriptions = {}  # (description file, robot, overrides text) -> URDF text: xacro once per worker and overrides


def mission_descriptions(spec, world_file, overrides, folder):
    """{robot: URDF file in `folder`} of the mission's robots (each robot's description of the world file, with the
    mission's overrides), expanded by xacro once per worker process for each distinct overrides text."""
    from unexmin.description import expand
    from unexmin.worlds.files import PACKAGE_DIR
    from unexmin.worlds.schema import read_world

    text = ""
    if overrides:
        with open(overrides) as f:
            text = f.read()
    files = {}
    for entry in read_world(world_file)["robots"][: spec["robots"]]:
        name, source = entry["name"], PACKAGE_DIR / "urdf" / entry.get("description", "ux1.urdf.xacro")
        key = (str(source), name, text)
        if key not in _descriptions:
            _descriptions[key] = expand(source, name, overrides or None)
        files[name] = os.path.join(folder, f"{name}.urdf")
        with open(files[name], "w") as f:
            f.write(_descriptions[key])
    return files


def run_mission(spec, mission, out):
    """Run one mission (Dask task) and return its row: index, seed, parameters, metrics, status, error, log,
    wall_time_s, attempts."""
    from unexmin.batch.spec import write_launch

    folder = mission_folder(out, mission["index"])
    t0 = time.monotonic()
    status, error, metrics = "failed", "", {}
    try:
        launch = write_launch(spec, mission, folder)
        task = {"spec": spec, "mission": mission, "launch_file": launch}
        if spec.get("backend", "core") == "core":
            task["world_file"] = os.path.join(folder, "mission.world")  # written by write_launch, as the overrides
            overrides = os.path.join(folder, "overrides.xacro")
            overrides = overrides if os.path.exists(overrides) else ""
            task["descriptions"] = mission_descriptions(spec, task["world_file"], overrides, folder)
        task_path = os.path.join(folder, "task.json")
        with open(task_path, "w") as f:
            json.dump(task, f, indent=1)
        attempts = 0
        for attempt in range(1, spec["retries"] + 2):
            attempts = attempt
            status, error, metrics = _attempt(task_path, folder, spec["timeout"], attempt)
            if status == "ok":
                break
        log = os.path.join(folder, f"attempt{attempts}.log")
    except Exception as e:  # the mission's files could not be written: a failure of this mission only
        error, attempts, log = f"{type(e).__name__}: {e}", 0, ""
    row = {"index": mission["index"], "seed": mission["seed"]}
    row.update(mission["params"])
    row.update(metrics)
    row.update(
        {
            "status": status,
            "error": error,
            "log": log,
            "attempts": attempts,
            "wall_time_s": round(time.monotonic() - t0, 3),
        }
    )
    return row


def main(argv=None):
    """`python -m unexmin.batch.task TASK.json`: one attempt of one mission, as run_mission starts it."""
    import argparse

    parser = argparse.ArgumentParser(
        prog="python -m unexmin.batch.task", description="One attempt of one batch mission (started by unexmin.batch)."
    )
    parser.add_argument("task", help="the task file run_mission writes (spec, mission, launch file)")
    return _child(parser.parse_args(argv).task)


if __name__ == "__main__":
    sys.exit(main())

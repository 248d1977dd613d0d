"""The ROS-free path (docs/python_api.md, "Back ends"): `from unexmin import Simulation`, a script of
`Simulation.launch(..., backend="core")`, `unexmin.core` and `unexmin.gym` run in a Python where no ROS module can be
imported. Each case runs in a child Python whose first import finder refuses rospy, rosgraph, genpy, the other ROS
client libraries and every message package (ours in message_packages/, unexmin.msg and unexmin.srv, any *_msgs or
*_srvs): the case fails if the code tries to import one (even an import it would survive) or finds one in sys.modules.
The ROS back end is imported only when chosen: choosing it in such a Python fails on its first ROS import.
"""

import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
MESSAGE_PACKAGES = sorted(p.name for p in (REPO / "message_packages").iterdir() if (p / "package.xml").is_file())

# The ROS 1 client libraries and tools a Python module could import (their top-level names).
ROS_LIBRARIES = (
    "rospy",
    "rosgraph",
    "genpy",
    "genmsg",
    "roslib",
    "rospkg",
    "rosbag",
    "roslaunch",
    "rosnode",
    "rostopic",
    "rosservice",
    "rosparam",
    "rosmsg",
    "rosunit",
    "rostest",
    "tf",
    "tf2_ros",
    "tf2_py",
    "actionlib",
    "message_filters",
    "dynamic_reconfigure",
)

# Defines is_ros(name) and the finder; run by the child (and by this file, to test is_ros).
BLOCKER = """
import importlib.abc


def is_ros(name):
    top = name.split(".")[0]
    own = name.split(".")[:2] in (["unexmin", "msg"], ["unexmin", "srv"])  # unexmin's generated messages, services
    return top in ROS_LIBRARIES or top in MESSAGE_PACKAGES or top.endswith(("_msgs", "_srvs")) or own


class RefuseRos(importlib.abc.MetaPathFinder):
    def __init__(self):
        self.tried = []

    def find_spec(self, name, path=None, target=None):
        if is_ros(name):
            self.tried.append(name)
            raise ModuleNotFoundError(f"{name}: a ROS module, refused on the ROS-free path", name=name)
        return None
"""

CHILD = """
import json, sys

ROS_LIBRARIES, MESSAGE_PACKAGES = json.loads(sys.argv[1])
exec(sys.argv[2])
loaded_before = sorted(m for m in sys.modules if is_ros(m))
finder = RefuseRos()
sys.meta_path.insert(0, finder)
result = {}
exec(compile(sys.argv[3], "<case>", "exec"), {"result": result})
print(json.dumps({
    "loaded_before": loaded_before,
    "tried": finder.tried,
    "loaded": sorted(m for m in sys.modules if is_ros(m)),
    "result": result,
}))
"""


def run_without_ros(case):
    """Run the Python text `case` in a child where no ROS module imports; it fills the dict `result`. Returns the
    child's report: loaded_before (ROS modules present before the finder), tried (ROS imports refused), loaded (ROS
    modules in sys.modules at the end), result."""
    names = json.dumps([list(ROS_LIBRARIES), MESSAGE_PACKAGES])
    out = subprocess.run(
        [sys.executable, "-c", CHILD, names, BLOCKER, case],
        capture_output=True,
        text=True,
        timeout=300,
        env=os.environ,
        cwd=REPO,
    )
    assert out.returncode == 0, f"the case failed:\n{out.stdout[-3000:]}\n{out.stderr[-3000:]}"
    return json.loads(out.stdout.strip().splitlines()[-1])


def assert_ros_free(report):
    assert not report["loaded_before"], f"ROS modules loaded at start-up: {report['loaded_before']}"
    assert not report["tried"], f"the ROS-free path tried to import ROS modules: {report['tried']}"
    assert not report["loaded"], f"ROS modules in sys.modules: {report['loaded']}"


@pytest.fixture(scope="module")
def rates():
    from unexmin.description import ROBOT_FILE, expand

    urdf = expand(ROBOT_FILE, "UX_1")
    return {s.get("name"): float(s.get("rate")) for s in ET.fromstring(urdf).iter("sensor")}


def is_ros_here():
    ns = {"ROS_LIBRARIES": ROS_LIBRARIES, "MESSAGE_PACKAGES": MESSAGE_PACKAGES}
    exec(BLOCKER, ns)
    return ns["is_ros"]


@pytest.mark.parametrize(
    "name,expected",
    [
        ("rospy", True),
        ("rospy.impl.registration", True),
        ("rosgraph", True),
        ("genpy", True),
        ("nav_msgs.msg", True),
        ("std_srvs.srv", True),
        ("kvh_1775.msg", True),
        ("dvl_nortek", True),
        ("unexmin.msg", True),
        ("unexmin.srv._Step", True),
        ("unexmin.core", False),
        ("unexmin.scripting.simulation", False),
        ("numpy", False),
        ("gymnasium", False),
    ],
)
def test_ros_modules_are_told_from_the_rest(name, expected):
    assert is_ros_here()(name) is expected


def test_the_child_refuses_ros_modules_and_reports_them():
    case = """
for name in ("rospy", "nav_msgs.msg", "kvh_1775.msg", "unexmin.srv"):
    try:
        __import__(name)
    except ModuleNotFoundError as e:
        result[name] = str(e)
import numpy
result["numpy"] = numpy.__name__
"""
    report = run_without_ros(case)
    assert report["tried"] == ["rospy", "nav_msgs", "kvh_1775", "unexmin.srv"]
    assert set(report["result"]) == {"rospy", "nav_msgs.msg", "kvh_1775.msg", "unexmin.srv", "numpy"}
    assert not report["loaded"]


def test_core_back_end_runs_without_ros(rates):
    case = """
from unexmin import Simulation

with Simulation.launch("tank", seed=3, sensors="imu,dvl", backend="core") as sim:
    ux = sim.robot("UX_1")
    start = ux.state()["position"].tolist()
    ux.thrusts([6.0, 2.0, -6.0, -2.0, 6.0, 2.0, -6.0, -2.0])
    result["time"] = sim.step(250)
    with ux.collect("dvl") as dvl:
        sim.run_for(1.0)
    result["dvl"] = len(dvl)
    result["imu_time"] = ux.latest("kvh/imu_raw")["time"]
    result["end"] = sim.time
    result["moved"] = sum((a - b) ** 2 for a, b in zip(ux.state()["position"].tolist(), start)) ** 0.5
    result["rate"] = sim.physics_rate
    result["backend"] = sim.backend
"""
    report = run_without_ros(case)
    assert_ros_free(report)
    r = report["result"]
    assert r["backend"] == "core"
    assert r["time"] == pytest.approx(250 / r["rate"], abs=1e-12)
    assert r["end"] == pytest.approx(r["time"] + 1.0, abs=1e-9)
    assert r["dvl"] == round(1.0 * rates["dvl"]), "a DVL sample lost or doubled over 1 s"
    assert r["end"] - 1.0 / rates["imu"] - 1e-9 <= r["imu_time"] <= r["end"] + 1e-9
    assert r["moved"] > 0.01, "the thrusts did not move the robot"


@pytest.mark.parametrize(
    "case",
    [
        "import unexmin.core\nw = unexmin.core.World('tank', sensors='imu')\nresult['t'] = w.step(5)",
        "import gymnasium, unexmin.gym\nenv = gymnasium.make('unexmin/StationKeeping-v0')\n"
        "env.reset(seed=0)\nresult['reward'] = float(env.step(env.action_space.sample())[1])\nenv.close()",
        "from unexmin import Simulation\nresult['name'] = Simulation.__name__",
    ],
    ids=["core", "gym", "facade"],
)
def test_modules_import_and_run_without_ros(case):
    assert_ros_free(run_without_ros(case))


def test_the_ros_back_end_is_imported_only_when_chosen():
    case = """
from unexmin import Simulation
for call in (lambda: Simulation.launch("tank"), lambda: Simulation(timeout=1.0)):
    try:
        call()
    except ModuleNotFoundError as e:
        result.setdefault("errors", []).append(e.name)
"""
    report = run_without_ros(case)
    assert report["result"]["errors"] == ["rosgraph", "rosgraph"], report
    assert report["tried"] == ["rosgraph", "rosgraph"]


def test_core_odom_without_nav_msgs_names_what_it_needs():
    case = """
from unexmin import Simulation
with Simulation.launch("tank", sensors="none", backend="core") as sim:
    sim.step(1)
    try:
        sim.robot("UX_1").odom()
    except ImportError as e:
        result["error"] = str(e)
"""
    report = run_without_ros(case)
    assert "nav_msgs" in report["result"]["error"] and "state()" in report["result"]["error"]
    assert report["tried"] and all(name in ("genpy", "nav_msgs") for name in report["tried"]), report["tried"]

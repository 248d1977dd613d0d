"""Your own workspace (README): scripts/add_to_workspace.sh links the package and its msg packages into
<ws>/src, and the package then builds and runs there.

The first tests check the links (idempotent, stale links removed, refusals); the last one builds the
simulator in a fresh workspace made that way, with an environment from which the project's own
workspace is removed (so nothing is found through it), starts `roslaunch unexmin tank_world.launch`
from that workspace on a private master and waits for the simulation clock to advance, for UX_1's
odometry and for every node of the launch file (the rospy nodes import the generated messages).
The fresh workspace compiles through the project workspace's ccache (scripts/setup.sh): a compile whose source,
headers (each where the fresh workspace finds it) and flags are byte-identical to one of set-up's takes that object,
anything else is compiled; configuring, generating the messages and linking are all done in the fresh workspace.
"""

import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

from unexmin.scripting.launcher import free_port, stop_process_group, wait_for

REPO = Path(__file__).resolve().parents[2]
REAL = REPO.resolve()
SCRIPT = REPO / "scripts" / "add_to_workspace.sh"
MSGS = sorted(p.name for p in (REPO / "message_packages").iterdir() if (p / "package.xml").is_file())
# What a workspace-sourced shell has set (scripts/env.sh, <ws>/devel/setup.bash).
WORKSPACE_VARS = (
    "CMAKE_PREFIX_PATH",
    "ROS_PACKAGE_PATH",
    "PYTHONPATH",
    "LD_LIBRARY_PATH",
    "PKG_CONFIG_PATH",
    "ROSLISP_PACKAGE_DIRECTORIES",
    "UNEXMIN_WS",
    "UNEXMIN_REPO",
)


def add(ws, *flags, script=SCRIPT):
    return subprocess.run(["bash", str(script), *flags, str(ws)], capture_output=True, text=True, timeout=60)


def links(src):
    return {p.name: os.readlink(p) for p in src.iterdir() if p.is_symlink()}


def expected_links(repo):
    return {"unexmin": str(repo), **{m: str(repo / "message_packages" / m) for m in MSGS}}


def test_links_the_package_and_its_msg_packages_idempotently(tmp_path):
    ws = tmp_path / "catkin_ws"  # no src/ yet
    first = add(ws)
    assert first.returncode == 0, first.stderr
    assert links(ws / "src") == expected_links(REAL)
    assert "catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3" in first.stdout  # what to run next
    again = add(ws, "--quiet")
    assert again.returncode == 0, again.stderr
    assert again.stdout == ""  # nothing changed, nothing said
    assert links(ws / "src") == expected_links(REAL)


def test_removes_only_the_stale_links_it_made(tmp_path):
    src = tmp_path / "ws" / "src"
    src.mkdir(parents=True)
    (src / "old_msgs").symlink_to(REAL / "message_packages" / "old_msgs")  # a msg package since removed
    (src / "unexmin").symlink_to(tmp_path)  # an older link to another copy
    (src / "theirs").symlink_to(tmp_path / "elsewhere")  # the user's own (broken) link
    (src / "CMakeLists.txt").symlink_to("/usr/share/catkin/cmake/toplevel.cmake")
    (src / "my_pkg").mkdir()
    out = add(tmp_path / "ws")
    assert out.returncode == 0, out.stderr
    assert not os.path.lexists(src / "old_msgs")
    assert f"removed stale link {src / 'old_msgs'}" in out.stdout
    assert links(src) == {
        **expected_links(REAL),
        "theirs": str(tmp_path / "elsewhere"),
        "CMakeLists.txt": "/usr/share/catkin/cmake/toplevel.cmake",
    }
    assert (src / "my_pkg").is_dir()


def test_refuses_another_copy_and_a_workspace_inside_the_repository(tmp_path):
    src = tmp_path / "ws" / "src"
    (src / "ux1_msgs").mkdir(parents=True)  # another copy of a msg package
    out = add(tmp_path / "ws")
    assert out.returncode == 1
    assert f"{src / 'ux1_msgs'} exists and is not a link" in out.stderr
    assert links(src) == {}  # checked before changing anything
    inside = REPO / "catkin_ws_test_own_workspace"
    out = add(inside)
    assert out.returncode == 1
    assert "inside the repository" in out.stderr
    assert not inside.exists()
    assert add("").returncode == 2 and "usage:" in add("").stderr


def test_a_clone_inside_src_gets_only_its_msg_packages_beside_it(tmp_path):
    """`git clone` into <ws>/src, then the clone's own script: catkin finds the clone, and the links."""
    clone = tmp_path / "ws" / "src" / "unexmin"
    (clone / "scripts").mkdir(parents=True)
    shutil.copy2(SCRIPT, clone / "scripts")
    shutil.copy2(REPO / "package.xml", clone)
    shutil.copytree(REPO / "message_packages", clone / "message_packages")
    out = add(tmp_path / "ws", script=clone / "scripts" / "add_to_workspace.sh")
    assert out.returncode == 0, out.stderr
    assert "already inside" in out.stdout
    assert links(clone.parent) == {m: str(clone.resolve() / "message_packages" / m) for m in MSGS}


def clean_env(tmp_path):
    """This environment without the project's workspace: only what add_to_workspace.sh links counts."""
    env = {k: v for k, v in os.environ.items() if k not in WORKSPACE_VARS and not k.startswith("ROS_")}
    venv = Path(os.environ.get("UNEXMIN_VENV", sys.prefix))  # xacro 1.13.3 for the launch files
    path = [p for p in env.get("PATH", "").split(os.pathsep) if p and not p.endswith("/devel/bin")]
    env["PATH"] = os.pathsep.join([str(venv / "bin"), *path])
    env.update(ROS_HOME=str(tmp_path / "ros_home"), ROS_LOG_DIR=str(tmp_path / "ros_log"))
    return env


def compiler_launcher(ws):
    """setup.sh's ccache launcher for workspace `ws`, reading and filling the cache of the project's workspace
    (UNEXMIN_WS; paths under `ws` hashed relative to it, as setup.sh's are to its own)."""
    cache = Path(os.environ["UNEXMIN_WS"]).resolve() / "ccache"
    return f"/usr/bin/env;CCACHE_DIR={cache};CCACHE_BASEDIR={ws.resolve()};CCACHE_MAXSIZE=1G;ccache"


def in_workspace(ws, command):
    """`command` (a list) in a shell that has sourced <ws>/devel/setup.bash."""
    return ["bash", "-c", 'source "$0/devel/setup.bash" && exec "$@"', str(ws), *command]


CHECK = """
import sys, threading, time
import rosnode, rospy
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
expected, seen, advanced = set(sys.argv[1:]), {}, threading.Event()
def on_clock(m):
    seen.setdefault("t0", m.clock.to_sec())
    seen["t1"] = m.clock.to_sec()
    if "odom" in seen and seen["t1"] >= seen["t0"] + 1.0:
        advanced.set()
def on_odom(m):
    seen["odom"] = m.pose.pose.position
rospy.init_node("own_workspace_check", anonymous=True, disable_signals=True)
rospy.Subscriber("/clock", Clock, on_clock)
rospy.Subscriber("/UX_1/odom", Odometry, on_odom)
deadline = time.monotonic() + 150
while True:
    missing = expected - set(rosnode.get_node_names())
    if advanced.is_set() and not missing:
        break
    if time.monotonic() > deadline:
        sys.exit(f"after 150 s: 1 s of /clock with /UX_1/odom: {advanced.is_set()} (saw {sorted(seen)}); "
                 f"nodes not up: {sorted(missing)}")
    time.sleep(0.1)
print(f"clock {seen['t0']:.3f} -> {seen['t1']:.3f} s, UX_1 at z = {seen['odom'].z:.3f} m, nodes up: {sorted(expected)}")
"""


@pytest.mark.long
def test_builds_and_runs_in_a_fresh_workspace(tmp_path):
    ws = tmp_path / "catkin_ws"
    env = clean_env(tmp_path)
    out = subprocess.run(["bash", str(SCRIPT), "--quiet", str(ws)], env=env, capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    launcher = compiler_launcher(ws)

    # setup.sh's flags; only the simulator, the bind shim env.sh's roslaunch preloads and the messages the
    # launch file's Python nodes import
    targets = ["simulator_node", "unexmin_bind_shim", *(f"{p}_generate_messages" for p in ("unexmin", *MSGS))]
    start = time.monotonic()
    with open(tmp_path / "build.log", "w") as log:
        build = subprocess.run(
            [
                "catkin_make",
                "-C",
                str(ws),
                "-DPYTHON_EXECUTABLE=/usr/bin/python3",
                "-DPython3_EXECUTABLE=/usr/bin/python3",
                "-DCMAKE_BUILD_TYPE=Release",
                "-DCATKIN_ENABLE_TESTING=OFF",
                f"-DCMAKE_C_COMPILER_LAUNCHER={launcher}",
                f"-DCMAKE_CXX_COMPILER_LAUNCHER={launcher}",
                "-j2",
                *targets,
            ],
            env=env,
            stdout=log,
            stderr=subprocess.STDOUT,
            timeout=900,
        )
    build_s = time.monotonic() - start
    assert build.returncode == 0, (tmp_path / "build.log").read_text()[-3000:]

    where = subprocess.run(
        in_workspace(ws, ["bash", "-c", 'echo "$CMAKE_PREFIX_PATH"; rospack find unexmin; rospack find ux1_msgs']),
        env=env,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert where.returncode == 0, where.stderr
    assert where.stdout.split() == [str(ws / "devel"), str(ws / "src" / "unexmin"), str(ws / "src" / "ux1_msgs")]

    nodes = subprocess.run(
        in_workspace(ws, ["roslaunch", "--nodes", "unexmin", "tank_world.launch"]),
        env=env,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert nodes.returncode == 0 and "/simulator" in nodes.stdout.split(), nodes.stderr

    port = free_port()
    env.update(ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_IP="127.0.0.1")
    launch_log = open(tmp_path / "roslaunch.log", "w")
    launch = subprocess.Popen(
        in_workspace(ws, ["roslaunch", "--port", str(port), "unexmin", "tank_world.launch"]),
        env=env,
        stdout=launch_log,
        stderr=subprocess.STDOUT,
        start_new_session=True,
    )
    check = subprocess.Popen(
        in_workspace(ws, ["python3", "-c", CHECK, *nodes.stdout.split()]),
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        start_new_session=True,
    )

    def launch_log_text():
        return (tmp_path / "roslaunch.log").read_text()

    try:
        try:
            wait_for(
                lambda: launch.poll() is not None
                or check.poll() is not None
                or "process has died" in launch_log_text(),
                180,
                "/clock, /UX_1/odom and every node of tank_world.launch from the fresh workspace",
                poll=0.2,
            )
        except TimeoutError as e:
            pytest.fail(f"{e}\nroslaunch:\n{launch_log_text()[-3000:]}")
        log = launch_log_text()
        assert launch.poll() is None, f"roslaunch exited ({launch.returncode}):\n{log[-3000:]}"
        assert "process has died" not in log, log[-3000:]  # a node of the launch file failed from here
        report = check.communicate(timeout=10)[0]
        assert check.returncode == 0, f"{report}\nroslaunch:\n{log[-3000:]}"
        print(f"built in {build_s:.0f} s; {report.strip()}")
    finally:
        stop_process_group(check)
        stop_process_group(launch, 30.0)
        launch_log.close()
    shutil.rmtree(ws / "build")  # a few hundred MB; kept when the test fails

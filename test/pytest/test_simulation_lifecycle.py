"""The scripting API's life cycle (python/unexmin/scripting/simulation.py, python/unexmin/scripting/ros_backend.py),
in this process as a script uses it.

- `with Simulation.launch(...) as sim:` stops the launched world (roslaunch, master, simulator) when
  the block raises, whatever it raises, and when it ends normally: every process of the world
  (roslaunch, the master, the nodes) is gone and its master port refuses connections.
- One open Simulation per process (rospy: one node, one master): a second launch or join while one
  is open raises RuntimeError saying why and what to do; after close(), a new launch works, on the
  same master port (rospy stays bound to the master it first registered with).
- Robots and thruster counts come from the simulator (/sim/robots, /sim/thruster_count/<robot>);
  an unknown robot raises KeyError at once, naming the known ones.
- A world that dies at start-up gives a RuntimeError naming its log, and leaves nothing running.
"""

import os
import socket
import time
from pathlib import Path

import pytest

ENV_KEYS = ("ROS_MASTER_URI", "ROS_IP", "ROS_LOG_DIR")
pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")  # rospy's own (notifyAll, warn)


@pytest.fixture(autouse=True, scope="module")
def restore_environment():
    """Simulation.launch points this process's ROS_MASTER_URI and ROS_LOG_DIR at its world: put them
    back for the test modules that follow."""
    saved = {k: os.environ.get(k) for k in ENV_KEYS}
    yield
    for k, v in saved.items():
        if v is None:
            os.environ.pop(k, None)
        else:
            os.environ[k] = v


def processes():
    """{pid: (parent pid, command name)} of the live (not zombie) processes."""
    table = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue
        fields = stat[stat.rindex(")") + 2 :].split()  # after "pid (comm) ": state ppid ...
        if fields[0] != "Z":
            table[int(entry.name)] = (int(fields[1]), stat[stat.index("(") + 1 : stat.rindex(")")])
    return table


def world_tree(root):
    """{pid: command name} of `root` (the world's roslaunch) and every live process below it: the
    master and the nodes (roslaunch starts each in a session of its own)."""
    table = processes()
    tree, grew = {root} & set(table), True
    while grew:
        below = {pid for pid, (ppid, _) in table.items() if ppid in tree} - tree
        tree |= below
        grew = bool(below)
    return {pid: table[pid][1] for pid in tree}


def alive(pids):
    table = processes()
    return [pid for pid in pids if pid in table]


def port_open(port):
    with socket.socket() as s:
        s.settimeout(1.0)
        return s.connect_ex(("127.0.0.1", port)) == 0


def launch(tmp_path, name, **kwargs):
    from unexmin import Simulation

    return Simulation.launch("tank", log_dir=str(tmp_path / name), **kwargs)


def test_with_block_stops_the_world_on_an_exception_then_a_second_launch_works(tmp_path):
    class Boom(Exception):
        pass

    with pytest.raises(Boom):
        with launch(tmp_path, "first", seed=1) as sim:
            world = sim._world
            port = world.port
            tree = world_tree(world.proc.pid)
            assert {"roslaunch", "rosmaster", "simulator_node"} <= set(tree.values()), tree
            assert port_open(port)
            sim.robot("UX_1").thrusts([0.0] * 8)
            sim.run_for(0.5)
            raise Boom()
    assert world.proc.returncode is not None
    assert alive(tree) == []
    assert not port_open(port)

    # The same process launches again (on the same master port) and the new world works.
    with launch(tmp_path, "second", seed=1) as sim:
        assert sim._world.port == port
        tree = world_tree(sim._world.proc.pid)
        ux = sim.robot("UX_1")
        assert sim.run_for(0.5) == pytest.approx(0.5, abs=1e-12)
        assert ux.latest("imu").header.stamp.to_sec() == pytest.approx(0.5, abs=1e-9)
    assert alive(tree) == []  # normal exit of the block: stopped too


def test_keyboard_interrupt_also_stops_the_world(tmp_path):
    with pytest.raises(KeyboardInterrupt):
        with launch(tmp_path, "ctrl_c") as sim:
            tree = world_tree(sim._world.proc.pid)
            raise KeyboardInterrupt
    assert len(tree) >= 3 and alive(tree) == []


def test_one_open_simulation_per_process_with_a_clear_error(tmp_path):
    from unexmin import Simulation

    with launch(tmp_path, "open") as sim:
        for attempt in (lambda: Simulation.launch("tank"), lambda: Simulation(timeout=5.0)):
            with pytest.raises(RuntimeError) as e:
                attempt()
            msg = str(e.value)
            assert "already has an open Simulation" in msg and sim.master_uri in msg
            assert "one ROS node per process" in msg and "close()" in msg
        assert sim.run_for(0.1) == pytest.approx(0.1)  # the open one is untouched
    sim.close()  # idempotent


def test_robots_and_thruster_counts_come_from_the_simulator(tmp_path):
    with launch(tmp_path, "two", robots=2) as sim:
        assert sim.robots == ("UX_1", "UX_2")  # tank.world's first two spawn entries
        ux2 = sim.robot("UX_2", streams="none")
        assert ux2.thruster_count == 8  # the UX-1's eight thrusters
        with pytest.raises(ValueError, match="thrusts needs 8 values for UX_2"):
            ux2.thrusts([1.0] * 7)
        t0 = time.monotonic()
        with pytest.raises(KeyError) as e:
            sim.robot("UX_9")
        assert time.monotonic() - t0 < 0.5  # at once: no wait for topics that never come
        assert "UX_9" in str(e.value) and "UX_1, UX_2" in str(e.value)
        with pytest.raises(KeyError, match="UX_3"):  # in tank.world, but not spawned (robots=2)
            sim.robot("UX_3")


def test_a_world_that_dies_at_start_up_names_its_log_and_leaves_nothing(tmp_path):
    with pytest.raises(RuntimeError, match=r"exited .*see .*roslaunch\.log") as e:
        launch(tmp_path, "bad", robots=4, timeout=60.0)  # tank.world spawns at most 3
    log = Path(str(e.value).split("see ")[-1].rstrip(")"))
    assert log.is_file() and "robots" in log.read_text()
    with launch(tmp_path, "after_bad") as sim:  # the failed launch released the process
        assert sim.step(1) == pytest.approx(1.0 / sim.physics_rate)

"""Two hosts on one machine, for the hardware-in-the-loop test and bench (docs/real_robot.md): two network
namespaces, "robot" and "simulator", joined by a veth pair with link-local addresses (a link between these two
namespaces only). The robot's host runs a master and the stand-in (unexmin.hil.robot_standin); the simulator's
host runs the tank world in real time and the ESC driver, on the robot's master, and a probe (unexmin.hil.probe)
records what arrives there. Needs root (`ip netns`). Everything is stopped and both namespaces are deleted on the
way out, whatever happened."""

import json
import os
import subprocess
import sys
import time
from pathlib import Path

from unexmin.bind_shim import ros_environment
from unexmin.hil.probe import link_drop, load
from unexmin.scripting.launcher import marked_processes, stop_process_group, wait_for

SIM_ADDRESS, ROBOT_ADDRESS = "169.254.73.1", "169.254.73.2"
ROBOT_MASTER = f"http://{ROBOT_ADDRESS}:11311"
TIME_PORT = 11399  # the stand-in's clock-offset server (UDP, on the robot's link address)
ROBOT_DEVICE = "hil-robot"  # the robot's end of the veth pair (taken down to drop the link)


def ip(*args):
    run = subprocess.run(["ip", *args], capture_output=True, text=True, timeout=30)
    if run.returncode != 0:
        raise RuntimeError(f"ip {' '.join(args)}: {run.stderr.strip()}")


class HilRig:
    """`with HilRig(folder) as rig:` the two hosts, each process's output in `folder`."""

    def __init__(self, folder, period=1.0, rate=10.0, sensors="imu,dvl,pressure"):
        self.folder, self.period, self.rate, self.sensors = Path(folder), period, rate, sensors
        tag = os.getpid()
        self.robot_ns, self.sim_ns = f"unexmin-hil-robot-{tag}", f"unexmin-hil-sim-{tag}"
        self.marker = f"unexmin-hil-{tag}"
        self.procs = []
        self.record = self.folder / "sim_probe.jsonl"  # the simulator host's probe
        self.robot_record = self.folder / "robot_probe.jsonl"  # the robot host's probe (sensors, thrust coming back)

    # --------------------------------------------------------------------------------------------- set-up
    def __enter__(self):
        try:
            self._network()
            self._start()
        except BaseException:
            self.close()
            raise
        return self

    def __exit__(self, *exc):
        self.close()

    def _network(self):
        for ns in (self.robot_ns, self.sim_ns):
            ip("netns", "add", ns)
        ip(
            "link",
            "add",
            "hil-sim",
            "netns",
            self.sim_ns,
            "type",
            "veth",
            "peer",
            "name",
            ROBOT_DEVICE,
            "netns",
            self.robot_ns,
        )
        ends = ((self.sim_ns, "hil-sim", SIM_ADDRESS), (self.robot_ns, ROBOT_DEVICE, ROBOT_ADDRESS))
        for ns, device, address in ends:
            ip("-n", ns, "addr", "add", f"{address}/30", "dev", device)
            ip("-n", ns, "link", "set", device, "up")
            ip("-n", ns, "link", "set", "lo", "up")

    def environment(self, address):
        """This process's environment for a process of the host at `address`: ROS_IP, the robot's master, the
        bind shim preloaded, ROS's logs in the rig's folder."""
        env = {k: v for k, v in os.environ.items() if k not in ("ROS_IP", "ROS_HOSTNAME", "LD_PRELOAD")}
        env.update(
            ROS_IP=address,
            ROS_MASTER_URI=ROBOT_MASTER,
            ROS_HOME=str(self.folder / "ros_home"),
            UNEXMIN_RUN=self.marker,
            PYTHONUNBUFFERED="1",
        )
        return ros_environment(env)

    def start(self, ns, address, name, *command, preload=True):
        """Start `command` in the namespace `ns` (output in <folder>/<name>.out); without the bind shim preloaded
        when not `preload` (the hil tools load it themselves)."""
        out = open(self.folder / f"{name}.out", "w")
        env = self.environment(address)
        if not preload:
            del env["LD_PRELOAD"]
        proc = subprocess.Popen(
            ["ip", "netns", "exec", ns, *command], env=env, stdout=out, stderr=subprocess.STDOUT, start_new_session=True
        )
        self.procs.append((name, proc))
        return proc

    def python(self, ns, address, name, module, *args):
        """Start a hil tool as a user would: `python -m module args`, the bind shim not preloaded."""
        return self.start(ns, address, name, sys.executable, "-m", module, *map(str, args), preload=False)

    def _start(self):
        self.start(self.robot_ns, ROBOT_ADDRESS, "roscore", "roscore", "-p", "11311")
        wait_for(lambda: self.master_up() or self.died(), 60, "the robot's master")
        self.python(
            self.robot_ns,
            ROBOT_ADDRESS,
            "robot_standin",
            "unexmin.hil.robot_standin",
            "--period",
            self.period,
            "--rate",
            self.rate,
            "--time-port",
            TIME_PORT,
        )
        self.start(
            self.sim_ns,
            SIM_ADDRESS,
            "simulator",
            "roslaunch",
            "unexmin",
            "tank_world.launch",
            "control:=false",
            f"sensors:={self.sensors}",
        )
        self.start(
            self.sim_ns,
            SIM_ADDRESS,
            "esc_driver",
            "roslaunch",
            "unexmin",
            "control.launch",
            "allocator:=false",
            "esc_driver:=true",
        )
        self.python(self.sim_ns, SIM_ADDRESS, "sim_probe", "unexmin.hil.probe", "--out", self.record)
        self.python(
            self.robot_ns,
            ROBOT_ADDRESS,
            "robot_probe",
            "unexmin.hil.probe",
            "--out",
            self.robot_record,
            "--sensor-topic",
            "/UX_1/kvh/imu_raw",
        )
        # Running: the commands' steps reach the simulator's thrust, and the sensors come back to the robot.
        wait_for(
            lambda: self.died()
            or (self.steps() >= 2 and self.robot_record.exists() and load(self.robot_record)["sensor"]),
            120,
            "the simulator to follow the robot's commands",
        )
        failed = self.died()
        if failed:
            raise RuntimeError(f"{failed} stopped: {(self.folder / (failed + '.out')).read_text()[-3000:]}")

    # --------------------------------------------------------------------------------------------- state
    def died(self):
        """The name of a process of the rig that has exited, else None."""
        return next((name for name, proc in self.procs if proc.poll() is not None), None)

    def master_up(self):
        run = subprocess.run(
            ["ip", "netns", "exec", self.robot_ns, "ss", "-ltnH", "sport = :11311"],
            capture_output=True,
            text=True,
            timeout=30,
        )
        return ROBOT_ADDRESS in run.stdout

    def steps(self):
        """How many changes of the ESC driver's thruster input the simulator's probe has seen."""
        if not self.record.exists():
            return 0
        values = [e["v"] for e in load(self.record)["in"]]
        return sum(1 for a, b in zip(values, values[1:]) if a != b)

    def run_in(self, ns, address, module, *args, timeout=30):
        """Run `python -m module args` in `ns` to its end: (exit status, stdout, seconds taken)."""
        start = time.monotonic()
        run = subprocess.run(
            ["ip", "netns", "exec", ns, sys.executable, "-m", module, *map(str, args)],
            env=self.environment(address),
            capture_output=True,
            text=True,
            timeout=timeout,
        )
        return run.returncode, run.stdout + run.stderr, time.monotonic() - start

    def listening(self, ns):
        """[(local address, port, process)] of every TCP and UDP socket listening in the namespace `ns`."""
        run = subprocess.run(["ip", "netns", "exec", ns, "ss", "-ltunpH"], capture_output=True, text=True, timeout=30)
        found = []
        for line in run.stdout.splitlines():
            fields = line.split()
            address, port = fields[4].rsplit(":", 1)
            found.append((address.strip("[]"), int(port), fields[-1]))
        return found

    def clock_offset(self, samples=20):
        """The four-timestamp exchange from the simulator's host with the stand-in's time server: {offset, delay}
        [s], offset = robot clock - simulator host's clock."""
        code = (
            "import json, sys; from unexmin.hil.clock_sync import measure_offset; "
            f"print(json.dumps(measure_offset('{ROBOT_ADDRESS}', {TIME_PORT}, {samples})))"
        )
        run = subprocess.run(
            ["ip", "netns", "exec", self.sim_ns, sys.executable, "-c", code],
            env=self.environment(SIM_ADDRESS),
            capture_output=True,
            text=True,
            timeout=30,
        )
        if run.returncode != 0:
            raise RuntimeError(f"clock offset: {run.stderr.strip()}")
        return json.loads(run.stdout)

    def link(self, up):
        """Take the robot's end of the link down (False) or up (True); returns the wall time it was done."""
        ip("-n", self.robot_ns, "link", "set", ROBOT_DEVICE, "up" if up else "down")
        return time.time()

    def wait_steps(self, count, timeout=60):
        """Wait until the simulator's probe has seen `count` more steps of the thruster input; the time of the last."""
        target = self.steps() + count
        wait_for(lambda: self.steps() >= target or self.died(), timeout, f"{count} steps of the robot's command")
        return load(self.record)["in"][-1]["t"]

    def drop_link(self, seconds, during=None):
        """0.7 level period after a step of the command (the thrust settled on its level), take the link down for
        `seconds` [s], calling during() meanwhile; returns the wall times (down, up) [s]."""
        step = self.wait_steps(1)
        wait_for(lambda: time.time() >= step + 0.7 * self.period, self.period, "0.7 level period")
        down = self.link(False)
        try:
            result = during() if during else None
            remaining = down + seconds - time.time()
            if remaining > 0:
                time.sleep(remaining)  # the drop itself lasts `seconds`: nothing to wait for
        finally:
            up = self.link(True)
        return down, up, result

    def wait_recovered(self, down, up, offset, timeout=30):
        """Wait until a command stamped after `up` (robot clock - `offset` = this host's) has reached the simulator
        and its thrust has followed; unexmin.hil.probe.link_drop's figures of the drop from `down` to `up`."""

        def recovered():
            figures = link_drop(load(self.record), down, up, offset)
            return figures if figures["thrust_follows_after"] is not None or self.died() else None

        return wait_for(recovered, timeout, "the link to recover (a fresh command followed by the thrust)", poll=0.2)

    # --------------------------------------------------------------------------------------------- tear-down
    def close(self):
        for _name, proc in reversed(self.procs):
            stop_process_group(proc, 10.0)
        for pid in marked_processes(self.marker):  # anything a roslaunch left behind
            try:
                os.kill(pid, 9)
            except ProcessLookupError:
                pass
        for ns in (self.robot_ns, self.sim_ns):  # deleting a namespace deletes its end of the veth pair and the pair
            subprocess.run(["ip", "netns", "delete", ns], capture_output=True, timeout=30)

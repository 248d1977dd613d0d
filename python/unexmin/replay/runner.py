"""Plays a mission's timed commands into a paused simulator, step by step, and samples the robot."""

import math
import time

import numpy as np

from unexmin.replay.errors import ReplayError
from unexmin.replay.metrics import TRAJ_COLUMNS, pose_row
from unexmin.topics import ESC_COMMAND_TOPIC


class LockstepRunner:
    """Plays timed commands into a paused simulator with /sim/step and samples the robot's pose.

    Motor commands are published on motors_topic and converted by an ESC driver running in this
    process (the same class as nodes/esc_driver). The runner waits until the driver has published
    the thrusts and tells the Simulation how many command messages went out, so the next /sim/step
    waits for them: every command applies from the physics step after its time, deterministically.
    Mission time 0 is LEAD seconds after the (re)start, so the first sample is the start pose.
    The robot's sensor streams are not subscribed (the samples come with each step's answer), so the
    simulator builds no sensor message for this runner.
    """

    LEAD = 0.02  # [s] between the reset and mission time 0

    def __init__(self, sim, robot="UX_1", motors_topic=ESC_COMMAND_TOPIC, sample_period=0.1, timeout=30.0):
        """sim: a unexmin.Simulation; sample_period [s]: a whole number of physics steps; timeout [s] of
        wall time for the ESC driver to connect and to handle each command."""
        from ux1_msgs.msg import MotorCommand

        from unexmin.control.esc_driver_node import EscDriverNode
        from unexmin.scripting.launcher import wait_for
        from unexmin.topics import sync_publisher

        self.MotorCommand = MotorCommand
        self._timing(sim, robot, sample_period, timeout)
        self.driver = EscDriverNode(robot=robot, motor_topic=motors_topic, announce=False)
        self.pub = sync_publisher(motors_topic, MotorCommand)
        wait_for(
            lambda: self.pub.get_num_connections() > 0
            and all(p.get_num_connections() > 0 for p in self.driver.thruster_pubs),
            timeout,
            f"the ESC driver and the simulator to connect on {motors_topic} and /{robot}/thrusters",
        )
        self.sent = 0

    def _timing(self, sim, robot, sample_period, timeout):
        """The runner's simulation, robot handle (no streams) and step counts; ReplayError for a sample period that
        is not a whole number of physics steps."""
        self.sim, self.timeout = sim, timeout
        self.rate = sim.physics_rate
        self.lead_steps = max(1, round(self.LEAD * self.rate))
        self.sample_steps = round(sample_period * self.rate)
        if self.sample_steps < 1 or abs(self.sample_steps - sample_period * self.rate) > 1e-6:
            raise ReplayError(
                f"--sample-period {sample_period} s must be a whole number of physics steps ({1.0 / self.rate} s)"
            )
        self.ux = sim.robot(robot, streams="none")

    def close(self):
        """Unregister the runner's publisher and its ESC driver (the Simulation closes the rest)."""
        self.pub.unregister()
        self.driver.close()

    def _apply(self, kind, payload, t_sim):
        import rospy

        if kind == "motors":
            mode, values = payload
            msg = self.MotorCommand()
            msg.header.stamp = rospy.Time.from_sec(t_sim)
            msg.mode = mode
            msg.values = list(values)
            published = self.driver.published
            self.pub.publish(msg)
            self.sent += 1
            if not self.driver.wait_processed(self.sent, self.timeout):
                raise RuntimeError(f"the ESC driver did not handle motor command {self.sent} within {self.timeout} s")
            # The driver publishes from this node: the next /sim/step waits until these have arrived.
            self.sim.note_published(self.driver.published - published)
        elif kind == "pendulum":
            self.ux.pendulum(payload)
        else:
            self.ux.vbs(payload)

    def run(self, events, duration, seed=0, progress=None, pace=0.0, on_sample=None):
        """Reset the world (seed), play `events` [(t, kind, payload)] and sample until `duration` [s].

        progress: callable(dt [s]) told how much mission time each chunk advanced (tqdm.update).
        pace: 0 = as fast as possible; f > 0 keeps sim time <= f x wall time.
        on_sample: callable(t [s], nav_msgs/Odometry) called for every sample (e.g. to record a bag).
        Returns the simulated trajectory, rows of TRAJ_COLUMNS at mission times k * sample_period.
        """
        self.sim.pause()
        self.sim.reset(seed=seed)
        lead = self.lead_steps
        samples = list(
            range(
                lead,
                lead + int(math.floor(duration * self.rate / self.sample_steps + 1e-9)) * self.sample_steps + 1,
                self.sample_steps,
            )
        )
        timed = [(lead + round(t * self.rate), 1, kind, payload) for t, kind, payload in events if t <= duration + 1e-9]
        timed += [(s, 0, "sample", None) for s in samples]
        timed.sort(key=lambda e: (e[0], e[1]))  # at one step: sample the state, then apply commands
        traj, step, wall0 = [], 0, time.monotonic()
        for target, _, kind, payload in timed:
            if target > step:
                self.sim.step(target - step)
                if progress and target - max(step, lead) > 0:
                    progress((target - max(step, lead)) / self.rate)
                step = target
                if pace > 0:
                    ahead = (step / self.rate) / pace - (time.monotonic() - wall0)
                    if ahead > 0:
                        time.sleep(ahead)  # pacing to wall time (--pace), not a wait for a condition
            if kind == "sample":
                odom = self.ux.odom()  # the state at the last step call's time
                traj.append(pose_row((step - lead) / self.rate, odom.pose.pose))
                if on_sample:
                    on_sample(traj[-1][0], odom)
            else:
                self._apply(kind, payload, step / self.rate)
        return np.array(traj, dtype=float).reshape(-1, len(TRAJ_COLUMNS))


class CoreRunner(LockstepRunner):
    """LockstepRunner on the core back end (Simulation.launch(..., backend="core")): the motor commands are
    converted to thrusts in this process by the ESC driver's converter (unexmin.control.esc, its default tables, as
    the replay's in-process driver node has no parameters of its own) and applied from the next physics step, as
    the ROS runner's driver does; no ROS node runs."""

    def __init__(self, sim, robot="UX_1", motors_topic=ESC_COMMAND_TOPIC, sample_period=0.1, timeout=30.0):
        from unexmin.control.esc import converter_from_params

        self._timing(sim, robot, sample_period, timeout)
        self.converter = converter_from_params(lambda name, default: default)
        self.rejected = 0  # motor commands the converter refused (the ROS driver logs and skips them too)

    def close(self):
        """Nothing of its own to release (the Simulation closes the world)."""

    def _apply(self, kind, payload, t_sim):
        from unexmin.control.esc import EscTableError

        if kind != "motors":
            return super()._apply(kind, payload, t_sim)
        mode, values = payload
        try:
            thrusts, _ = self.converter.to_thrust(mode, list(values)[: self.ux.thruster_count])
        except EscTableError:
            self.rejected += 1
            return None
        self.ux.thrusts(thrusts)
        return None

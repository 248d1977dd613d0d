#!/usr/bin/env python3
"""Make the sample "real robot" bag of the mission replay (docs/replay.md), with our own simulator.

    source scripts/env.sh
    python worlds/tools/make_sample_bag.py                       # -> worlds/bags/ux1_tank_perturbed.bag
    python worlds/tools/make_sample_bag.py --nominal --out /tmp/nominal.bag --duration 12

What the bag is: the laboratory-tank world (worlds/tank.world) with UX_1 replaced by the
"prototype" robot of thesis 6.5 -- urdf/ux1_perturbed.urdf.xacro: 50 g of positive buoyancy and a
centre of gravity that makes it rest at 14 deg pitch and 8 deg roll. It is spawned at the tank's
UX_1 position already at that rest attitude (no swinging in from level). A fixed remote-control
mission (MISSION below: forward, yaw, left, pendulum, down, VBS; thesis 6.5 "X, Y, Z and Yaw remote
control") is turned into the real robot's ESC commands the way the robot's own software does it:
thesis allocation matrix (unexmin.control.allocation) then thrust -> rpm with the ESC table (unexmin.control.esc),
published at 10 Hz as ux1_msgs/MotorCommand. The simulator runs in lockstep through the same
runner as the replay (unexmin.replay.LockstepRunner: /ux1/command/motors -> ESC driver ->
thrusters), seed 0, and the robot's ground-truth odometry stands in for the real robot's
navigation.

Topics (bag time = simulation time [s]; MotorCommand header stamps = bag time):
    /ux1/command/motors  ux1_msgs/MotorCommand  10 Hz, mode RPM
    /UX_1/pendulum       std_msgs/Float64       [rad], when it changes
    /UX_1/vbs            std_msgs/Float64       [kg], when it changes
    /UX_1/odom           nav_msgs/Odometry      10 Hz, "navigation" (perturbed robot's ground truth)
  with --sensors, the robot's navigation sensors as the simulator publishes them (their noise:
  docs/sensors.md), for dead reckoning (python -m unexmin.identify --nav dead-reckoning):
    /UX_1/imu            sensor_msgs/Imu        every --imu-every-th sample of the 500 Hz IMU (default 10: 50 Hz)
    /UX_1/dvl_twist      geometry_msgs/TwistWithCovarianceStamped  8 Hz, DVL frame, with bottom lock
    /UX_1/pressure       sensor_msgs/FluidPressure                 10 Hz [Pa]

--nominal records the same mission with the shipped robot in the shipped world: its replay must
reproduce the recorded trajectory (test/pytest/test_replay.py).

--overrides FILE records it with any robot: ux1.urdf.xacro with FILE as its overrides (a xacro file
of properties, docs/robot_description.md), spawned at that robot's rest attitude (centre of gravity
below the centre of buoyancy). The identification's tests make bags of robots with known
parameters this way (docs/identification.md).
"""

import argparse
import math
import os
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
DEFAULT_OUT = REPO / "worlds" / "bags" / "ux1_tank_perturbed.bag"
PERTURBED_DESCRIPTION = REPO / "urdf" / "ux1_perturbed.urdf.xacro"
PERTURBED_ROLL_DEG, PERTURBED_PITCH_DEG = 8.0, 14.0  # must match urdf/ux1_perturbed.xacro
COMMAND_PERIOD = 0.1  # [s] MotorCommand period of the mission

# (start [s], end [s], wrench [X Y Z K M N] in force_moments units: the teleop's "speeds")
MISSION = (
    (2.0, 7.0, (6.0, 0, 0, 0, 0, 0)),  # I: forward
    (11.0, 14.0, (0, 0, 0, 0, 0, 1.5)),  # D: +yaw
    (14.0, 16.5, (0, 0, 0, 0, 0, -1.5)),  # A: brake the turn
    (21.0, 27.0, (0, 6.0, 0, 0, 0, 0)),  # J: left
    (31.0, 35.0, (0, 0, -3.0, 0, 0, 0)),  # S: down
)
PENDULUM = ((0.0, 0.0), (28.0, math.radians(10.0)), (36.0, 0.0))  # (t [s], angle [rad]), E/R
VBS = ((0.0, 0.0), (36.0, 0.02))  # (t [s], mass [kg]), Y/U
DURATION = 42.0


def mission_events(duration, vbs_trim=0.0, level_roll_pitch=None):
    """The mission as replay events [(t, kind, payload)] (kind motors | pendulum | vbs), t [s].
    vbs_trim [kg] is added to every VBS command (an operator's trim of a heavy or light robot).
    level_roll_pitch (roll, pitch) [rad]: the robot's rest attitude; the mission's forces (X, Y, Z) are
    then meant in the level frame (forward, left, up of the horizon at the robot's heading) and turned
    into the body frame, as an operator's attitude-compensated teleop would: a robot trimmed at 20 deg
    of pitch then runs level instead of diving along its tilted x axis (moments stay in the body frame)."""
    import numpy as np

    from unexmin.control.allocation import ThrusterAllocator
    from unexmin.control.esc import MODE_RPM, EscConverter
    from unexmin.geometry import rpy_matrix

    alloc, esc = ThrusterAllocator(), EscConverter()
    to_body = rpy_matrix((level_roll_pitch[0], level_roll_pitch[1], 0.0)).T if level_roll_pitch else None
    events = []
    for k in range(int(round(duration / COMMAND_PERIOD)) + 1):
        t = round(k * COMMAND_PERIOD, 9)
        wrench = next((w for a, b, w in MISSION if a <= t < b), (0.0,) * 6)
        if to_body is not None:
            wrench = (*(float(v) for v in to_body @ np.array(wrench[:3], float)), *wrench[3:])
        thrusts, _ = alloc.allocate(wrench)
        events.append((t, "motors", (MODE_RPM, tuple(float(v) for v in esc.to_command(MODE_RPM, thrusts)))))
    events += [(t, "pendulum", v) for t, v in PENDULUM if t <= duration]
    events += [(t, "vbs", v + vbs_trim) for t, v in VBS if t <= duration]
    return sorted(events, key=lambda e: e[0])


def perturbed_world_files(tmp, overrides=None, spawn_xyz=None):
    """A copy of tank.world spawning UX_1 at the perturbed rest attitude, and a launch file that starts
    it with urdf/ux1_perturbed.urdf.xacro as UX_1's description, or with ux1.urdf.xacro and
    `overrides` (spawned at that robot's rest attitude)."""
    from unexmin.worlds.spawn import world_launch_file

    if overrides:
        from unexmin.description import ROBOT_FILE, load
        from unexmin.identify.vehicle import rest_attitude

        return world_launch_file(
            tmp,
            "tank",
            "UX_1",
            rest_attitude(load(ROBOT_FILE, "UX_1", overrides)),
            overrides=overrides,
            spawn_xyz=spawn_xyz,
        )
    return world_launch_file(
        tmp,
        "tank",
        "UX_1",
        (math.radians(PERTURBED_ROLL_DEG), math.radians(PERTURBED_PITCH_DEG)),
        description=PERTURBED_DESCRIPTION,
    )


SENSOR_TOPICS = ("imu", "dvl_twist", "pressure")  # under /UX_1/, recorded with --sensors


def record(
    out,
    nominal=False,
    duration=DURATION,
    seed=0,
    overrides=None,
    vbs_trim=0.0,
    spawn_xyz=None,
    sensors=False,
    imu_every=10,
    level=False,
):
    """Run the mission and write the bag `out` (the robot: perturbed, nominal, or ux1.urdf.xacro with
    the xacro file `overrides`); with `sensors`, the IMU (every imu_every-th sample), DVL twist and
    pressure messages too; with `level` (and `overrides`), the mission's forces in the level frame of
    the robot's rest attitude (mission_events). Returns the number of messages written."""
    import rospy
    from std_msgs.msg import Float64
    from ux1_msgs.msg import MotorCommand

    from unexmin.bag import BagWriter
    from unexmin.replay import LockstepRunner
    from unexmin.scripting.simulation import Simulation
    from unexmin.topics import ESC_COMMAND_TOPIC

    tmp = tempfile.mkdtemp(prefix="unexmin_bag_")
    launch_file = None if nominal else perturbed_world_files(tmp, overrides, spawn_xyz)
    count = 0
    with (
        Simulation.launch(
            "tank", robots=1, seed=seed, log_dir=os.path.join(tmp, "log"), launch_file=launch_file, timeout=60.0
        ) as sim,
        BagWriter(out, callerid="/make_sample_bag") as bag,
    ):
        runner = LockstepRunner(sim, "UX_1", ESC_COMMAND_TOPIC, sample_period=0.1)
        ux = sim.robot("UX_1", streams="none")
        collectors = [ux.collect(topic) for topic in SENSOR_TOPICS] if sensors else []
        lead = runner.lead_steps / runner.rate  # mission time 0 is sim time `lead`
        level_rp = None
        if level:
            from unexmin.description import ROBOT_FILE, load
            from unexmin.identify.vehicle import rest_attitude

            level_rp = rest_attitude(load(ROBOT_FILE, "UX_1", overrides))
        events = mission_events(duration, vbs_trim, level_rp)
        for t, kind, payload in events:
            if kind == "motors":
                msg = MotorCommand()
                msg.header.stamp = rospy.Time.from_sec(t + lead)
                msg.mode, msg.values = payload[0], list(payload[1])
                bag.write(ESC_COMMAND_TOPIC, msg, t + lead)
            else:
                bag.write(f"/UX_1/{kind}", Float64(payload), t + lead)
            count += 1

        imu_seen = 0

        def on_sample(t, odom):
            # the sensors' messages of the steps since the last sample (in time order), then the odometry
            nonlocal count, imu_seen
            for topic, collector in zip(SENSOR_TOPICS, collectors):
                msgs = collector.messages
                collector.clear()
                for m in msgs:
                    stamp = m.header.stamp.to_sec()
                    if stamp < lead - 1e-9:  # mission time 0 is sim time `lead`
                        continue
                    if topic == "imu":
                        imu_seen += 1
                        if (imu_seen - 1) % imu_every:
                            continue
                    bag.write(f"/UX_1/{topic}", m, stamp)
                    count += 1
            bag.write("/UX_1/odom", odom, odom.header.stamp.to_sec())
            count += 1

        traj = runner.run(events, duration, seed=seed, on_sample=on_sample)
        runner.close()
        for collector in collectors:
            collector.stop()
    print(
        f"{out}: {count} messages, {duration:.0f} s; robot went from "
        f"({traj[0, 1]:.2f}, {traj[0, 2]:.2f}, {traj[0, 3]:.2f}) to ({traj[-1, 1]:.2f}, {traj[-1, 2]:.2f}, "
        f"{traj[-1, 3]:.2f}) m, roll/pitch at start "
        f"{math.degrees(traj[0, 4]):.1f}/{math.degrees(traj[0, 5]):.1f} deg"
    )
    return count


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=str(DEFAULT_OUT), help=f"bag to write (default {DEFAULT_OUT})")
    ap.add_argument("--nominal", action="store_true", help="the shipped robot in the shipped world")
    ap.add_argument("--duration", type=float, default=DURATION, help=f"[s] mission length (default {DURATION})")
    ap.add_argument("--seed", type=int, default=0, help="simulator seed (default 0)")
    ap.add_argument(
        "--overrides",
        help="xacro overrides file: record with ux1.urdf.xacro and these properties "
        "instead of the thesis prototype (spawned at its rest attitude)",
    )
    ap.add_argument(
        "--vbs-trim",
        type=float,
        default=0.0,
        help="[kg] added to every VBS command: trims a robot "
        "of other buoyancy to near neutral so that it stays in mid-water (default 0)",
    )
    ap.add_argument(
        "--spawn-xyz",
        type=float,
        nargs=3,
        metavar=("X", "Y", "Z"),
        help="[m] spawn position of UX_1 with --overrides (default the world's: -1.7 -0.85 -1)",
    )
    ap.add_argument(
        "--sensors",
        action="store_true",
        help="record the IMU, DVL and pressure sensors too "
        "(/UX_1/imu, /UX_1/dvl_twist, /UX_1/pressure), for dead reckoning",
    )
    ap.add_argument(
        "--imu-every",
        type=int,
        default=10,
        help="with --sensors: keep every n-th IMU sample of the "
        "500 Hz stream (default 10: 50 Hz, which keeps the sample bag under 2 MB)",
    )
    ap.add_argument(
        "--level",
        action="store_true",
        help="with --overrides: the mission's forces in the level "
        "frame of the robot's rest attitude (attitude-compensated teleop), so a tilted robot runs level",
    )
    args = ap.parse_args(argv)
    if args.level and not args.overrides:
        ap.error("--level goes with --overrides")
    if args.imu_every < 1:
        ap.error(f"--imu-every {args.imu_every}: expected a whole number >= 1")
    if args.spawn_xyz is not None and not args.overrides:
        ap.error("--spawn-xyz goes with --overrides")
    if args.overrides and args.nominal:
        ap.error("--overrides and --nominal exclude each other")
    if args.overrides and not Path(args.overrides).is_file():
        ap.error(f"--overrides {args.overrides}: no such file")
    if not math.isfinite(args.vbs_trim):
        ap.error(f"--vbs-trim {args.vbs_trim}: expected a finite mass [kg]")
    record(
        args.out,
        args.nominal,
        args.duration,
        args.seed,
        args.overrides,
        args.vbs_trim,
        args.spawn_xyz,
        args.sensors,
        args.imu_every,
        args.level,
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())

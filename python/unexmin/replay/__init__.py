"""Rosbag mission replay (thesis 6.5): a real robot's motor commands, played into the simulator.

    rosrun unexmin replay_mission worlds/bags/ux1_tank_perturbed.bag --out /tmp/replay
    python -m unexmin.replay BAG --out DIR [--world tank] [--seed 0] [--nav-topic /UX_1/odom] ...

1. bag_io: the bag is read completely first (unexmin.bag: rosbags, no roscore; message types are
   registered from the definitions stored in the bag) into a Mission: /ux1/command/motors
   (ux1_msgs/MotorCommand), the robot's pendulum and VBS commands (std_msgs/Float64) if present, and
   its navigation if present (nav_msgs/Odometry, geometry_msgs/PoseStamped or
   PoseWithCovarianceStamped). A truncated or corrupt bag stops here with one error and exit
   status 2, before any simulator is started.
2. runner: a headless lockstep world is launched (Simulation.launch, its own master). The motor
   commands go through the simulated ESC driver (unexmin.control.esc_driver_node, run in this process) on
   /ux1/command/motors, exactly as a live robot's would; pendulum and VBS commands go to the robot's
   topics. Every command is applied at its bag time (mission time 0 = the first command) rounded to
   a physics step, and the simulator is advanced with /sim/step between commands, so the replay is
   deterministic and runs as fast as the machine allows (or paced with --pace).
3. metrics: the simulated ground-truth pose is sampled every --sample-period seconds and compared
   with the bag's navigation: position error over time, final and RMS error, yaw error. By default
   both trajectories are first expressed in their own start frame (origin at the start position, x
   along the start heading), since the simulated robot starts at the world's spawn pose and the real
   one wherever it was.
4. plots: XY, XZ, YZ, yaw and error over time (PNG) and trajectory.csv; cli writes them and
   report.json to --out.

Parameters and report fields: docs/replay.md. Sample bag: worlds/bags/ (worlds/tools/make_sample_bag.py).
Importing this package needs neither ROS nor rosbags; they are imported when used.
"""

from unexmin.replay.bag_io import MOTORS_TOPIC, Mission, read_bag
from unexmin.replay.cli import main, replay, summary
from unexmin.replay.errors import ReplayError
from unexmin.replay.metrics import TRAJ_COLUMNS, compare, path_length, pose_row, to_start_frame
from unexmin.replay.plots import write_csv, write_plots
from unexmin.replay.runner import LockstepRunner

__all__ = [
    "MOTORS_TOPIC",
    "Mission",
    "read_bag",
    "main",
    "replay",
    "summary",
    "ReplayError",
    "TRAJ_COLUMNS",
    "compare",
    "path_length",
    "pose_row",
    "to_start_frame",
    "write_csv",
    "write_plots",
    "LockstepRunner",
]

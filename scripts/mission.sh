#!/usr/bin/env bash
# The main job: sets the machine up, then runs a headless lockstep tank mission that records a bag
# of odometry and thrusts and reports where UX_1 went, then replays a sample real-robot bag
# (rosbag mission replay) and writes its error report and plots. Outputs in $UNEXMIN_OUT (default
# ./mission_output beside the repository's README).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$repo/scripts/setup.sh"
# shellcheck disable=SC1091
source "$repo/scripts/env.sh"
out=${UNEXMIN_OUT:-$repo/mission_output}
export ROS_HOME=${ROS_HOME:-$out/ros_home}
python -m unexmin.mission --out "$out" "$@"
# Hardware-in-the-loop replay of a shipped "real robot" bag (docs/replay.md): report and plots.
python -m unexmin.replay "$repo/worlds/bags/ux1_tank_perturbed.bag" --out "$out/replay" --quiet

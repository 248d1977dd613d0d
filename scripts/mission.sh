#!/usr/bin/env bash
# The main job: sets the machine up, then runs a headless lockstep tank mission that records a bag
# of odometry and thrusts and reports where UX_1 went. Outputs in $UNEXMIN_OUT (default
# ./mission_output beside the repository's README).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$repo/scripts/setup.sh"
# shellcheck disable=SC1091
source "$repo/scripts/env.sh"
out=${UNEXMIN_OUT:-$repo/mission_output}
export ROS_HOME=${ROS_HOME:-$out/ros_home}
exec python -m unexmin.mission --out "$out" "$@"

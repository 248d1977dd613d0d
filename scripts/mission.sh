#!/usr/bin/env bash
# The main job: sets the machine up, then runs a headless lockstep mapping survey of the flooded mine
# (UX_1 spirals down the entry shaft, then flies the first level's gallery out and back and its side tunnels,
# turning, the mapper on; docs/mapping.md) and scores the map against the mine's mesh. Outputs in
# $UNEXMIN_OUT (default ./mission_output beside the repository's README): mine_mission.bag, mine_map.bt,
# map_quality.json/.png, mission_map.png, coverage.png, summary.json, snapshots/.
#
#   bash scripts/mission.sh [--tank] [--replay] [-- mine mission options, e.g. --visibility none --gallery 60]
#     --tank    also run the tank mission (tank/: bag of odometry and thrusts, trajectory, summary)
#     --replay  also replay the shipped "real robot" bag (replay/: error report and plots; docs/replay.md)
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
tank=0 replay=0 args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --tank) tank=1 ;;
    --replay) replay=1 ;;
    --) shift; args+=("$@"); break ;;
    *) args+=("$1") ;;
  esac
  shift
done
bash "$repo/scripts/setup.sh"
# shellcheck disable=SC1091
source "$repo/scripts/env.sh"
out=${UNEXMIN_OUT:-$repo/mission_output}
export ROS_HOME=${ROS_HOME:-$out/ros_home}
python -m unexmin.missions.mine --out "$out" "${args[@]+"${args[@]}"}"
if [ "$tank" = 1 ]; then
  python -m unexmin.missions.tank --out "$out/tank"
fi
if [ "$replay" = 1 ]; then
  # Hardware-in-the-loop replay of a shipped "real robot" bag (docs/replay.md): report and plots.
  python -m unexmin.replay "$repo/worlds/bags/ux1_tank_perturbed.bag" --out "$out/replay" --quiet
fi

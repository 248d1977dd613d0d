# Source me: the built workspace and the project's Python venv (xacro, rosbags, pytest) on PATH.
#   source scripts/env.sh
_unexmin_repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export UNEXMIN_REPO=$_unexmin_repo
export UNEXMIN_WS=${UNEXMIN_WS:-$(dirname "$_unexmin_repo")/$(basename "$_unexmin_repo")_ws}
export UNEXMIN_VENV=${UNEXMIN_VENV:-$UNEXMIN_WS/venv}
# ROS's setup files read unset variables: relax `set -u` while sourcing them.
case $- in *u*) _unexmin_u=1; set +u ;; *) _unexmin_u= ;; esac
_unexmin_master=${ROS_MASTER_URI:-}  # yours, if set (ROS's setup files set http://localhost:11311 otherwise)
# shellcheck disable=SC1091
source "$UNEXMIN_WS/devel/setup.bash"
[ -n "$_unexmin_u" ] && set -u
unset _unexmin_u
export PATH="$UNEXMIN_VENV/bin:$PATH"
unset _unexmin_repo
# Safe by default (docs/reliability.md): the master and every node listen on and advertise 127.0.0.1, unless
# you set ROS_IP or ROS_HOSTNAME (e.g. export ROS_IP=<this machine's address> before sourcing, to reach a real
# robot or another machine: they then listen on that address only) or ROS_MASTER_URI yourself. roslaunch,
# roscore, rostest and rosrun come from scripts/bind_shim/: the real ones with the bind shim preloaded, which
# keeps every process they start on that address.
if [ -z "${ROS_IP:-}" ] && [ -z "${ROS_HOSTNAME:-}" ]; then
  export ROS_IP=127.0.0.1
fi
export ROS_MASTER_URI=${_unexmin_master:-http://${ROS_IP:-$ROS_HOSTNAME}:11311}
unset _unexmin_master
case ":$PATH:" in
  *":$UNEXMIN_REPO/scripts/bind_shim:"*) ;;
  *) export PATH="$UNEXMIN_REPO/scripts/bind_shim:$PATH" ;;
esac

# Source me: the built workspace and the project's Python venv (xacro, rosbags, pytest) on PATH.
#   source scripts/env.sh
_unexmin_repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export UNEXMIN_REPO=$_unexmin_repo
export UNEXMIN_WS=${UNEXMIN_WS:-$(dirname "$_unexmin_repo")/$(basename "$_unexmin_repo")_ws}
export UNEXMIN_VENV=${UNEXMIN_VENV:-$UNEXMIN_WS/venv}
# ROS's setup files read unset variables: relax `set -u` while sourcing them.
case $- in *u*) _unexmin_u=1; set +u ;; *) _unexmin_u= ;; esac
# shellcheck disable=SC1091
source "$UNEXMIN_WS/devel/setup.bash"
[ -n "$_unexmin_u" ] && set -u
unset _unexmin_u
export PATH="$UNEXMIN_VENV/bin:$PATH"
unset _unexmin_repo

# Source me: the built workspace and the project's Python venv (xacro, rosbags, pytest) on PATH.
#   source scripts/env.sh
_unexmin_repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export UNEXMIN_REPO=$_unexmin_repo
export UNEXMIN_WS=${UNEXMIN_WS:-$(dirname "$_unexmin_repo")/$(basename "$_unexmin_repo")_ws}
export UNEXMIN_VENV=${UNEXMIN_VENV:-$UNEXMIN_WS/venv}
# shellcheck disable=SC1091
source "$UNEXMIN_WS/devel/setup.bash"
export PATH="$UNEXMIN_VENV/bin:$PATH"
unset _unexmin_repo

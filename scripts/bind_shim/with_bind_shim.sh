#!/usr/bin/env bash
# roslaunch, roscore, rostest and rosrun (the links in this folder, first on PATH after `source scripts/env.sh`):
# the real command, found further on PATH, with libunexmin_bind_shim.so first in LD_PRELOAD. The master, rosout and
# every node it starts inherit it and listen on ROS_IP only (docs/reliability.md "Safe by default"); other
# programs of the shell are left alone.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd -P)
name=$(basename "$0")
real=
IFS=: read -ra folders <<<"$PATH"
for folder in "${folders[@]}"; do
  [ -n "$folder" ] && [ "$(cd "$folder" 2>/dev/null && pwd -P)" != "$here" ] && [ -x "$folder/$name" ] \
    && { real=$folder/$name; break; }
done
[ -n "$real" ] || { echo "$name: not found on PATH (outside $here)" >&2; exit 127; }
shim=
IFS=: read -ra folders <<<"${LD_LIBRARY_PATH:-}"
for folder in "${folders[@]}"; do
  [ -n "$folder" ] && [ -f "$folder/libunexmin_bind_shim.so" ] && { shim=$folder/libunexmin_bind_shim.so; break; }
done
if [ -z "$shim" ]; then
  echo "$name: libunexmin_bind_shim.so is in no folder of LD_LIBRARY_PATH (build the workspace and source" \
    "scripts/env.sh): not starting ROS processes that would listen on every interface" >&2
  exit 1
fi
case " ${LD_PRELOAD:-} " in
  *" $shim "*) ;;
  *) export LD_PRELOAD="$shim${LD_PRELOAD:+ $LD_PRELOAD}" ;;
esac
exec "$real" "$@"

#!/usr/bin/env bash
# Add this repository to a catkin workspace: link the package (the repository root) and each message
# package in message_packages/ into <ws>/src. catkin does not look for packages inside a package, so a plain
# `git clone` into <ws>/src finds `unexmin` but not ux1_msgs, dvl_nortek or kvh_1775.
#
#   bash scripts/add_to_workspace.sh [--quiet] <ws>     # --quiet: print only the changes it makes
#
# Creates <ws>/src if needed. Idempotent. Links in <ws>/src that point into this repository but name
# no package of it any more (a renamed or removed msg package) are removed; other entries are left
# alone. Stops, changing nothing, when <ws>/src holds a real folder or file under one of the names
# (another copy of the package), or when <ws> lies inside the repository (a symlink loop).
# If the repository itself was cloned into <ws>/src, only the msg packages are linked beside it.
# scripts/setup.sh makes its own workspace with this script.
set -euo pipefail

quiet=0
if [ "${1:-}" = "--quiet" ]; then quiet=1; shift; fi
if [ $# -ne 1 ] || [ -z "$1" ]; then
  echo "usage: bash scripts/add_to_workspace.sh [--quiet] <catkin workspace folder>" >&2
  exit 2
fi

say() { echo "[add_to_workspace] $*"; }
die() { echo "[add_to_workspace] error: $*" >&2; exit 1; }

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)
ws=$(realpath -m "$1")
src=$ws/src
case "$ws/" in
  "$repo/"*) die "the workspace $ws lies inside the repository $repo: roslaunch and rosrun would find every file several times. Use a folder outside it (e.g. $(dirname "$repo")/catkin_ws)." ;;
esac
mkdir -p "$src"

# The packages to link: name -> folder.
names=() targets=()
case "$repo/" in
  "$src/"*) say "the repository is already inside $src: linking only its msg packages" ;;
  *) names+=(unexmin); targets+=("$repo") ;;
esac
for m in "$repo"/message_packages/*/; do
  [ -f "$m/package.xml" ] || continue
  names+=("$(basename "$m")"); targets+=("${m%/}")
done

# Check everything before changing anything.
for i in "${!names[@]}"; do
  link=$src/${names[$i]}
  if [ -e "$link" ] && [ ! -L "$link" ]; then
    die "$link exists and is not a link (another copy of the package '${names[$i]}'?). Move it out of $src, or use another workspace."
  fi
done

for i in "${!names[@]}"; do
  link=$src/${names[$i]} target=${targets[$i]}
  if [ -L "$link" ] && [ "$(readlink "$link")" = "$target" ]; then
    continue
  fi
  [ -L "$link" ] && say "replacing $link -> $(readlink "$link")"
  ln -sfn "$target" "$link"
  say "linked $link -> $target"
done

# Links this script made earlier (they point into this repository) that name no package now.
for link in "$src"/*; do
  [ -L "$link" ] || continue
  case "$(readlink "$link")" in
    "$repo"|"$repo/"*) ;;
    *) continue ;;
  esac
  name=$(basename "$link")
  keep=0
  for n in "${names[@]}"; do [ "$n" = "$name" ] && keep=1; done
  if [ "$keep" -eq 0 ]; then
    rm -f "$link"
    say "removed stale link $link"
  fi
done

[ "$quiet" -eq 1 ] && exit 0
say "$src holds: ${names[*]}. Next, build and use the workspace:"
say "  cd $ws && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release -j2"
say "  source $ws/devel/setup.bash    # roslaunch also needs xacro 1.13.3 (scripts/setup.sh's venv) on PATH"
say "or let scripts/setup.sh install the Debian packages and the venv, then build this workspace:"
say "  UNEXMIN_WS=$ws bash $repo/scripts/setup.sh && UNEXMIN_WS=$ws source $repo/scripts/env.sh"

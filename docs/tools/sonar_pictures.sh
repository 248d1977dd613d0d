#!/usr/bin/env bash
# The sonar pictures of docs/sonars.md: expands the shipped UX-1 and runs the catkin-built sonar_pictures
# (docs/tools/sonar_pictures.cpp) in worlds/tank.world, writing docs/images/sonar/*.png.
#   source scripts/env.sh && bash docs/tools/sonar_pictures.sh
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out="$repo/docs/images/sonar"
mkdir -p "$out"
urdf=$(mktemp --suffix=.urdf)
trap 'rm -f "$urdf"' EXIT
xacro "$repo/urdf/ux1.urdf.xacro" name:=UX_1 >"$urdf"
"$UNEXMIN_WS/devel/lib/unexmin/sonar_pictures" "$urdf" "$repo/worlds/tank.world" "$out"

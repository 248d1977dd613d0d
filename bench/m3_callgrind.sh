#!/usr/bin/env bash
# Instructions per M3 ping (callgrind), independent of the machine's load: bench/sensors_core_cost of a workspace
# (the UX-1 in worlds/tank.world, every sensor, the caster on one thread) under valgrind, collecting only inside
# M3Sensor::sample (its ray casts included). Three scenes:
#   level   the shipped UX-1 and tank (the M3 level, 1 m deep: no ray reaches the surface before a wall)
#   tilted  the M3 pitched 5 deg up, the robot 0.27 m deep (the M3 0.4 m): rays reach the surface (its echo)
#   ghost   the same with surface_backscatter -100 dB: the surface echo is no detection, the reflected rays are cast
# A workspace built before the M3 multipath knows no surface_backscatter: its ghost line says so.
#   source scripts/env.sh && bash bench/m3_callgrind.sh [workspace, default $UNEXMIN_WS] [physics steps, default 800]
#                                                        [directory of other libunexmin_sensors/_ros.so to load first]
# (the third: libraries built from another commit, e.g. the base, run by this workspace's sensors_core_cost).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
ws=${1:-$UNEXMIN_WS}
steps=${2:-800}
libs=${3:-$ws/devel/lib}
exe="$ws/devel/lib/unexmin/sensors_core_cost"
pings=$((steps * 2 * 40 / 1000))  # sensors_core_cost steps 2 ms; the M3 pings at 40 Hz
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
xacro "$repo/urdf/ux1.urdf.xacro" name:=UX_1 >"$tmp/level.urdf"
# The M3 joint's origin follows its child line: pitch it 5 deg up (rpy 0 -5 deg 0).
python3 - "$tmp" <<'EOF'
import re, sys
tmp = sys.argv[1]
urdf = open(f"{tmp}/level.urdf").read()
joint = re.search(r'<child link="UX_1/m3_link"/>\s*<origin rpy="0 0 0"', urdf)
if not joint:
    sys.exit("m3_link joint with rpy 0 0 0 not found in the expanded UX-1")
tilted = urdf[:joint.start()] + joint.group(0).replace('rpy="0 0 0"', 'rpy="0 -0.0872664626 0"') + urdf[joint.end():]
open(f"{tmp}/tilted.urdf", "w").write(tilted)
ghost = tilted.replace('<sensor link="UX_1/m3_link" name="m3" rate="40.0" type="m3">',
                       '<sensor link="UX_1/m3_link" name="m3" rate="40.0" type="m3">\n'
                       '      <param name="surface_backscatter" value="-100"/>', 1)
if ghost == tilted:
    sys.exit("the M3's <sensor> element not found in the expanded UX-1")
open(f"{tmp}/ghost.urdf", "w").write(ghost)
EOF
ln -s "$repo/worlds/meshes" "$tmp/meshes"
cp "$repo/worlds/tank.world" "$tmp/tank.world"
sed 's/xyz: \[-1.7, -0.85, -1.0\]/xyz: [-1.7, -0.85, -0.273]/' "$repo/worlds/tank.world" >"$tmp/shallow.world"
grep -q -- "-0.273" "$tmp/shallow.world" || { echo "UX_1's spawn in tank.world moved: update this script" >&2; exit 1; }
echo "workspace $ws, libraries $libs, $steps steps: $pings M3 pings per scene"
for scene in level tilted ghost; do
  world="$tmp/shallow.world"
  [ "$scene" = level ] && world="$tmp/tank.world"
  if ! LD_LIBRARY_PATH="$libs:$ws/devel/lib:${LD_LIBRARY_PATH:-}" valgrind --tool=callgrind --callgrind-out-file="$tmp/$scene.out" \
      --toggle-collect='unexmin::sensors::sonar::M3Sensor::sample*' "$exe" "$tmp/$scene.urdf" "$world" "$steps" 1 1 >"$tmp/$scene.log" 2>&1; then
    echo "$scene: does not run ($(grep -m1 -o "parameter '[a-z_]*'[^.]*" "$tmp/$scene.log" || tail -1 "$tmp/$scene.log"))"
    continue
  fi
  ir=$(grep -o 'Collected : [0-9]*' "$tmp/$scene.log" | grep -o '[0-9]*$')
  echo "$scene: $ir instructions in M3Sensor::sample, $((ir / pings)) per ping"
done

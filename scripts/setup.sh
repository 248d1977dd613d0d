#!/usr/bin/env bash
# One-stop set-up for a fresh Debian 12 machine: Debian's ROS 1 and C++ libraries, a Python venv
# (from /usr/bin/python3, with system site packages so rospy is visible) and the catkin workspace
# built outside the repository. Idempotent: a second run on a set-up machine takes seconds.
#
# Environment:
#   UNEXMIN_WS    catkin workspace folder   (default: <repo>/../<repo-name>_ws)
#   UNEXMIN_VENV  Python venv folder        (default: $UNEXMIN_WS/venv)
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
ws=${UNEXMIN_WS:-$(dirname "$repo")/$(basename "$repo")_ws}
venv=${UNEXMIN_VENV:-$ws/venv}

apt_packages=(
  # ROS 1 from Debian
  ros-core-dev rosbash python3-rostest python3-rosbag ros-robot-state-publisher
  libtf2-ros-dev python3-tf2-ros libsensor-msgs-dev libgeometry-msgs-dev libnav-msgs-dev
  libvisualization-msgs-dev python3-sensor-msgs python3-geometry-msgs python3-nav-msgs python3-visualization-msgs
  libstd-srvs-dev python3-std-srvs librosbag-storage-dev
  # C++ core
  libbullet-dev libeigen3-dev liboctomap-dev libembree-dev libassimp-dev libyaml-cpp-dev libtinyxml2-dev
  # KDL: test_joint_transform checks the mounts against robot_state_publisher's arithmetic (urdfdom + KDL)
  liborocos-kdl-dev
  # image textures of world meshes (sim/texture_image.h)
  libpng-dev libjpeg-dev
  # OctoMap's bt2vrml and binvox2bt (map_quality, its tests); urdfdom (test_urdf.py checks the description with it)
  octomap-tools liburdfdom-dev
  # tests, viewer (rviz under Xvfb, screenshots with ImageMagick's import, teleop's test in tmux), Python
  libgtest-dev googletest rviz xvfb imagemagick tmux python3-venv python3-numpy python3-yaml
  build-essential cmake
  # compiles through a cache in the workspace (below): test/pytest/test_own_workspace.py's fresh workspace reuses it
  ccache
  # test/pytest/test_loopback.py: ss and ip netns (not in a minimal Debian 12 image)
  iproute2
  # teleop:=keyboard opens the keyboard teleop in a terminal window of its own (launch/teleop.launch)
  xterm
  # unexmin.core, the engine in-process from Python (docs/python_api.md)
  pybind11-dev
  # ROS's camera calibrator and rectification judge the cameras (test/pytest/test_camera_calibration.py,
  # test/pytest/test_camera_rectify.py; docs/vision.md "Tests")
  ros-camera-calibration python3-camera-calibration python3-cv-bridge ros-image-proc python3-image-geometry
)
pip_packages=(rosbags==0.11.9 xacro==1.13.3 pytest==8.3.4 pytest-xdist==3.6.1 pytest-timeout==2.4.0 numpy==1.26.4 matplotlib==3.9.2
  trimesh==4.5.3 tqdm==4.67.1 manifold3d==3.5.4 rtree==1.4.1 scipy==1.15.3
  open3d-cpu==0.20.0 laspy==2.5.4 lazrs==0.6.2)
# OpenCV judges the cameras' images (test/pytest/test_camera_orb.py, docs/vision.md "Tests")
pip_packages+=(opencv-python-headless==4.10.0.84)
# batch missions on Dask (docs/batch.md): scheduler/workers, results table (Parquet), dashboard
pip_packages+=("dask[distributed]==2025.1.0" distributed==2025.1.0 pandas==2.2.3 pyarrow==18.1.0 bokeh==3.6.2)
# the C++ formatter the test command checks against (.clang-format, test/pytest/test_cpp_format.py)
pip_packages+=(clang-format==19.1.7)
# Python lint and format (ruff.toml; test/pytest/test_style.py)
pip_packages+=(ruff==0.8.6)
# Gymnasium environments of the UX-1's jobs (python/unexmin/gym, docs/gym.md)
pip_packages+=(gymnasium==1.2.0)
# quadric decimation of the scan worlds' tiles (python/unexmin/worlds/from_scan/surface.py)
pip_packages+=(fast-simplification==0.2.0)

missing=()
for p in "${apt_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "[setup] installing ${#missing[@]} Debian packages: ${missing[*]}"
  sudo_cmd=""; [ "$(id -u)" -ne 0 ] && sudo_cmd=sudo
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

stamp="$venv/.unexmin-pip-$(printf '%s\n' "${pip_packages[@]}" | md5sum | cut -c1-12)"
if [ ! -f "$stamp" ]; then
  echo "[setup] creating venv $venv"
  [ -x "$venv/bin/python" ] || /usr/bin/python3 -m venv --system-site-packages "$venv"
  "$venv/bin/pip" install -q --disable-pip-version-check "${pip_packages[@]}" 2>&1 | { grep -v "is ignored: it is neither" || true; }
  rm -f "$venv"/.unexmin-pip-*; touch "$stamp"
fi

# The flooded mine's meshes (docs/mine_world.md): generated here (about 15 s), not committed; skipped
# when worlds/meshes/mine/ already holds the output of this seed and generator version.
PYTHONPATH="$repo/python" "$venv/bin/python" -m unexmin.worlds.generator --seed 7 --quiet \
  --out "$repo/worlds/meshes/mine" | sed 's/^/[setup] /'

# The same way a user adds the package to their own workspace (README, "Your own workspace").
bash "$repo/scripts/add_to_workspace.sh" --quiet "$ws"

# Every compile goes through ccache, its cache in <ws>/ccache. Paths under the workspace are hashed relative to it
# (CCACHE_BASEDIR), so another workspace of this repository (test_own_workspace.py's fresh one, given this cache)
# takes the object of each compile whose source, headers and flags are byte-identical instead of compiling it again.
ws_real=$(realpath "$ws")
launcher="/usr/bin/env;CCACHE_DIR=$ws_real/ccache;CCACHE_BASEDIR=$ws_real;CCACHE_MAXSIZE=1G;ccache"
echo "[setup] building workspace $ws"
(
  set +u
  source /opt/ros/*/setup.bash 2>/dev/null || true
  cd "$ws"
  export PATH="$venv/bin:$PATH"
  catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_C_COMPILER_LAUNCHER="$launcher" -DCMAKE_CXX_COMPILER_LAUNCHER="$launcher" -j2 >"$ws/build.log" 2>&1 \
    || { tail -n 60 "$ws/build.log"; echo "[setup] build failed, full log: $ws/build.log" >&2; exit 1; }
)
echo "[setup] ready: source $repo/scripts/env.sh"

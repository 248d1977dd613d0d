"""Layering of the C++ code (CMakeLists.txt, docs/adding_a_sensor.md): one library per folder of cpp/unexmin,
in the order core -> mapping (needs only core and OctoMap) -> hydro -> sim -> raycast -> sensors (-> its
sub-folders sonar, vision) -> ros_layer. No folder includes a folder above it (the sub-folders of sensors stand
side by side: neither includes the other), no core folder includes a ROS header or links a ROS library, and
every project header is included with its package prefix (<unexmin/<folder>/...>) so nothing collides with
roscpp's <ros/...>."""

import re
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
CPP = REPO / "cpp" / "unexmin"
LAYERS = ["core", "mapping", "hydro", "sim", "raycast", "sensors", "sensors/sonar", "sensors/vision", "ros_layer"]
SIBLINGS = {"sensors/sonar", "sensors/vision"}  # same rank
# First path components of headers that come from ROS (roscpp, tf2, message and service packages).
ROS_ROOTS = {
    "ros",
    "roscpp",
    "rosbag",
    "rosconsole",
    "tf",
    "tf2",
    "tf2_ros",
    "tf2_eigen",
    "image_transport",
    "kvh_1775",
    "ux1_msgs",
    "dvl_nortek",
    "std_srvs",
    "pluginlib",
    "nodelet",
    "urdf",
}
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)


def folder_of(path):
    """The layer folder of a file under cpp/unexmin (the deepest entry of LAYERS that contains it)."""
    rel = path.relative_to(CPP).parent.as_posix()
    matches = [layer for layer in LAYERS if rel == layer or rel.startswith(layer + "/")]
    assert matches, f"{path.relative_to(REPO)} is in no library folder (expected one of {LAYERS})"
    return max(matches, key=len)


def is_ros_header(header):
    root = header.split("/")[0]
    generated = re.match(r"unexmin/[A-Z]\w*\.h$", header)  # unexmin's own messages and services
    return root in ROS_ROOTS or root.endswith("_msgs") or bool(generated)


def sources():
    files = sorted(p for p in CPP.rglob("*") if p.suffix in (".h", ".cpp"))
    assert len(files) > 40, "cpp/unexmin looks empty: the layout test would check nothing"
    return files


def includes(path):
    return INCLUDE.findall(path.read_text())


def test_every_folder_is_a_known_library():
    folders = {folder_of(p) for p in sources()}
    assert folders == set(LAYERS), f"library folders {sorted(folders)}, expected {LAYERS}"


def test_project_headers_are_included_with_the_package_prefix_and_exist():
    bad = []
    for path in sources():
        for kind, header in includes(path):
            if kind == '"':
                bad.append(f'{path.relative_to(REPO)}: #include "{header}" (use <unexmin/...>)')
            elif header.startswith("unexmin/") and not is_ros_header(header) and not (REPO / "cpp" / header).exists():
                bad.append(f"{path.relative_to(REPO)}: <{header}> does not exist")
    assert not bad, "\n".join(bad)


def test_no_folder_includes_a_folder_above_it():
    bad = []
    for path in sources():
        own = LAYERS.index(folder_of(path))
        for _, header in includes(path):
            if not header.startswith("unexmin/") or is_ros_header(header):
                continue
            other = folder_of(REPO / "cpp" / header)
            siblings = other != LAYERS[own] and {other, LAYERS[own]} <= SIBLINGS
            if LAYERS.index(other) > own or siblings:
                bad.append(f"{path.relative_to(REPO)} ({LAYERS[own]}) includes <{header}> ({other})")
    assert not bad, "\n".join(bad)


def test_the_core_includes_no_ros_header():
    bad = [
        f"{p.relative_to(REPO)}: <{h}>"
        for p in sources()
        if folder_of(p) != "ros_layer"
        for _, h in includes(p)
        if is_ros_header(h)
    ]
    assert not bad, "ROS headers in the ROS-free core:\n" + "\n".join(bad)


def libraries():
    """{folder: [linked libraries]} from the unexmin_library(...) calls of CMakeLists.txt."""
    text = (REPO / "CMakeLists.txt").read_text()
    calls = re.findall(r"^unexmin_library\(([^)]*)\)", text, re.M)
    return {c.split()[0]: c.split()[1:] for c in calls}


def test_each_library_links_only_libraries_below_it_and_only_ros_links_ros():
    libs = libraries()
    assert set(libs) == set(LAYERS) - SIBLINGS, f"libraries {sorted(libs)}"
    for folder, deps in libs.items():
        for dep in deps:
            m = re.match(r"unexmin_(\w+)$", dep)
            if m:
                assert LAYERS.index(m.group(1)) < LAYERS.index(folder), f"unexmin_{folder} links {dep}"
            if "catkin" in dep or "ros" in dep.lower() and not dep.startswith("unexmin_"):
                assert folder == "ros_layer", f"unexmin_{folder} links the ROS library {dep}"


@pytest.mark.parametrize(
    "header,expected",
    [
        ("ros/ros.h", True),
        ("sensor_msgs/Imu.h", True),
        ("unexmin/Step.h", True),
        ("unexmin/sim/world.h", False),
        ("Eigen/Core", False),
        ("embree3/rtcore.h", False),
    ],
)
def test_ros_headers_are_recognised(header, expected):
    assert is_ros_header(header) is expected

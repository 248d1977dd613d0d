"""The in-repo octomap_msgs/Octomap is the upstream definition (same MD5, so upstream tools read our topic), and the
world launch files start the mapper only with mapping:=true, passing map_file and map_resolution (roslaunch
--dump-params and --nodes: no master needed)."""

import subprocess

import pytest
import yaml

UPSTREAM_OCTOMAP_MD5 = "9a45536b45c5e409cd49f04bb2d9999f"


def test_octomap_message_md5_is_the_upstream_one():
    from octomap_msgs.msg import Octomap

    assert Octomap._md5sum == UPSTREAM_OCTOMAP_MD5
    assert Octomap._type == "octomap_msgs/Octomap"
    assert Octomap.__slots__ == ["header", "binary", "id", "resolution", "data"]


@pytest.mark.parametrize("launch_file", ["tank_world.launch", "mine_world.launch"])
def test_mapping_launch_argument(launch_file):
    def nodes(*args):
        out = subprocess.run(
            ["roslaunch", "--nodes", "unexmin", launch_file, *args], capture_output=True, text=True, timeout=120
        )
        assert out.returncode == 0, out.stderr
        return out.stdout.split()

    assert "/mapper" not in nodes()
    assert "/mapper" in nodes("mapping:=true")
    out = subprocess.run(
        [
            "roslaunch",
            "--dump-params",
            "unexmin",
            launch_file,
            "mapping:=true",
            "map_file:=/tmp/x.bt",
            "map_resolution:=0.05",
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert out.returncode == 0, out.stderr
    params = yaml.safe_load(out.stdout)
    assert params["/mapper/map_file"] == "/tmp/x.bt"
    assert params["/mapper/resolution"] == pytest.approx(0.05)

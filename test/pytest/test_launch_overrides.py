"""Per-robot configuration through the world launch files: UX_k_overrides:=<xacro> changes that
robot's description only (roslaunch --dump-params evaluates the xacro commands; no master needed)."""

import re
import subprocess
from pathlib import Path

import pytest
import yaml

REPO = Path(__file__).resolve().parents[2]
OVERRIDES = REPO / "urdf" / "ux1_perturbed.xacro"  # buoyancy surplus 0.05 kg, 14 deg pitch, 8 deg roll


def hydro_mass(urdf):
    block = re.search(r"<hydrodynamics\b.*?</hydrodynamics>", urdf, re.S)
    assert block, "no <hydrodynamics> block in the description"
    return float(re.search(r'<mass value="([^"]+)"', block.group(0)).group(1))


@pytest.mark.parametrize("launch_file", ["tank_world.launch", "mine_world.launch"])
def test_overrides_reach_one_robot_only(launch_file):
    out = subprocess.run(
        ["roslaunch", "--dump-params", "unexmin", launch_file, "robots:=3", f"UX_2_overrides:={OVERRIDES}"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert out.returncode == 0, out.stderr
    params = yaml.safe_load(out.stdout)
    masses = {r: hydro_mass(params[f"/{r}/robot_description"]) for r in ("UX_1", "UX_2", "UX_3")}
    neutral = 1000.0 * 4.0 / 3.0 * 3.141592653589793 * 0.3**3
    assert masses["UX_1"] == pytest.approx(neutral, abs=1e-6)
    assert masses["UX_3"] == pytest.approx(neutral, abs=1e-6)
    assert masses["UX_2"] == pytest.approx(neutral - 0.05, abs=1e-6)
    assert 'name="UX_2/base_link"' in params["/UX_2/robot_description"]

"""The xacro expander: a robot file (urdf/*.urdf.xacro) with its arguments -> URDF text, as the launch files run it."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

from unexmin.description.errors import DescriptionError

REPO = Path(__file__).resolve().parents[3]
#: The UX-1's robot file.
ROBOT_FILE = REPO / "urdf" / "ux1.urdf.xacro"


def xacro_executable():
    """xacro of the running interpreter's venv, else $XACRO, else PATH."""
    for candidate in (os.environ.get("XACRO"), str(Path(sys.executable).parent / "xacro"), shutil.which("xacro")):
        if candidate and Path(candidate).is_file():
            return candidate
    raise DescriptionError("xacro not found: install xacro==1.13.3 (scripts/setup.sh) or set $XACRO")


def expand(description=ROBOT_FILE, name="UX_1", overrides=None):
    """URDF text of the xacro robot file `description` for robot `name`, with an optional overrides file."""
    args = [xacro_executable(), str(description), f"name:={name}"]
    if overrides:
        args.append(f"overrides:={Path(overrides).resolve()}")
    proc = subprocess.run(args, capture_output=True, text=True)
    if proc.returncode != 0:
        raise DescriptionError(f"xacro {description} {' '.join(args[2:])} failed: {proc.stderr.strip()}")
    return proc.stdout

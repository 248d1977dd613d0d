"""The house style holds over the whole tree: ruff (pinned in scripts/setup.sh, configured in ruff.toml) finds no
lint error and no file that `ruff format` would change. Fix with `ruff check --fix .` and `ruff format .`.

Run: python -m pytest test/pytest/test_style.py -q -p no:cacheprovider
"""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


def ruff():
    """The ruff of this Python's venv (scripts/setup.sh installs it there), else the one on PATH."""
    found = shutil.which("ruff", path=os.pathsep.join([str(Path(sys.executable).parent), os.environ.get("PATH", "")]))
    assert found, "ruff not found: scripts/setup.sh installs it into the venv"
    return found


@pytest.mark.parametrize("command", [["check", "--no-cache"], ["format", "--check", "--no-cache"]])
def test_ruff(command):
    run = subprocess.run([ruff(), *command, "."], cwd=REPO, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, f"ruff {' '.join(command)} .: exit status {run.returncode}\n{run.stdout}{run.stderr}"


def test_ruff_sees_the_whole_tree():
    # The node scripts have no .py suffix: ruff.toml includes them; a tree ruff did not read passes trivially.
    run = subprocess.run([ruff(), "check", "--show-files", "."], cwd=REPO, capture_output=True, text=True, timeout=60)
    seen = {Path(line).relative_to(REPO).as_posix() for line in run.stdout.split()}
    nodes = {f"nodes/{p.name}" for p in (REPO / "nodes").iterdir() if p.is_file()}
    assert nodes <= seen, f"ruff does not read {sorted(nodes - seen)}"
    for folder in ("python/unexmin", "test/pytest", "test/rostest", "bench", "scripts"):
        assert any(s.startswith(folder + "/") for s in seen), f"ruff reads nothing in {folder}"

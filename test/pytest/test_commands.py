"""Every command the docs name answers --help: each `python -m unexmin.…` written in README.md, docs/*.md or
scripts/*.sh, each `rosrun unexmin …` written there and each executable in nodes/. A documented command whose
module moved or broke fails here (exit status 0 and a usage line expected). No roscore needed.

Run: python -m pytest test/pytest/test_commands.py -q -p no:cacheprovider (workspace sourced).
"""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
DOCUMENTS = [REPO / "README.md", *sorted((REPO / "docs").glob("*.md")), *sorted((REPO / "scripts").glob("*.sh"))]
NODES = sorted(p.name for p in (REPO / "nodes").iterdir() if p.is_file() and os.access(p, os.X_OK))


def documented(pattern):
    """Every distinct first group of `pattern` in the documents."""
    found = set()
    for path in DOCUMENTS:
        found.update(re.findall(pattern, path.read_text()))
    return sorted(found)


MODULES = documented(r"python -m (unexmin[a-z_.]*[a-z_])")
ROSRUN = documented(r"rosrun unexmin ([A-Za-z_][A-Za-z0-9_]*)")


def help_of(command):
    run = subprocess.run(command + ["--help"], capture_output=True, text=True, timeout=120, cwd=REPO)
    return run.returncode, run.stdout + run.stderr


def test_the_docs_name_commands():
    # The lists below come from the docs: an empty one would test nothing.
    assert {
        "unexmin.batch",
        "unexmin.identify",
        "unexmin.map_quality",
        "unexmin.missions.explore",
        "unexmin.worlds.generator",
        "unexmin.replay",
        "unexmin.worlds.from_scan",
    } <= set(MODULES)
    assert set(ROSRUN) <= set(NODES), f"documented but not in nodes/: {set(ROSRUN) - set(NODES)}"
    assert len(NODES) >= 9


@pytest.mark.parametrize("module", MODULES)
def test_python_module_help(module):
    status, out = help_of([sys.executable, "-m", module])
    assert status == 0, f"python -m {module} --help: exit status {status}\n{out}"
    assert "usage:" in out, out


@pytest.mark.parametrize("node", NODES)
def test_node_help(node):
    status, out = help_of([sys.executable, str(REPO / "nodes" / node)])
    assert status == 0, f"nodes/{node} --help: exit status {status}\n{out}"
    assert "usage:" in out and node in out, out

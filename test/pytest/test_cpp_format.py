"""Every C++ file of the tree is formatted as .clang-format says (clang-format pinned in scripts/setup.sh).
Fix with: clang-format -i $(git ls-files '*.h' '*.cpp')"""

import shutil
import subprocess
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
FOLDERS = ("cpp", "test", "bench", "docs/tools")


def cpp_files():
    files = sorted(p for folder in FOLDERS for p in (REPO / folder).rglob("*") if p.suffix in (".h", ".cpp"))
    assert len(files) > 100, f"only {len(files)} C++ files found under {FOLDERS}: the check would check nothing"
    return files


def test_clang_format_is_the_pinned_one():
    exe = shutil.which("clang-format")
    assert exe, "clang-format is not on PATH (scripts/setup.sh installs it into the venv)"
    version = subprocess.run([exe, "--version"], capture_output=True, text=True, check=True).stdout
    assert "version 19." in version, f"expected the pinned clang-format 19, got: {version.strip()}"


def test_every_cpp_file_is_formatted():
    files = [str(p) for p in cpp_files()]
    run = subprocess.run(["clang-format", "--dry-run", "--Werror", *files], capture_output=True, text=True, cwd=REPO)
    wrong = sorted({line.split(":")[0] for line in run.stderr.splitlines() if ": error:" in line})
    assert run.returncode == 0 and not wrong, (
        f"{len(wrong)} C++ file(s) differ from .clang-format (run clang-format -i on them):\n"
        + "\n".join(str(Path(w).relative_to(REPO)) for w in wrong)
    )

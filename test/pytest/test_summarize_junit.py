"""scripts/summarize_junit.py on synthetic JUnit files in the three dialects scripts/test.sh collects
(gtest, pytest, rostest/rosunit): an unexpected skip fails, an allowed one does not, and the last line
counts right. rosunit cannot report a skip, so the rostests are checked not to skip."""

import importlib.util
import re
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "scripts" / "summarize_junit.py"
spec = importlib.util.spec_from_file_location("summarize_junit", SCRIPT)
summarize_junit = importlib.util.module_from_spec(spec)
spec.loader.exec_module(summarize_junit)

GTEST = """<?xml version="1.0" encoding="UTF-8"?>
<testsuites tests="4" failures="0" disabled="1" errors="0" name="AllTests">
  <testsuite name="Hydro" tests="4" failures="0" disabled="1" skipped="1" errors="0">
    <testcase name="Buoyancy" status="run" result="completed" classname="Hydro" />
    <testcase name="Drag" status="run" result="completed" classname="Hydro" />
    <testcase name="NeedsEmbree" status="run" result="skipped" classname="Hydro">
      <skipped message="test_hydro.cpp:9&#x0A;no embree"><![CDATA[test_hydro.cpp:9
no embree]]></skipped>
    </testcase>
    <testcase name="DISABLED_Old" status="notrun" result="suppressed" classname="Hydro" />
  </testsuite>
</testsuites>
"""
PYTEST = """<?xml version="1.0" encoding="utf-8"?><testsuites><testsuite name="pytest" errors="0" failures="1"
skipped="3" tests="6"><testcase classname="test_replay" name="test_a" time="0.1" /><testcase
classname="test_replay" name="test_b" time="0.1"><failure message="assert 1 == 2">boom</failure></testcase><testcase
classname="test_replay" name="test_bag[1]" time="0.0"><skipped type="pytest.skip" message="sample bag not made yet"
>test_replay.py:118: sample bag not made yet</skipped></testcase><testcase classname="" name="test_translators"
time="0.0"><skipped message="collection skipped">Skipped: source the workspace</skipped></testcase><testcase
classname="test_esc" name="test_known" time="0.0"><skipped type="pytest.xfail" message="known" /></testcase><testcase
classname="test_esc" name="test_c" time="0.0" /></testsuite></testsuites>
"""
ROSTEST = """<?xml version="1.0" encoding="utf-8"?>
<testsuite errors="0" failures="0" name="unittest.suite.TestSuite" tests="2" time="3.0">
  <testcase classname="unexmin.test_sensors.Sensors" name="test_imu" time="1.0"></testcase>
  <testcase classname="unexmin.test_sensors.Sensors" name="test_dvl" time="1.0"><skipped>no DVL</skipped></testcase>
</testsuite>
"""
SKIPS = [
    "Hydro.NeedsEmbree",
    "Hydro.DISABLED_Old",
    "test_replay.test_bag[1]",
    "test_translators",
    "test_esc.test_known",
    "unexmin.test_sensors.Sensors.test_dvl",
]


@pytest.fixture
def results(tmp_path):
    (tmp_path / "unexmin").mkdir()
    (tmp_path / "unexmin" / "gtest-test_hydro.xml").write_text(GTEST)
    (tmp_path / "unexmin" / "pytest-unexmin.xml").write_text(PYTEST)
    (tmp_path / "unexmin" / "rostest-test_rostest_sensors.xml").write_text(ROSTEST)
    return tmp_path


def run(results, capsys, allowed):
    rc = summarize_junit.main(str(results), allowed)
    lines = capsys.readouterr().out.strip().splitlines()
    return rc, lines


def test_every_kind_of_skip_fails_by_default(results, capsys):
    rc, lines = run(results, capsys, {})
    assert rc == 1
    # passed: Buoyancy, Drag, test_a, test_c, test_imu; failed: test_b and the six skips
    assert lines[-1] == "unexmin: 5 passed, 7 failed"
    for test_id in SKIPS:
        assert sum(line.startswith("FAILED: skipped: ") and f": {test_id}: " in line for line in lines) == 1, test_id
    assert any("no embree" in line for line in lines)  # the skip's own message is shown


def test_allowed_skips_pass_and_count_as_neither(results, capsys):
    allowed = {
        "Hydro.*": "Embree is optional",
        "test_replay.test_bag[[]*": "bag made by hand",
        "test_translators": "x",
        "test_esc.test_known": "x",
        "unexmin.test_sensors.*.test_dvl": "x",
    }
    rc, lines = run(results, capsys, allowed)
    assert rc == 1  # test_b still fails
    assert lines[-1] == "unexmin: 5 passed, 1 failed"
    assert sum(line.startswith("allowed skip: ") for line in lines) == len(SKIPS)
    assert "allowed skip: gtest-test_hydro.xml: Hydro.NeedsEmbree (Embree is optional)" in lines
    assert not any(line.startswith("FAILED: skipped") for line in lines)


def test_all_green_with_allowed_skip_exits_zero(tmp_path, capsys):
    (tmp_path / "gtest-a.xml").write_text(GTEST)
    rc, lines = run(tmp_path, capsys, {"Hydro.NeedsEmbree": "why", "Hydro.DISABLED_Old": "why"})
    assert rc == 0
    assert lines[-1] == "unexmin: 2 passed, 0 failed"


def test_missing_and_unreadable_files_and_nothing_run(tmp_path, capsys):
    # catkin's placeholder for a test that wrote no result (the Python module catkin.test_results)
    (tmp_path / "MISSING-rostest-test_world.xml").write_text(
        '<?xml version="1.0" encoding="UTF-8"?>\n<testsuite tests="1" failures="1" time="1" errors="0" '
        'name="rostest-test_world.xml">\n  <testcase name="test_ran" status="run" time="1" classname="Results">\n'
        '    <failure message="Unable to find test results" type=""/>\n  </testcase>\n</testsuite>'
    )
    (tmp_path / "broken.xml").write_text("<testsuite")
    rc, lines = run(tmp_path, capsys, {})
    assert rc == 1
    assert lines[-1] == "unexmin: 0 passed, 2 failed"  # the missing result once, the unreadable file
    empty = tmp_path / "empty"
    empty.mkdir()
    rc, lines = run(empty, capsys, {})
    assert (rc, lines) == (1, ["no test ran", "unexmin: 0 passed, 1 failed"])


def test_an_allowed_skip_needs_a_reason(results):
    with pytest.raises(ValueError, match="no reason"):
        summarize_junit.main(str(results), {"Hydro.*": " "})


def test_command_line_uses_the_shipped_allow_list(results, capsys):
    rc = summarize_junit.main(str(results))
    expected = capsys.readouterr().out
    out = subprocess.run([sys.executable, str(SCRIPT), str(results)], capture_output=True, text=True, timeout=60)
    assert (out.returncode, out.stdout) == (rc, expected)
    assert rc == 1  # test_b fails whatever the allow-list says


def test_rostests_do_not_skip():
    """rosunit (rostest's Python runner) writes a unittest skip as a passed test case, so the summary
    cannot see it: test/rostest/ must not skip at all."""
    pattern = re.compile(r"\bskipTest\b|\bunittest\.skip|@skip(If|Unless)?\b|\bSkipTest\b")
    offenders = [
        f"{path.name}:{n}"
        for path in sorted((REPO / "test" / "rostest").glob("*.py"))
        for n, line in enumerate(path.read_text().splitlines(), 1)
        if pattern.search(line)
    ]
    assert not offenders, f"unittest skips in rostests (reported as passed by rosunit): {offenders}"

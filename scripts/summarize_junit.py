#!/usr/bin/env python3
"""Count every JUnit result file under a folder; the last line is 'unexmin: N passed, N failed';
exit 1 on any failure.

Counted as failed:
- a test case with a failure or an error;
- a result file that is unreadable, or missing: catkin writes a MISSING-*.xml placeholder for a
  gtest that crashed or a rostest that never started;
- a test case that did not run (a pytest skip, skipif, importorskip or xfail; GTEST_SKIP; a
  DISABLED_ gtest), unless ALLOWED_SKIPS names it with a reason: CI must not be green because a
  dependency was missing. (rosunit writes a rostest's unittest skip as a pass, so
  test/pytest/test_summarize_junit.py forbids skips in test/rostest/.)
- no test case at all.
An allowed skip counts as neither passed nor failed; it is listed above the summary line.
"""

import fnmatch
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

# Tests that may legitimately be skipped: {"<classname>.<name>" (fnmatch pattern): "why"}.
# pytest names a case by module path (test.pytest.test_replay.test_sample_bag_contents), gtest by
# suite (RayCaster.EmbreeWatertightOptionIsWhatStopsEdgeLeaks).
ALLOWED_SKIPS = {
    # Eight AVX2 lanes against one: on a CPU without AVX2 and FMA only the one-lane kernels exist (a build that lost
    # its AVX2 flags on a CPU that has both fails Shading.EightLanesAreBuiltAndUsedWhereTheCpuHasAvx2AndFma instead).
    "Shading.EightLanesGiveWhatOneLaneGivesForEveryTileSize": "no AVX2 and FMA on this CPU: nothing to compare",
    "Camera.EightLanesAndOneLaneRenderTheSameImage": "no AVX2 and FMA on this CPU: nothing to compare",
}


def case_id(case):
    classname = case.get("classname") or ""
    return f"{classname}.{case.get('name')}" if classname else str(case.get("name"))


def skip_message(case):
    """Why the case did not run, or None if it ran."""
    skipped = case.find("skipped")
    if skipped is not None:
        return (skipped.text or "").strip() or skipped.get("message") or "skipped"
    if case.get("status") == "notrun" or case.get("result") in ("skipped", "suppressed"):
        return f"not run ({case.get('result') or 'notrun'})"
    return None


def allowed_reason(test_id, allowed):
    for pattern, reason in allowed.items():
        if fnmatch.fnmatchcase(test_id, pattern):
            return reason
    return None


def main(folder, allowed=None):
    allowed = ALLOWED_SKIPS if allowed is None else allowed
    for pattern, reason in allowed.items():
        if not str(reason).strip():
            raise ValueError(f"allowed skip {pattern!r} has no reason")
    passed = failed = 0
    allowed_skips = []
    for path in sorted(Path(folder).rglob("*.xml")):
        if path.name.startswith("MISSING-"):  # one failure, not also its placeholder test case
            failed += 1
            print(f"FAILED: no result written: {path.name}")
            continue
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError:
            print(f"unreadable result file: {path}")
            failed += 1
            continue
        for case in root.iter("testcase"):
            test_id = case_id(case)
            skipped = skip_message(case)
            if case.find("failure") is not None or case.find("error") is not None:
                failed += 1
                print(f"FAILED: {path.name}: {test_id}")
            elif skipped is not None:
                reason = allowed_reason(test_id, allowed)
                if reason is None:
                    failed += 1
                    print(
                        f"FAILED: skipped: {path.name}: {test_id}: {' '.join(skipped.split())[:200]}"
                        f" (fix the cause, or allow it in scripts/summarize_junit.py ALLOWED_SKIPS)"
                    )
                else:
                    allowed_skips.append(f"allowed skip: {path.name}: {test_id} ({reason})")
            else:
                passed += 1
    if passed + failed == 0:
        print("no test ran")
        failed = 1
    for line in allowed_skips:
        print(line)
    print(f"unexmin: {passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))

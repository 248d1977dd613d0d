#!/usr/bin/env python3
"""Count every JUnit result file under a folder; print 'N passed, N failed' and exit 1 on failure.

A test file that is missing or empty (a gtest that crashed, a rostest that never started) counts
as a failure: catkin writes a MISSING-*.xml placeholder for those.
"""

import sys
import xml.etree.ElementTree as ET
from pathlib import Path


def main(folder):
    passed = failed = skipped = 0
    for path in sorted(Path(folder).rglob("*.xml")):
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError:
            print(f"unreadable result file: {path}")
            failed += 1
            continue
        for case in root.iter("testcase"):
            if case.find("failure") is not None or case.find("error") is not None:
                failed += 1
                print(f"FAILED: {path.name}: {case.get('classname')}.{case.get('name')}")
            elif case.find("skipped") is not None:
                skipped += 1
            else:
                passed += 1
        if path.name.startswith("MISSING-"):
            failed += 1
            print(f"FAILED: no result written: {path.name}")
    if passed + failed == 0:
        print("no test ran")
        failed = 1
    print(f"unexmin: {passed} passed, {failed} failed, {skipped} skipped")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))

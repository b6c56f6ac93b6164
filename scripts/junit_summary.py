#!/usr/bin/env python3
"""Aggregate the JUnit XML files under a colcon build folder.

Prints each failing or erroring test case, then a closing line 'N passed, N failed'.
Exits 1 when any test failed or errored, when a result file is unreadable, or when no test ran.
Skipped tests count as failures: a missing dependency must not pass silently.
"""

import sys
import xml.etree.ElementTree as ET
from pathlib import Path


def main(build_dir: str) -> int:
    passed = failed = 0
    bad_files = []
    for path in sorted(Path(build_dir).glob("*/test_results/**/*.xml")):
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError as exc:
            bad_files.append(f"{path}: {exc}")
            continue
        suites = [root] if root.tag == "testsuite" else list(root.iter("testsuite"))
        for suite in suites:
            # rosunit counts failed unittest subTests in the suite's attributes without writing them into any
            # testcase: whatever the attributes count beyond the failed testcases is a failure too.
            declared = int(suite.get("failures") or 0) + int(suite.get("errors") or 0)
            recorded = sum(1 for case in suite.iter("testcase") if any(c.tag in ("failure", "error") for c in case))
            if declared > recorded:
                failed += declared - recorded
                print(f"FAILURE: {path.parent.name}/{path.name} :: {declared - recorded} failure(s) counted by the "
                      f"suite '{suite.get('name')}' without a failing testcase (failed subTests?): see its output")
        for case in root.iter("testcase"):
            problems = [c for c in case if c.tag in ("failure", "error", "skipped")]
            if problems:
                failed += 1
                kind = problems[0].tag
                text = (problems[0].get("message") or problems[0].text or "").strip().splitlines()
                print(f"{kind.upper()}: {path.parent.name}/{path.name} :: {case.get('classname')}.{case.get('name')}"
                      f" {text[0] if text else ''}")
            else:
                passed += 1
    for line in bad_files:
        print(f"UNREADABLE RESULT FILE: {line}")
    print(f"{passed} passed, {failed + len(bad_files)} failed")
    return 0 if (passed > 0 and failed == 0 and not bad_files) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "build"))

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

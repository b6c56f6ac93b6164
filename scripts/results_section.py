#!/usr/bin/env python3
"""Replace (or add) one section of bench/results.md, keeping every other section.

    scripts/results_section.py bench/results.md report.md

The report's first line is the section header (e.g. "## pick (scripts/bench_pick.sh)"); the section it
replaces runs from that header to the next "## " header. Sections written by a script name it in their header,
which is how scripts/bench.sh knows to keep them when it rewrites the executables' sections."""

import sys
from pathlib import Path


def replace_section(text: str, report: str) -> str:
    header = report.splitlines()[0].rstrip()
    if not header.startswith("## "):
        raise ValueError(f"the report must start with a '## ' header, got {header!r}")
    kept: list[str] = []
    skipping = False
    for line in text.splitlines():
        if line.startswith("## "):
            skipping = line.rstrip() == header
        if not skipping:
            kept.append(line)
    return "\n".join(kept).rstrip("\n") + "\n\n" + report.rstrip("\n") + "\n"


def main() -> int:
    if len(sys.argv) != 3:
        print("usage: results_section.py RESULTS.md REPORT.md", file=sys.stderr)
        return 2
    results, report = Path(sys.argv[1]), Path(sys.argv[2])
    text = results.read_text() if results.exists() else "# Benchmark results\n"
    try:
        updated = replace_section(text, report.read_text())
    except (OSError, ValueError) as err:
        print(f"results_section.py: {err}", file=sys.stderr)
        return 2
    tmp = results.with_suffix(".md.tmp")
    tmp.write_text(updated)
    tmp.replace(results)
    return 0


if __name__ == "__main__":
    sys.exit(main())

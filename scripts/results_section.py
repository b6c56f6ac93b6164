#!/usr/bin/env python3
"""Replace (or add) one section of bench/results.md, keeping every other section.

    scripts/results_section.py bench/results.md report.md

The report's first line is the section header (e.g. "## pick (scripts/bench_pick.sh)"); the section it
replaces runs from that header to the next "## " header, and the report takes its place (a new section goes at
the end). Sections written by a script name it in their header, which is how scripts/bench.sh knows to keep them
when it rewrites the executables' sections."""

import sys
from pathlib import Path


def replace_section(text: str, report: str) -> str:
    header = report.splitlines()[0].rstrip()
    if not header.startswith("## "):
        raise ValueError(f"the report must start with a '## ' header, got {header!r}")
    # The text as sections: the part before the first "## " header, then one block per header.
    blocks: list[list[str]] = [[]]
    for line in text.splitlines():
        if line.startswith("## "):
            blocks.append([])
        blocks[-1].append(line)
    parts = ["\n".join(block).strip("\n") for block in blocks]
    new = report.strip("\n")
    at = [k for k, block in enumerate(blocks) if k > 0 and block[0].rstrip() == header]
    if at:
        parts[at[0]] = new
        parts = [part for k, part in enumerate(parts) if k not in at[1:]]
    else:
        parts.append(new)
    return "\n\n".join(part for part in parts if part) + "\n"


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

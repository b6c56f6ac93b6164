#!/usr/bin/env python3
"""Plot the scaling curves of bench/results.md into PNGs and write their section of it.

    scripts/plot_scaling.py bench/results.md

Reads the tables that `make bench` wrote (scaling_bench: planning time and collision checks per second against
the number of obstacles; occupancy_bench: the occupancy map's update time against the cloud's size), draws each
into a PNG beside results.md, and replaces the section "## scaling curves (scripts/plot_scaling.py)" with a link
to each figure and one line of what it measured: the growth between the smallest and the largest size. A curve
whose table is missing (a partial run, `scripts/bench.sh ik_bench`) is left out and named on stderr."""

import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402 (the backend first)

sys.path.insert(0, str(Path(__file__).resolve().parent))
from results_section import replace_section  # noqa: E402

HEADER = "## scaling curves (scripts/plot_scaling.py)"


@dataclass
class Table:
    columns: list[str]
    rows: list[list[str]]

    def column(self, name: str) -> list[float]:
        index = self.columns.index(name)
        return [float(row[index].split("x")[0] if name == "image" else row[index]) for row in self.rows]


def find_table(text: str, section: str, title: str) -> Table | None:
    """The markdown table after the line `title` inside section `section` ("## <section>" header)."""
    in_section = False
    after_title = False
    lines: list[str] = []
    for line in text.splitlines():
        if line.startswith("## "):
            in_section = line.startswith(f"## {section}")
            after_title = False
            continue
        if not in_section:
            continue
        if line.strip() == title:
            after_title = True
            continue
        if after_title:
            if line.startswith("|"):
                lines.append(line)
            elif lines:
                break
    if len(lines) < 3:
        return None

    def cells(row: str) -> list[str]:
        return [c.strip() for c in row.strip().strip("|").split("|")]

    return Table(cells(lines[0]), [cells(row) for row in lines[2:]])


def ratio(values: list[float]) -> str:
    """The growth from the first value to the last, as "x1.3" or "x255"."""
    if values[0] <= 0:
        return "n/a"
    r = values[-1] / values[0]
    return f"x{r:.0f}" if r >= 10 else f"x{r:.2g}"


def plot(
    path: Path, t: Table, x: str, series: dict[str, str], xlabel: str, ylabel: str, title: str
) -> dict[str, list[float]]:
    """Draw column `x` against each column of `series` ({legend label: column}); returns every column drawn."""
    columns = {name: t.column(name) for name in [x, *series.values()]}
    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=100)
    # One colour per method (FCL red, the rest blue), p95 dashed.
    for label, name in series.items():
        ax.plot(
            columns[x],
            columns[name],
            marker="o",
            label=label,
            color="C3" if "FCL" in label else "C0",
            linestyle="--" if "p95" in label else "-",
        )
    ax.set_xscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.set_ylim(bottom=0)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    return columns


def planning(t: Table, out: Path) -> str:
    series = {
        "median, pre-check": "median ms, pre-check",
        "p95, pre-check": "p95 ms, pre-check",
        "median, FCL only": "median ms, FCL only",
        "p95, FCL only": "p95 ms, FCL only",
    }
    c = plot(
        out / "scaling_planning.png",
        t,
        "boxes",
        series,
        "boxes in the scene",
        "planning time (ms)",
        "Planning time vs obstacles (table-top queries)",
    )
    boxes, pre, fcl = c["boxes"], c["median ms, pre-check"], c["median ms, FCL only"]
    solved = ", ".join(
        f"{s:.0f}/{f:.0f}" for s, f in zip(t.column("solved, pre-check"), t.column("feasible"), strict=True)
    )
    return (
        f"[planning time vs obstacles](scaling_planning.png): {boxes[0]:.0f} -> {boxes[-1]:.0f} boxes, median "
        f"{pre[0]:.2f} -> {pre[-1]:.2f} ms with the pre-check ({ratio(pre)}), {fcl[0]:.2f} -> {fcl[-1]:.2f} ms FCL "
        f"only ({ratio(fcl)}); solved/feasible with the pre-check {solved}"
    )


def collision_checks(t: Table, out: Path) -> str:
    fcl_name, pre_name = "full-state checks/s (FK + FCL)", "pre-check calls/s (FK + spheres)"
    series = {"full-state checks (FK + FCL)": fcl_name, "pre-check calls (FK + spheres)": pre_name}
    c = plot(
        out / "scaling_collision_checks.png",
        t,
        "boxes",
        series,
        "boxes in the scene",
        "per second",
        "Collision checks per second vs obstacles",
    )
    boxes, fcl, pre = c["boxes"], c[fcl_name], c[pre_name]
    return (
        f"[collision checks per second vs obstacles](scaling_collision_checks.png): {boxes[0]:.0f} -> "
        f"{boxes[-1]:.0f} boxes, {fcl[0]:,.0f} -> {fcl[-1]:,.0f} full-state checks/s ({ratio(fcl)}), "
        f"{pre[0]:,.0f} -> {pre[-1]:,.0f} pre-check calls/s ({ratio(pre)})"
    )


def octomap(t: Table, out: Path) -> str:
    c = plot(
        out / "scaling_octomap.png",
        t,
        "points in range",
        {"median": "per cloud, median ms", "p95": "per cloud, p95 ms"},
        "points in range per cloud",
        "update time (ms)",
        "Occupancy map update vs cloud size (0.025 m cells)",
    )
    points, median = c["points in range"], c["per cloud, median ms"]
    return (
        f"[occupancy map update vs cloud size](scaling_octomap.png): {points[0]:,.0f} -> {points[-1]:,.0f} points "
        f"({ratio(points)}), median {median[0]:.1f} -> {median[-1]:.1f} ms per cloud ({ratio(median)})"
    )


# Each curve: the section and title of its table in results.md, and what draws and summarizes it.
CURVES: dict[str, tuple[str, str, Callable[[Table, Path], str]]] = {
    "planning": ("scaling_bench", "planning time vs obstacles (RRTConnect, 0.005 rad)", planning),
    "collision checks": (
        "scaling_bench",
        "collision checks per second vs obstacles (random arm states)",
        collision_checks,
    ),
    "octomap": ("occupancy_bench", "update time vs cloud size (0.025 m)", octomap),
}


def main() -> int:
    if len(sys.argv) != 2:
        print("usage: plot_scaling.py RESULTS.md", file=sys.stderr)
        return 2
    results = Path(sys.argv[1])
    try:
        text = results.read_text()
    except OSError as err:
        print(f"plot_scaling.py: {err}", file=sys.stderr)
        return 2
    lines = []
    for name, (section, title, curve) in CURVES.items():
        t = find_table(text, section, title)
        if t is None:
            print(f"plot_scaling.py: no {name} table in {results}: that curve is left out", file=sys.stderr)
        else:
            lines.append(f"- {curve(t, results.parent)}")
    if not lines:
        return 0
    report = HEADER + "\n\n" + "\n".join(lines) + "\n"
    tmp = results.with_suffix(".md.tmp")
    tmp.write_text(replace_section(text, report))
    tmp.replace(results)
    return 0


if __name__ == "__main__":
    sys.exit(main())

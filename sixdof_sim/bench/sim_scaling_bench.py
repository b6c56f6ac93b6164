#!/usr/bin/env python3
"""sim_scaling_bench: the simulator's real-time factor against the number of objects, with PyBullet alongside.

    sim_scaling_bench [--counts 5,20,50,100] [--rounds N] [--plot PNG]

For each count, sim_bench with that many dynamic objects (the default world's, then 3 x 3 x 5 cm boxes on an 8 cm
grid on its table), alternated with the same scenario in PyBullet (objects awake, its default, and allowed to
sleep), --rounds times; medians. Prints the bench/results.md section and draws the curves into PNG (default:
$SIXDOF_BENCH_DIR/sim_scaling.png, the repository's bench/ when scripts/bench.sh runs it)."""

import argparse
import os
import sys
from pathlib import Path

from matplotlib.figure import Figure
from sim_compare import BenchError, alternate, median


def plot(counts: list[int], curves: dict[str, list[float]], path: Path) -> None:
    fig = Figure(figsize=(7, 4.2), dpi=110)
    ax = fig.subplots()
    for label, values in curves.items():
        ax.plot(counts, values, marker="o", label=label)
    ax.set_xlabel("dynamic objects in the world")
    ax.set_ylabel("real-time factor (x real time)")
    ax.set_title("Simulator speed vs objects: 1 kHz steps, arm on a trajectory, objects resting", fontsize=10)
    ax.set_xticks(counts)
    ax.set_ylim(bottom=0)
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--counts", default="5,20,50,100")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--plot", type=Path)
    args = parser.parse_args()
    try:
        counts = [int(c) for c in args.counts.split(",")]
    except ValueError:
        counts = []
    if not counts or min(counts) < 0 or args.rounds < 1:
        print(
            "sim_scaling_bench: --counts must be object counts >= 0 (e.g. 5,20,50,100), --rounds >= 1", file=sys.stderr
        )
        return 2
    png = args.plot
    if png is None:
        bench_dir = os.environ.get("SIXDOF_BENCH_DIR", "")
        if not bench_dir:
            print("sim_scaling_bench: give --plot PNG, or SIXDOF_BENCH_DIR (scripts/bench.sh sets it)", file=sys.stderr)
            return 2
        png = Path(bench_dir) / "sim_scaling.png"
    ours, pybullet, pybullet_sleep, step_us, settled_us = [], [], [], [], []
    try:
        for n in counts:
            rounds = alternate(n, args.rounds)
            ours.append(median([r.ours.rtf_wall for r in rounds]))
            pybullet.append(median([r.pybullet.rtf_wall for r in rounds]))
            pybullet_sleep.append(median([r.pybullet_sleep.rtf_wall for r in rounds]))
            step_us.append(median([r.ours.us_per_step for r in rounds]))
            settled_us.append(
                median([1e6 * r.ours.extra["settled_wall"] / r.ours.extra["settled_steps"] for r in rounds])
            )
    except BenchError as err:
        print(f"sim_scaling_bench: {err}", file=sys.stderr)
        return 1
    plot(
        counts,
        {
            "sixdof_sim": ours,
            "PyBullet (objects awake, its default)": pybullet,
            "PyBullet (objects may sleep)": pybullet_sleep,
        },
        png,
    )
    print(
        f"20 s simulated per run, median of {args.rounds} alternated runs per count; the objects settle on the "
        "table in their first seconds (ours then lets them sleep) and rest while the arm moves (sim_vs_pybullet_bench "
        "has the setup). Plot: "
        f"[{png.name}]({png.name})"
    )
    print()
    print(
        "| dynamic objects | ours, x real time | ours, us per step | ours, us per step after 5 s | PyBullet | "
        "PyBullet, sleeping objects |"
    )
    print("|---:|---:|---:|---:|---:|---:|")
    for row in zip(counts, ours, step_us, settled_us, pybullet, pybullet_sleep, strict=True):
        print("| {} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.1f} |".format(*row))
    if len(counts) > 1:
        span = counts[-1] - counts[0]
        print()
        print(
            f"ours, per object added ({counts[0]} -> {counts[-1]}): {(step_us[-1] - step_us[0]) / span:.2f} us per "
            f"step over the whole run, {(settled_us[-1] - settled_us[0]) / span:.2f} us once the objects rest asleep"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())

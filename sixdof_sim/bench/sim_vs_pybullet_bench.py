#!/usr/bin/env python3
"""sim_vs_pybullet_bench: this simulator against PyBullet on the same work, alternated three times in one run.

    sim_vs_pybullet_bench [--rounds N] [--objects N]

Each round runs sim_bench (20 s simulated at 1 kHz: the default world's objects, the arm's joints on sinusoids),
then the scenario it wrote in PyBullet (pybullet_world.py), then the same with PyBullet's objects allowed to sleep.
Prints the bench/results.md section: the setup, every round and the median ratios."""

import argparse
import sys
from collections import Counter

from sim_compare import BenchError, alternate, median


def shapes(scenario: dict) -> str:
    """The dynamic objects by shape, e.g. '3 box, 1 cylinder, 1 sphere'."""
    count = Counter(o["shape"] for o in scenario["objects"] if not o["static"])
    return ", ".join(f"{n} {shape}" for shape, n in sorted(count.items()))


def setup_text(scenario: dict, pybullet_version: str, control_us: float) -> str:
    static = sum(1 for o in scenario["objects"] if o["static"] and o["collision"])
    dt = scenario["time_step"]
    kp = scenario["position_gain"] * dt
    return f"""Same work in both: the robot's URDF (its mesh collisions as convex hulls of the STL vertices, fixed links
merged into their parent, inertias from the file; a link without `<inertial>` is massless in both), sim_bench's
default world: its dynamic objects ({shapes(scenario)}; btRigidBody in both, PyBullet's maximal coordinates), its
{static} static bodies and the ground plane; no robot self-collision. {scenario["steps"] * dt:g} s simulated in
steps of {dt * 1e3:g} ms (no substeps); every non-mimic joint on a sinusoid about the middle of its range, position
and velocity targets every step to the same servo (Bullet's btMultiBodyJointMotor, kp {kp:g},
kd 1, bounded by the URDF effort), the mimic finger coupled by a gear constraint (erp 0.2, 1000 N);
{scenario["solver_iterations"]} solver iterations at most, residual threshold 1e-7, split impulse below 0.5 mm,
ERP 0.2, two friction directions (PyBullet's cone friction off), the same friction, rolling and spinning friction
per object. PyBullet {pybullet_version} (the PyPI wheel, in the benchmark venv) is driven as its users drive it:
one `setJointMotorControlArray` and one `stepSimulation` per step through its Python API (the targets computed
before the timed loop; the control call alone costs {control_us:.1f} us).

What differs: PyBullet's Bullet is single precision (ours double); a contact's friction is the product of the two
coefficients in PyBullet, the smaller one in ours; PyBullet keeps its own collision margins (ours 1 mm); PyBullet's
API has no articulated warm starting (ours warm-starts the servos and limits); PyBullet keeps objects awake
by default (the last column lets them sleep, at PyBullet's own sleeping thresholds). The arm's trajectory keeps it
clear of the objects, so both do the same work: the objects settle on the table, then rest."""


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--objects", type=int, default=5)
    args = parser.parse_args()
    if args.rounds < 1 or args.objects < 0:
        print("sim_vs_pybullet_bench: --rounds must be >= 1 and --objects >= 0", file=sys.stderr)
        return 2
    try:
        rounds = alternate(args.objects, args.rounds)
    except BenchError as err:
        print(f"sim_vs_pybullet_bench: {err}", file=sys.stderr)
        return 1
    control_us = 1e6 * median([r.pybullet.extra["control_call"] for r in rounds])
    print(setup_text(rounds[0].ours.extra, rounds[0].pybullet.extra["pybullet"], control_us))
    print()
    print("| round | ours, x real time | PyBullet | ratio | PyBullet, sleeping objects | ratio |")
    print("|---:|---:|---:|---:|---:|---:|")
    for i, r in enumerate(rounds, 1):
        print(
            f"| {i} | {r.ours.rtf_wall:.1f} ({r.ours.us_per_step:.1f} us/step) | {r.pybullet.rtf_wall:.1f} "
            f"({r.pybullet.us_per_step:.1f} us/step) | {r.ours.rtf_wall / r.pybullet.rtf_wall:.2f} | "
            f"{r.pybullet_sleep.rtf_wall:.1f} | {r.ours.rtf_wall / r.pybullet_sleep.rtf_wall:.2f} |"
        )
    print()
    ratio = median([r.ours.rtf_wall / r.pybullet.rtf_wall for r in rounds])
    ratio_cpu = median([r.ours.rtf_cpu / r.pybullet.rtf_cpu for r in rounds])
    ratio_sleep = median([r.ours.rtf_wall / r.pybullet_sleep.rtf_wall for r in rounds])
    print(
        f"median ratio, ours / PyBullet (real-time factors): {ratio:.2f} on the wall clock, {ratio_cpu:.2f} in CPU "
        f"time (target >= 2.0); against PyBullet with sleeping objects {ratio_sleep:.2f}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())

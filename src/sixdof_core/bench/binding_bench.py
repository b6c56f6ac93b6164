#!/usr/bin/env python3
"""The Python bindings against the C++ core: the same IK and planning problems, the same seeds, in one run.

    binding_bench.py --baseline BINARY [--report FILE] [--rounds 3] [--urdf U --srdf S --package-dir D]

The problems: IK of random reachable poses of the first chain group (forward kinematics of StateSampler states,
seed 1) with every solver, and a chain of pose goals of the group's tip on a table-top world (top-down poses over
a pick spot, a place spot and random points; each planned from where the previous one ended, with RRTConnect,
IK-sampled goals and OMPL reseeded per query). They are written to one problem file; the C++ baseline
(bench/binding_baseline.cpp, the core called directly) and this script (the same calls through sixdof_core) run
them in alternating rounds, each call timed by wall clock around it. The report gives the medians, their ratio,
and how many problems had the same outcome (status and solution) on both paths. Default robot: the sixdof
description of this checkout.
"""

from __future__ import annotations

import argparse
import datetime
import math
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

import sixdof_core

REPO = Path(__file__).resolve().parents[3]
DESCRIPTION = REPO / "sixdof_description"
# IK problems per solver (KDL's restarts spend the whole 5 ms timeout on most poses: fewer of them).
IK_COUNTS = {"analytic": 10000, "numeric": 10000, "kdl": 300}
IK_TIMEOUT = 0.005
PLAN_QUERIES = 100
# plan_bench's settings: 1 s allowed, motions checked every 0.005 rad, points at most 0.05 rad apart.
PLAN_TIME, PLAN_SEGMENT, PLAN_STEP = 1.0, 0.005, 0.05
PADDING = 0.005
# The table-top world of test/test_planning_table_top.h: (kind, id, position, dimensions).
WORLD = (
    ("box", "table", (0.3, 0.0, -0.025), (1.2, 1.2, 0.05)),
    ("box", "red_cube", (0.40, -0.15, 0.02), (0.04, 0.04, 0.04)),
    ("cylinder", "post", (0.42, 0.03, 0.15), (0.025, 0.30)),
    ("sphere", "ball", (0.20, 0.30, 0.06), (0.06,)),
)


@dataclass
class Problems:
    model: sixdof_core.RobotModel
    group: str
    ik: list[tuple[str, np.ndarray]]  # (solver, tip pose)
    plans: list[np.ndarray]  # tip poses in the chain's base frame


@dataclass
class Outcome:
    status: int
    micros: float
    q: np.ndarray


@dataclass
class Timings:
    outcomes: dict[tuple[str, int], list[Outcome]] = field(default_factory=dict)

    def add(self, kind: str, index: int, outcome: Outcome) -> None:
        self.outcomes.setdefault((kind, index), []).append(outcome)


def make_problems(model: sixdof_core.RobotModel) -> Problems:
    group = next(g for g in model.groups if g.is_chain)
    chain = sixdof_core.KinematicChain.for_group(model, group.name)
    sampler = sixdof_core.StateSampler(model, 1)
    state = sixdof_core.RobotState(model)
    poses = []
    for _ in range(max(IK_COUNTS.values())):
        state.set_to_random_positions(sampler, group.name)
        poses.append(chain.forward(state.group_positions(group.name)))
    ik = [(solver, poses[i]) for solver, count in IK_COUNTS.items() for i in range(count)]
    rng = np.random.default_rng(12345)
    plans = []
    for q in range(PLAN_QUERIES):
        yaw = rng.uniform(-1.0, 1.0)
        if q % 3 == 0:
            x, y, z, yaw = 0.40, -0.15, 0.23, 0.3 * yaw
        elif q % 3 == 1:
            x, y, z, yaw = 0.40, 0.20, 0.23, 0.3 * yaw
        else:
            x, y, z = rng.uniform(0.20, 0.50), rng.uniform(-0.35, 0.35), rng.uniform(0.19, 0.41)
        plans.append(sixdof_core.pose_from_xyz_rpy(x, y, z, math.pi, 0.0, yaw))
    return Problems(model, group.name, ik, plans)


def pose_text(pose: np.ndarray) -> str:
    return " ".join(repr(float(v)) for v in pose.reshape(16))


def write_problems(problems: Problems, urdf: Path, srdf: Path, package_dir: Path, path: Path) -> None:
    lines = [f"model {urdf} {srdf} {package_dir.name} {package_dir}", f"group {problems.group} analytic"]
    lines += [f"ik {solver} {IK_TIMEOUT!r} {pose_text(pose)}" for solver, pose in problems.ik]
    lines.append(f"padding {PADDING!r}")
    for kind, name, position, dims in WORLD:
        pose = sixdof_core.pose_from_xyz_rpy(*position, 0.0, 0.0, 0.0)
        lines.append(f"{kind} {name} {pose_text(pose)} {' '.join(repr(d) for d in dims)}")
    lines.append(f"allow {problems.model.root_link} table")
    lines += [f"plan {PLAN_TIME!r} {PLAN_SEGMENT!r} {PLAN_STEP!r} {pose_text(pose)}" for pose in problems.plans]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


def run_baseline(binary: Path, problem_file: Path, timings: Timings) -> None:
    out = subprocess.run([str(binary), str(problem_file)], capture_output=True, text=True, check=False)
    if out.returncode != 0:
        raise RuntimeError(f"{binary} failed ({out.returncode}): {out.stderr.strip()}")
    for line in out.stdout.splitlines():
        kind, index, status, micros, *q = line.split()
        timings.add(kind, int(index), Outcome(int(status), float(micros), np.array([float(v) for v in q])))


def make_scene(problems: Problems) -> sixdof_core.CollisionScene:
    scene = sixdof_core.CollisionScene(problems.model, padding=PADDING)
    for kind, name, position, dims in WORLD:
        pose = sixdof_core.pose_from_xyz_rpy(*position, 0.0, 0.0, 0.0)
        if kind == "box":
            scene.add_box(name, dims, pose)
        elif kind == "sphere":
            scene.add_sphere(name, dims[0], pose)
        else:
            scene.add_cylinder(name, dims[0], dims[1], pose)
    scene.set_allowed(problems.model.root_link, "table")
    return scene


def run_python(problems: Problems, timings: Timings) -> None:
    clock = time.perf_counter_ns
    options = sixdof_core.IkOptions(timeout=IK_TIMEOUT)
    for name in IK_COUNTS:
        solver = sixdof_core.create_ik_solver(name, problems.model, problems.group)
        indices = [i for i, (solver_name, _) in enumerate(problems.ik) if solver_name == name]
        times, results = [], []
        # The timed loop only calls and keeps: outcomes are read after it, as the C++ side prints them untimed.
        for index in indices:
            pose = problems.ik[index][1]
            start = clock()
            result = solver.solve(pose, options)
            stop = clock()
            times.append(stop - start)
            results.append(result)
        for index, elapsed, result in zip(indices, times, results, strict=True):
            timings.add("ik", index, Outcome(int(result.status), elapsed / 1e3, result.solution))
    ik = sixdof_core.create_ik_solver("analytic", problems.model, problems.group)
    context = sixdof_core.PlanningContext(make_scene(problems), problems.group, ik)
    state = sixdof_core.RobotState(problems.model)
    for index, pose in enumerate(problems.plans):
        plan_options = sixdof_core.PlanningOptions(allowed_planning_time=PLAN_TIME, seed=index + 1)
        plan_options.longest_valid_segment_length = PLAN_SEGMENT
        plan_options.max_joint_step = PLAN_STEP
        start = clock()
        result = context.plan_to_pose(state, pose, options=plan_options)
        stop = clock()
        last = result.path[-1] if result else np.empty(0)
        if result:
            state.set_group_positions(problems.group, last)
        timings.add("plan", index, Outcome(int(result.status), (stop - start) / 1e3, last))


def same(a: Outcome, b: Outcome) -> bool:
    return a.status == b.status and a.q.shape == b.q.shape and bool(np.allclose(a.q, b.q, rtol=0.0, atol=1e-9))


def row(label: str, keys: list[tuple[str, int]], cpp: Timings, py: Timings, unit: float, unit_name: str) -> str:
    cpp_times = [o.micros for k in keys for o in cpp.outcomes[k]]
    py_times = [o.micros for k in keys for o in py.outcomes[k]]
    matching = sum(same(cpp.outcomes[k][0], py.outcomes[k][0]) for k in keys)
    c, p = float(np.median(cpp_times)) / unit, float(np.median(py_times)) / unit
    return f"| {label} | {len(keys)} | {c:.{3 if unit == 1 else 2}f} {unit_name} | " \
           f"{p:.{3 if unit == 1 else 2}f} {unit_name} | {p / c:.2f} | {matching}/{len(keys)} |"


def report(problems: Problems, cpp: Timings, py: Timings, rounds: int) -> str:
    commit = subprocess.run(["git", "-C", str(REPO), "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, check=False).stdout.strip() or "unknown"
    now = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M UTC")
    lines = [
        "## bindings (scripts/bench.sh)",
        "",
        f"Run {now} at commit {commit}: src/sixdof_core/bench/binding_bench.py. The same problems and seeds through "
        f"the Python bindings (sixdof_core) and through the C++ core directly (bench/binding_baseline.cpp), "
        f"{rounds} alternating rounds each; every call timed by wall clock around it (Python: perf_counter_ns around "
        f"the method call); medians over all rounds. Robot '{problems.model.name}', group '{problems.group}'. "
        f"Same outcome: the status and the solution (IK) or the plan's last point (planning) agree to 1e-9 on both "
        "paths (first round).",
        "",
        "| problem | count | C++ median | Python median | Python / C++ | same outcome |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for solver in IK_COUNTS:
        keys = [("ik", i) for i, (name, _) in enumerate(problems.ik) if name == solver]
        lines.append(row(f"IK {solver}, random reachable poses, {IK_TIMEOUT * 1e3:g} ms timeout", keys, cpp, py,
                         1.0, "us"))
    keys = [("plan", i) for i in range(len(problems.plans))]
    lines.append(row("planning: chained top-down pose goals on the table-top world (RRTConnect, 1 s allowed)", keys,
                     cpp, py, 1e3, "ms"))
    return "\n".join(lines) + "\n"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--baseline", type=Path, required=True, help="the binding_baseline executable")
    parser.add_argument("--report", type=Path, help="write the markdown section here (default: stdout)")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--urdf", type=Path, default=DESCRIPTION / "urdf" / "sixdof.urdf")
    parser.add_argument("--srdf", type=Path, default=DESCRIPTION / "config" / "sixdof.srdf")
    parser.add_argument("--package-dir", type=Path, default=DESCRIPTION,
                        help="the package that the URDF's package:// URIs name")
    args = parser.parse_args()
    if args.rounds < 1 or not args.baseline.is_file():
        print(f"binding_bench.py: need --rounds >= 1 and an existing --baseline (got {args.baseline})", file=sys.stderr)
        return 2
    model = sixdof_core.RobotModel.from_files(str(args.urdf), str(args.srdf),
                                              package_dirs={args.package_dir.name: str(args.package_dir)})
    problems = make_problems(model)
    cpp, py = Timings(), Timings()
    with tempfile.TemporaryDirectory() as tmp:
        problem_file = Path(tmp) / "problems.txt"
        write_problems(problems, args.urdf, args.srdf, args.package_dir, problem_file)
        for _ in range(args.rounds):
            run_baseline(args.baseline, problem_file, cpp)
            run_python(problems, py)
    text = report(problems, cpp, py, args.rounds)
    if args.report:
        args.report.write_text(text, encoding="utf-8")
    print(text, end="")
    return 0


if __name__ == "__main__":
    sys.exit(main())

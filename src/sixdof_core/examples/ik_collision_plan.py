#!/usr/bin/env python3
"""IK, a collision check and a plan with sixdof_core's Python bindings: the C++ core, no ROS master.

    ik_collision_plan.py [--urdf URDF --srdf SRDF] [--package-dir DIR] [--search-root DIR] [--seed N]

Loads the robot (default: the sixdof arm, sixdof_description found below the --search-root folders, else on
ROS_PACKAGE_PATH, as package:// URIs resolve), puts it on a table (top at z = 0), takes the first chain group of its
SRDF from its first named state, solves IK for the tip pose of the group's last named state, checks that solution
for collisions, plans to the pose and time-parameterizes the path with the URDF's velocity limits. Exits 0 when the
plan succeeded, 1 when it did not, 2 on bad input.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

import sixdof_core


def load_model(args: argparse.Namespace) -> sixdof_core.RobotModel:
    if args.urdf is None:
        description = Path(sixdof_core.find_package("sixdof_description", args.search_root))
        args.urdf = description / "urdf" / "sixdof.urdf"
        args.srdf = description / "config" / "sixdof.srdf"
    package_dirs = {args.package_dir.name: str(args.package_dir)} if args.package_dir else {}
    return sixdof_core.RobotModel.from_files(str(args.urdf), str(args.srdf or ""), package_dirs=package_dirs,
                                             search_roots=args.search_root)


def table_scene(model: sixdof_core.RobotModel) -> sixdof_core.CollisionScene:
    scene = sixdof_core.CollisionScene(model)
    scene.add_box("table", [2.0, 2.0, 0.05], sixdof_core.pose_from_xyz_rpy(0.0, 0.0, -0.025, 0.0, 0.0, 0.0))
    scene.set_allowed(model.root_link, "table")  # the robot stands on it
    return scene


def run(model: sixdof_core.RobotModel, seed: int) -> int:
    group = next((g for g in model.groups if g.is_chain), None)
    states = [s.name for s in model.group_states if group and s.group == group.name]
    if group is None or len(states) < 2:
        print(f"{model.name}: needs an SRDF chain group with two named states", file=sys.stderr)
        return 2
    start = sixdof_core.RobotState(model)
    start.set_to_named_state(group.name, states[0])
    goal_state = start.copy()
    goal_state.set_to_named_state(group.name, states[-1])
    chain = sixdof_core.KinematicChain.for_group(model, group.name)
    goal = chain.forward(goal_state.group_positions(group.name))  # the tip in the chain's base frame
    print(f"robot '{model.name}', group '{group.name}' ({chain.base_link} -> {chain.tip_link}): "
          f"from '{states[0]}' to the tip pose of '{states[-1]}'")

    ik = sixdof_core.NumericIkSolver(chain)
    solution = ik.solve(goal, sixdof_core.IkOptions(seed=start.group_positions(group.name), random_seed=seed))
    print(f"IK ({ik.name}): {solution.status.name}, joints {np.round(solution.solution, 4)}")
    scene = table_scene(model)
    if solution:
        candidate = start.copy()
        candidate.set_group_positions(group.name, solution.solution)
        clearance = scene.distance(candidate)
        print(f"collision check: {'colliding' if scene.is_colliding(candidate) else 'free'}, "
              f"clearance {clearance.distance:.3f} m ({clearance.body1} - {clearance.body2})")

    planner = sixdof_core.PlanningContext(scene, group.name, ik)
    plan = planner.plan_to_pose(start, goal, options=sixdof_core.PlanningOptions(allowed_planning_time=2.0, seed=seed))
    print(f"plan: {plan.status.name} {plan.message}".rstrip() + f", {len(plan.path)} waypoints in "
          f"{plan.planning_time * 1e3:.1f} ms")
    if not plan:
        return 1
    velocities = [model.joint(name).limits.velocity for name in planner.joint_names]
    limits = sixdof_core.TimeParameterizationOptions(velocities, [2.0 * v for v in velocities], velocity_scaling=0.5)
    timed = sixdof_core.compute_time_optimal_trajectory(planner.joint_names, plan.path, limits)
    print(f"trajectory: {timed.status.name}, {timed.trajectory.duration:.2f} s, {len(timed.trajectory.points)} points")
    return 0 if timed else 1


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--urdf", type=Path, help="default: sixdof_description's URDF (with --srdf)")
    parser.add_argument("--srdf", type=Path)
    parser.add_argument("--package-dir", type=Path, help="the package the URDF's package:// URIs name")
    parser.add_argument("--search-root", action="append", help="where to look for sixdof_description and the "
                        "packages of package:// URIs (default: ROS_PACKAGE_PATH); may be repeated")
    parser.add_argument("--seed", type=int, default=1, help="IK restarts and OMPL (repeatable runs)")
    args = parser.parse_args()
    try:
        model = load_model(args)
    except ValueError as error:
        print(f"ik_collision_plan.py: {error}", file=sys.stderr)
        return 2
    return run(model, args.seed)


if __name__ == "__main__":
    sys.exit(main())

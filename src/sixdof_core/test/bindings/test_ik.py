"""Every IK solver through the bindings: seeded FK -> IK -> FK round trips, the analytic solver's solution set,
failures as results with a status, bad input as exceptions."""

from __future__ import annotations

import numpy as np
import pytest

import sixdof_core


def reachable_poses(model: sixdof_core.RobotModel, group: str, count: int, seed: int) -> list[np.ndarray]:
    chain = sixdof_core.KinematicChain.for_group(model, group)
    sampler = sixdof_core.StateSampler(model, seed)
    state = sixdof_core.RobotState(model)
    poses = []
    for _ in range(count):
        state.set_to_random_positions(sampler, group)
        poses.append(chain.forward(state.group_positions(group)))
    return poses


@pytest.mark.parametrize("solver", ["analytic", "numeric", "kdl"])
def test_round_trips(arm, solver):
    ik = sixdof_core.create_ik_solver(solver, arm, "arm")
    assert ik.name == solver and ik.chain.tip_link == "link6"
    options = sixdof_core.IkOptions(timeout=0.05)
    poses = reachable_poses(arm, "arm", 20, seed=4)
    solved = 0
    for pose in poses:
        result = ik.solve(pose, options)
        if result:
            solved += 1
            position, orientation = sixdof_core.pose_error(ik.chain.forward(result.solution), pose)
            assert position < 1e-5 and orientation < 1e-5
            assert ik.chain.within_limits(result.solution, 1e-9)
        else:
            assert result.status in (sixdof_core.IkStatus.TIMEOUT, sixdof_core.IkStatus.NO_SOLUTION)
    # KDL's Newton-Raphson misses some (the C++ test_ik measures its rate); the others solve every pose.
    assert solved >= (12 if solver == "kdl" else 20)


def test_position_and_quaternion_and_solver_classes(arm):
    chain = sixdof_core.KinematicChain.for_group(arm, "arm")
    # Link6 at (0.4, 0, 0.3) pointing down: half a turn about x, quaternion (x, y, z, w) = (1, 0, 0, 0).
    target = sixdof_core.pose_from_xyz_rpy(0.4, 0.0, 0.3, np.pi, 0.0, 0.0)
    quaternion = [1.0, 0.0, 0.0, 0.0]
    for solver in (sixdof_core.AnalyticIkSolver(chain), sixdof_core.NumericIkSolver(chain),
                   sixdof_core.KdlIkSolver(chain)):
        result = solver.solve([0.4, 0.0, 0.3], quaternion, sixdof_core.IkOptions(timeout=0.2, random_seed=7))
        assert result.ok, result.message
        assert max(sixdof_core.pose_error(chain.forward(result.solution), target)) < 1e-5
    seeded = sixdof_core.NumericIkSolver(chain).solve(target, sixdof_core.IkOptions(seed=np.zeros(6), attempts=5))
    assert seeded.ok and 1 <= seeded.attempts <= 5
    position_only = sixdof_core.NumericIkSolver(chain).solve(target, sixdof_core.IkOptions(position_only=True))
    assert position_only and position_only.position_error < 1e-5


def test_analytic_solution_set(arm):
    solver = sixdof_core.AnalyticIkSolver(sixdof_core.KinematicChain.for_group(arm, "arm"))
    q = np.array([0.3, 0.4, 0.5, 0.6, 0.7, 0.8])
    solutions = solver.solve_all(solver.chain.forward(q))
    assert solutions.ok and solutions.unconstrained_count <= 8
    assert solutions.solutions.shape[1] == 6 and len(solutions.solutions) >= 2
    assert min(np.abs(s - q).max() for s in solutions.solutions) < 1e-6
    np.testing.assert_allclose(solver.wrist_center, [0.3, 0.0, 0.6], atol=1e-9)  # at zero, docs/design.md
    far = sixdof_core.pose_from_xyz_rpy(2.0, 0.0, 0.3, 0.0, 0.0, 0.0)
    out_of_reach = solver.solve_all(far)
    assert not out_of_reach and out_of_reach.status == sixdof_core.IkStatus.OUT_OF_REACH
    assert out_of_reach.solutions.shape == (0, 6)


def test_failures_are_results_and_bad_input_raises(arm, ur_like):
    ik = sixdof_core.create_ik_solver("analytic", arm, "arm")
    sheared = np.eye(4)
    sheared[0, 1] = 0.5
    result = ik.solve(sheared)
    assert result.status == sixdof_core.IkStatus.INVALID_INPUT and "rotation" in result.message
    assert ik.solve(np.eye(4), sixdof_core.IkOptions(seed=[0.0, 1.0])).status == sixdof_core.IkStatus.INVALID_INPUT
    not_normalized = ik.solve([0.3, 0.0, 0.3], [0.0, 0.0, 0.0, 2.0])
    assert not not_normalized and "normalized" in not_normalized.message
    bad_last_row = np.eye(4)
    bad_last_row[3, 0] = 1.0
    with pytest.raises(ValueError, match="last row must be"):
        ik.solve(bad_last_row)
    with pytest.raises(TypeError):
        ik.solve(np.eye(3))
    with pytest.raises(ValueError, match="unknown kinematics solver 'ikfast'"):
        sixdof_core.create_ik_solver("ikfast", arm, "arm")
    with pytest.raises(sixdof_core.AnalyticIkUnsupported, match="spherical wrist"):
        sixdof_core.create_ik_solver("analytic", ur_like, "manipulator")
    with pytest.raises(sixdof_core.RobotModelError, match="mimic"):
        sixdof_core.KinematicChain(arm, "palm", "finger2")

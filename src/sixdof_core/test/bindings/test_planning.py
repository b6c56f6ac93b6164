"""Planning through the bindings: joint, named, pose and position goals and Cartesian paths in a scene, failures
as results with a status, time parameterization and sampling of the path, and a scene that cannot change while a
plan runs in it."""

from __future__ import annotations

import threading

import numpy as np
import pytest

import sixdof_core


@pytest.fixture()
def context(arm, table_scene) -> sixdof_core.PlanningContext:
    return sixdof_core.PlanningContext(table_scene, "arm", sixdof_core.create_ik_solver("analytic", arm, "arm"))


def home(arm: sixdof_core.RobotModel) -> sixdof_core.RobotState:
    state = sixdof_core.RobotState(arm)
    state.set_to_named_state("arm", "home pose")
    return state


def assert_valid_path(context: sixdof_core.PlanningContext, start: sixdof_core.RobotState,
                      result: sixdof_core.PlanningResult) -> None:
    assert result.ok, result.message
    assert result.path.shape[1] == 6
    np.testing.assert_allclose(result.path[0], start.group_positions("arm"), atol=1e-9)
    state = start.copy()
    for point in result.path:
        state.set_group_positions("arm", point)
        assert not context.scene.is_colliding(state)


def test_joint_named_pose_and_position_goals(arm, context):
    start = home(arm)
    options = sixdof_core.PlanningOptions(allowed_planning_time=2.0, seed=3)
    goal = np.array([0.5, 0.3, 0.6, 0.0, 1.0, 0.0])
    to_joints = context.plan_to_joints(start, goal, options=options)
    assert_valid_path(context, start, to_joints)
    np.testing.assert_allclose(to_joints.path[-1], goal, atol=1e-9)
    within = context.plan_to_joints(start, goal, np.full(6, 0.05), options)
    assert_valid_path(context, start, within)
    assert np.abs(within.path[-1] - goal).max() <= 0.05 + 1e-9
    to_named = context.plan_to_named(start, "place pose", options=options)
    assert_valid_path(context, start, to_named)
    place = start.copy()
    place.set_to_named_state("arm", "place pose")
    np.testing.assert_allclose(to_named.path[-1], place.group_positions("arm"), atol=1e-9)
    pose = place.link_pose("link6")
    to_pose = context.plan_to_pose(start, pose, options=options)
    assert_valid_path(context, start, to_pose)
    reached = start.copy()
    reached.set_group_positions("arm", to_pose.path[-1])
    assert max(sixdof_core.pose_error(reached.link_pose("link6"), pose)) < 1e-5
    to_position = context.plan_to_position(start, pose[:3, 3], options=options)
    assert_valid_path(context, start, to_position)
    assert context.group == "arm" and context.joint_names == arm.group("arm").active_joints
    assert "RRTConnect" in sixdof_core.available_planner_ids()


def test_failures_come_back_as_results(arm, context, table_scene):
    start = home(arm)
    unknown = context.plan_to_named(start, "wave")
    assert unknown.status == sixdof_core.PlanningStatus.INVALID_REQUEST and "'home pose'" in unknown.message
    assert unknown.path.shape[0] == 0
    wrong_size = context.plan_to_joints(start, [0.0, 1.0])
    assert wrong_size.status == sixdof_core.PlanningStatus.INVALID_REQUEST
    below_table = context.plan_to_joints(start, [0.0, 1.5, 0.4, 0.0, 0.0, 0.0])
    assert below_table.status == sixdof_core.PlanningStatus.GOAL_IN_COLLISION
    out_of_reach = context.plan_to_pose(start, sixdof_core.pose_from_xyz_rpy(2.0, 0.0, 0.3, 0.0, 0.0, 0.0))
    assert out_of_reach.status == sixdof_core.PlanningStatus.NO_IK_SOLUTION
    unknown_planner = context.plan_to_joints(start, start.group_positions("arm"),
                                             options=sixdof_core.PlanningOptions(planner_id="Teleport"))
    assert unknown_planner.status == sixdof_core.PlanningStatus.INVALID_REQUEST
    assert "Teleport" in unknown_planner.message
    without_ik = sixdof_core.PlanningContext(table_scene, "arm")
    assert without_ik.plan_to_pose(start, np.eye(4)).status == sixdof_core.PlanningStatus.INVALID_REQUEST
    with pytest.raises(ValueError, match="unknown planning group 'legs'"):
        sixdof_core.PlanningContext(table_scene, "legs")


def test_cartesian_path(arm, context):
    start = sixdof_core.RobotState(arm)
    start.set_to_named_state("arm", "pick pose")
    above = start.link_pose("link6")
    up = above.copy()
    up[2, 3] += 0.03
    result = context.cartesian_path(start, [up], 0.005, sixdof_core.JumpThreshold(revolute=0.5))
    assert result.ok and result.fraction == pytest.approx(1.0)
    assert len(result.path) >= 7
    reached = start.copy()
    reached.set_group_positions("arm", result.path[-1])
    assert max(sixdof_core.pose_error(reached.link_pose("link6"), up)) < 1e-5
    into_table = above.copy()
    into_table[2, 3] = 0.0
    stopped = context.cartesian_path(start, [into_table], 0.005)
    assert stopped.status == sixdof_core.CartesianStatus.IN_COLLISION and 0.0 < stopped.fraction < 1.0


def test_time_parameterization_and_sampling(arm, context):
    start = home(arm)
    result = context.plan_to_named(start, "place pose", options=sixdof_core.PlanningOptions(seed=5))
    names = context.joint_names
    limits = sixdof_core.TimeParameterizationOptions([1.0] * 6, [2.0] * 6, velocity_scaling=0.5)
    timed = sixdof_core.compute_time_optimal_trajectory(names, result.path, limits)
    assert timed.ok, timed.message
    trajectory = timed.trajectory
    assert trajectory.joint_names == names and trajectory.validate() == ""
    assert trajectory.positions.shape == (len(trajectory.points), 6) and trajectory.duration > 0.0
    np.testing.assert_allclose(trajectory.positions[-1], result.path[-1], atol=1e-6)
    assert np.abs(trajectory.velocities).max() <= 0.5 * 1.001
    middle = trajectory.sample(trajectory.duration / 2)
    assert middle.position.shape == (6,) and middle.velocity.shape == (6,)
    # joint_trajectory_controller's semantics: before the first point, the first point at rest.
    before = trajectory.sample(-1.0)
    np.testing.assert_allclose(before.position, trajectory.positions[0])
    assert not before.velocity.any()
    bad = sixdof_core.compute_time_optimal_trajectory(names, result.path,
                                                      sixdof_core.TimeParameterizationOptions([1.0] * 5, [2.0] * 6))
    assert bad.status == sixdof_core.TimeParameterizationStatus.INVALID_INPUT and bad.message
    parabolic = sixdof_core.compute_iterative_parabolic_trajectory(names, result.path, limits)
    assert parabolic.ok, parabolic.message
    np.testing.assert_array_equal(parabolic.trajectory.positions, result.path)
    assert not parabolic.trajectory.velocities[[0, -1]].any()
    assert np.abs(parabolic.trajectory.velocities).max() <= 0.5 * (1 + 1e-9)
    handmade = sixdof_core.Trajectory(["a"], [sixdof_core.TrajectoryPoint([0.0], time_from_start=1.0),
                                             sixdof_core.TrajectoryPoint([1.0], time_from_start=0.5)])
    assert "increasing" in handmade.validate()
    with pytest.raises(ValueError, match="increasing"):
        handmade.sample(0.7)


def test_the_scene_cannot_change_while_a_plan_runs(arm, context, table_scene):
    # RRT* refines until its time is up, so the plan runs for the whole second, without the GIL.
    options = sixdof_core.PlanningOptions(planner_id="RRTstar", allowed_planning_time=1.0, seed=1)
    results = []
    plan = threading.Thread(target=lambda: results.append(
        context.plan_to_joints(home(arm), [0.5, 0.3, 0.6, 0.0, 1.0, 0.0], options=options)))
    plan.start()
    refused = 0
    while plan.is_alive():
        try:
            table_scene.add_box("late", [0.1, 0.1, 0.1], sixdof_core.pose_from_xyz_rpy(1, 1, 1, 0, 0, 0))
            table_scene.remove_object("late")
        except RuntimeError as error:
            assert "while a plan runs" in str(error)
            refused += 1
        plan.join(0.01)
    assert refused > 0 and results[0].ok
    table_scene.add_box("late", [0.1, 0.1, 0.1])


def test_collision_matrix(joint_kinds, arm):
    progress = []
    options = sixdof_core.CollisionMatrixOptions(density=300, seed=1)
    matrix = sixdof_core.compute_disabled_collisions(arm, options, lambda done, total: progress.append((done, total)))
    assert matrix.samples == 300 and progress[-1] == (300, 300)
    adjacent = {(p.link1, p.link2) for p in matrix.disabled if p.reason == sixdof_core.DisableReason.ADJACENT}
    assert adjacent == set(sixdof_core.adjacent_link_pairs(arm))
    assert {p.reason_name for p in matrix.disabled} <= {"Adjacent", "Default", "Always", "Never"}
    assert matrix.link_pairs == len(arm.link_names[:-1]) * (len(arm.link_names) - 2) // 2
    with pytest.raises(ValueError, match="density"):
        sixdof_core.compute_disabled_collisions(joint_kinds, sixdof_core.CollisionMatrixOptions(density=0))

"""moveit_commander and moveit_msgs without a ROS master: names, exceptions, conversions, argument forms,
kinematics (Jacobian, bounds) and the iterative time parameterization, on the fixture robot."""

import inspect
import math
import sys
from pathlib import Path

import moveit_commander
import moveit_msgs.msg
import moveit_msgs.srv
import numpy as np
import pytest
import sixdof_commander.move_group
import sixdof_commander.planning_scene
from geometry_msgs.msg import Pose, Transform
from moveit_commander import conversions
from sixdof_commander import MoveItCommanderException, SixdofCommanderError
from sixdof_commander.cartesian_path import _cartesian_arguments
from sixdof_commander.exceptions import UnknownGroupError
from sixdof_commander.kinematics import bounded, iterative_parabolic_times, jacobian, link_pose
from sixdof_commander.robot_model import resolve_group


def test_moveit_msgs_is_the_generated_package_the_commander_uses():
    assert moveit_msgs.msg.DisplayTrajectory._type == "moveit_msgs/DisplayTrajectory"
    assert moveit_msgs.srv.GetMotionPlan._type == "moveit_msgs/GetMotionPlan"
    assert sixdof_commander.move_group.RobotTrajectory is moveit_msgs.msg.RobotTrajectory
    assert sixdof_commander.planning_scene.CollisionObject is moveit_msgs.msg.CollisionObject
    # No second moveit_msgs on the path (sixdof_scripts installs none): every one found is the generated package.
    found = [Path(entry) / "moveit_msgs" for entry in sys.path if (Path(entry) / "moveit_msgs").is_dir()]
    assert found
    for package in found:
        assert (package / "msg" / "_MoveItErrorCodes.py").is_file(), f"{package} is not the generated moveit_msgs"


def test_one_exception_hierarchy():
    assert moveit_commander.MoveItCommanderException is MoveItCommanderException
    assert issubclass(SixdofCommanderError, MoveItCommanderException)
    # MoveIt's C++ wrapper raises RuntimeError for an unknown group; ours is both.
    assert issubclass(UnknownGroupError, RuntimeError) and issubclass(UnknownGroupError, MoveItCommanderException)


def test_unknown_group_raises_runtime_error_naming_the_groups(urdf, srdf):
    with pytest.raises(RuntimeError, match=r"no group 'manipulator'; groups: \['arm', 'both', 'gripper'\]"):
        resolve_group(urdf, srdf, "manipulator")


def test_module_level_api():
    for name in ("roscpp_initialize", "roscpp_shutdown", "MoveItCommanderException", "conversions",
                 "RobotCommander", "MoveGroupCommander", "PlanningSceneInterface"):
        assert hasattr(moveit_commander, name), name
    moveit_commander.roscpp_initialize(["script.py", "__name:=x"])
    moveit_commander.roscpp_shutdown()
    with pytest.raises(MoveItCommanderException, match="roscpp_initialize needs a list of strings"):
        moveit_commander.roscpp_initialize("script.py")


def test_planning_scene_interface_is_synchronous_by_default():
    # Upstream defaults to False; ours applies each change before returning unless asked not to.
    parameters = inspect.signature(moveit_commander.PlanningSceneInterface).parameters
    assert parameters["synchronous"].default is True
    assert parameters["ns"].default == ""


def test_pose_list_conversions_round_trip():
    pose = conversions.list_to_pose([0.1, 0.2, 0.3, 0.0, 0.0, math.pi / 2])
    values = conversions.pose_to_list(pose)
    np.testing.assert_allclose(values, [0.1, 0.2, 0.3, 0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5)], atol=1e-12)
    assert conversions.pose_to_list(conversions.list_to_pose(values)) == values
    stamped = conversions.list_to_pose_stamped(values, "base_link")
    assert stamped.header.frame_id == "base_link" and isinstance(stamped.pose, Pose)
    transform = conversions.list_to_transform(values)
    assert isinstance(transform, Transform)
    assert conversions.transform_to_list(transform) == values
    restored = Pose()
    conversions.msg_from_string(restored, conversions.msg_to_string(pose))
    assert restored == pose


@pytest.mark.parametrize("bad", [[1, 2, 3], [0] * 8, "1234567", [0, 0, 0, 0, 0, float("nan")]])
def test_bad_pose_lists_raise(bad):
    with pytest.raises(MoveItCommanderException, match="list_to_pose"):
        conversions.list_to_pose(bad)


@pytest.mark.parametrize(
    "args, kwargs, expected",
    [
        ((), {}, (0.0, True)),
        ((False,), {}, (0.0, False)),  # 1.1.15 on: (waypoints, eef_step, avoid_collisions)
        ((0.0,), {}, (0.0, True)),  # before: (waypoints, eef_step, jump_threshold)
        ((0.0, False), {}, (0.0, False)),  # before: (waypoints, eef_step, jump_threshold, avoid_collisions)
        ((2,), {}, (2, True)),
        ((), {"avoid_collisions": False}, (0.0, False)),
        ((), {"jump_threshold": 1.5, "avoid_collisions": False}, (1.5, False)),
    ],
)
def test_cartesian_path_accepts_both_signatures(args, kwargs, expected):
    assert _cartesian_arguments(args, kwargs) == expected


@pytest.mark.parametrize(
    "args, kwargs, message",
    [
        ((0.0, True, 1), {}, "too many positional arguments"),
        ((0.5,), {"jump_threshold": 0.5}, "jump_threshold given twice"),
        ((False,), {"avoid_collisions": True}, "avoid_collisions given twice"),
        ((), {"eef": 1}, "unexpected keyword arguments"),
    ],
)
def test_cartesian_path_bad_arguments(args, kwargs, message):
    with pytest.raises(MoveItCommanderException, match=message):
        _cartesian_arguments(args, kwargs)


def test_pose_targets_are_alternative_goals(builder):
    builder.set_pose_targets([[0.4, 0.0, 0.3, math.pi, 0.0, 0.0], [0.3, 0.1, 0.3, math.pi, 0.0, 0.0]])
    request = builder.motion_plan_request()
    centres = [g.position_constraints[0].constraint_region.primitive_poses[0] for g in request.goal_constraints]
    assert [centre.position.y for centre in centres] == [0.0, 0.1]
    builder.set_pose_target([0.4, 0.0, 0.3, math.pi, 0.0, 0.0])
    assert len(builder.motion_plan_request().goal_constraints) == 1
    with pytest.raises(SixdofCommanderError, match="non-empty list of poses"):
        builder.set_pose_targets([])


def test_pose_reference_frame_is_the_default_frame(builder):
    builder.pose_reference_frame = "link1"
    builder.set_pose_target([0.4, 0.0, 0.3, math.pi, 0.0, 0.0])
    assert builder.pose_target.header.frame_id == "link1"


def test_forget_joint_values(builder):
    builder.remember_joint_values("here", [0.0] * 6)
    builder.forget_joint_values("here")
    assert "here" not in builder.named_targets()
    with pytest.raises(SixdofCommanderError, match="no remembered joint values named 'here'"):
        builder.forget_joint_values("here")


def test_jacobian_matches_finite_differences_of_forward_kinematics(urdf, arm):
    rng = np.random.default_rng(7)
    point = [0.0, 0.0, 0.1]  # the tcp, 0.1 m along link6's z axis
    for _ in range(20):
        q = {j.name: rng.uniform(max(j.lower, -3.0), min(j.upper, 3.0)) for j in arm.joints}
        jac = jacobian(urdf, arm, q, point)
        assert jac.shape == (6, 6)
        base = link_pose(urdf, "link6", q)
        origin = (base @ np.array(point + [1.0]))[:3]
        for column, joint in enumerate(arm.joints):
            shifted = dict(q)
            shifted[joint.name] += 1e-6
            moved = link_pose(urdf, "link6", shifted)
            velocity = ((moved @ np.array(point + [1.0]))[:3] - origin) / 1e-6
            np.testing.assert_allclose(jac[:3, column], velocity, atol=1e-5)
            skew = (moved[:3, :3] - base[:3, :3]) / 1e-6 @ base[:3, :3].T
            np.testing.assert_allclose(jac[3:, column], [skew[2, 1], skew[0, 2], skew[1, 0]], atol=1e-5)


def test_tcp_pose_at_zero_is_along_x(urdf):
    # design.md: at all-zero joints link6's z axis points along +x; tcp is 0.1 m further out.
    pose = link_pose(urdf, "tcp", {})
    np.testing.assert_allclose(pose[:3, 3], [0.12 + 0.18 + 0.08 + 0.1, 0.0, 0.6], atol=1e-9)


def test_bounds_are_enforced(urdf):
    assert bounded(urdf.joints["joint2"], 5.0) == 1.92
    assert bounded(urdf.joints["joint2"], -5.0) == -1.92
    assert bounded(urdf.joints["joint2"], 0.5) == 0.5


def test_iterative_time_parameterization_respects_the_limits():
    rng = np.random.default_rng(3)
    path = np.cumsum(rng.uniform(-0.2, 0.2, size=(30, 3)), axis=0)
    vmax, amax = np.array([1.0, 0.5, 2.0]), np.array([2.0, 1.0, 0.5])
    times, velocities, accelerations = iterative_parabolic_times(path, vmax, amax)
    assert times[0] == 0.0 and np.all(np.diff(times) > 0.0)
    np.testing.assert_allclose(velocities[0], 0.0)
    np.testing.assert_allclose(velocities[-1], 0.0)
    segment = np.diff(path, axis=0) / np.diff(times)[:, None]
    assert np.all(np.abs(segment) <= vmax * (1 + 1e-9))
    assert np.all(np.abs(velocities) <= vmax * (1 + 1e-9))
    assert np.all(np.abs(np.diff(velocities, axis=0)) / np.diff(times)[:, None] <= amax * (1 + 1e-6))
    # Halving the limits makes it slower, never faster.
    slower, _, _ = iterative_parabolic_times(path, vmax / 2, amax / 2)
    assert slower[-1] > times[-1]


def test_single_point_path_is_at_rest():
    times, velocities, accelerations = iterative_parabolic_times(np.zeros((1, 2)), np.ones(2), np.ones(2))
    assert times.tolist() == [0.0] and not velocities.any() and not accelerations.any()

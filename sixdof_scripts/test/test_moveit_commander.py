"""moveit_commander and moveit_msgs without a ROS master: names, exceptions, conversions, argument forms and
kinematics (the core's forward kinematics, Jacobian and random values; bounds), on the fixture robot."""

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
from sixdof_commander.kinematics import CoreKinematics, bounded
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


@pytest.fixture(scope="module")
def kinematics():
    data = Path(__file__).resolve().parent / "data"
    return CoreKinematics((data / "fixture.urdf").read_text(), (data / "fixture.srdf").read_text())


def test_jacobian_matches_finite_differences_of_forward_kinematics(kinematics, arm):
    rng = np.random.default_rng(7)
    point = [0.0, 0.0, 0.1]  # the tcp, 0.1 m along link6's z axis
    for _ in range(20):
        q = {j.name: rng.uniform(max(j.lower, -3.0), min(j.upper, 3.0)) for j in arm.joints}
        jac = kinematics.jacobian(arm.name, arm.tip_link, q, point)
        assert jac.shape == (6, 6)
        base = kinematics.link_pose("link6", q)
        origin = (base @ np.array(point + [1.0]))[:3]
        for column, joint in enumerate(arm.joints):
            shifted = dict(q)
            shifted[joint.name] += 1e-6
            moved = kinematics.link_pose("link6", shifted)
            velocity = ((moved @ np.array(point + [1.0]))[:3] - origin) / 1e-6
            np.testing.assert_allclose(jac[:3, column], velocity, atol=1e-5)
            skew = (moved[:3, :3] - base[:3, :3]) / 1e-6 @ base[:3, :3].T
            np.testing.assert_allclose(jac[3:, column], [skew[2, 1], skew[0, 2], skew[1, 0]], atol=1e-5)


def test_tcp_pose_at_zero_is_along_x(kinematics):
    # design.md: at all-zero joints link6's z axis points along +x; tcp is 0.1 m further out.
    pose = kinematics.link_pose("tcp", {})
    np.testing.assert_allclose(pose[:3, 3], [0.12 + 0.18 + 0.08 + 0.1, 0.0, 0.6], atol=1e-9)


def test_kinematics_errors_name_the_problem(kinematics, arm):
    with pytest.raises(SixdofCommanderError, match="nowhere"):
        kinematics.link_pose("nowhere", {})
    with pytest.raises(SixdofCommanderError, match="no_joint"):
        kinematics.link_pose("tcp", {"no_joint": 0.0})
    with pytest.raises(SixdofCommanderError, match="get_jacobian_matrix: .*no_group"):
        kinematics.jacobian("no_group", arm.tip_link, {})
    with pytest.raises(SixdofCommanderError, match="cannot read the robot description"):
        CoreKinematics("<robot name='x'>", "")


def test_random_group_values_are_within_the_limits(kinematics, arm):
    for _ in range(50):
        values = kinematics.random_group_values(arm.name)
        assert len(values) == len(arm.joints)
        for joint, value in zip(arm.joints, values, strict=True):
            assert joint.lower <= value <= joint.upper, (joint.name, value)


def test_bounds_are_enforced(urdf):
    assert bounded(urdf.joints["joint2"], 5.0) == 1.92
    assert bounded(urdf.joints["joint2"], -5.0) == -1.92
    assert bounded(urdf.joints["joint2"], 0.5) == 0.5

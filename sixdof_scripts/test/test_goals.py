"""Pose-target parsing, joint/named targets, parameter checks and MotionPlanRequest construction."""

import math

import numpy as np
import pytest
from geometry_msgs.msg import Pose, PoseStamped
from shape_msgs.msg import SolidPrimitive
from sixdof_commander import SixdofCommanderError
from sixdof_commander.goals import GoalBuilder, pose_stamped_from_target
from sixdof_commander.robot_model import resolve_group
from sixdof_commander.transforms import quaternion_from_rpy


def quat(pose):
    o = pose.orientation
    return (o.x, o.y, o.z, o.w)


def xyz(pose):
    p = pose.position
    return (p.x, p.y, p.z)


# Accepted pose forms ---------------------------------------------------------------------------------
def test_six_list_is_xyz_and_fixed_axis_rpy():
    target = pose_stamped_from_target([0.366, -0.0, 0.286, -math.pi, 0.012, 3.14], "base_link")
    assert target.header.frame_id == "base_link"
    assert xyz(target.pose) == pytest.approx((0.366, 0.0, 0.286))
    assert quat(target.pose) == pytest.approx(quaternion_from_rpy(-math.pi, 0.012, 3.14))


def test_seven_list_is_xyz_and_quaternion():
    q = quaternion_from_rpy(0.1, 0.2, 0.3)
    target = pose_stamped_from_target((0.1, 0.2, 0.3, *q), "base_link")
    assert xyz(target.pose) == pytest.approx((0.1, 0.2, 0.3))
    assert quat(target.pose) == pytest.approx(q)


def test_numpy_array_and_integers_are_accepted():
    target = pose_stamped_from_target(np.array([1, 0, 0, 0, 0, 0]), "base_link")
    assert xyz(target.pose) == pytest.approx((1.0, 0.0, 0.0))
    assert quat(target.pose) == pytest.approx((0.0, 0.0, 0.0, 1.0))


def test_nearly_unit_quaternion_is_renormalised():
    target = pose_stamped_from_target([0, 0, 0, 0, 0, 0, 1.0009], "base_link")
    assert quat(target.pose) == pytest.approx((0.0, 0.0, 0.0, 1.0), abs=1e-15)


def test_pose_message_gets_the_default_frame():
    pose = Pose()
    pose.position.x = 0.4
    pose.orientation.z = 1.0
    target = pose_stamped_from_target(pose, "base_link")
    assert target.header.frame_id == "base_link"
    assert xyz(target.pose) == pytest.approx((0.4, 0.0, 0.0))
    assert quat(target.pose) == pytest.approx((0.0, 0.0, 1.0, 0.0))


def test_pose_stamped_keeps_its_frame_and_empty_frame_means_default():
    stamped = PoseStamped()
    stamped.header.frame_id = "world"
    stamped.pose.orientation.w = 1.0
    assert pose_stamped_from_target(stamped, "base_link").header.frame_id == "world"
    stamped.header.frame_id = ""
    assert pose_stamped_from_target(stamped, "base_link").header.frame_id == "base_link"


# Rejected pose forms ---------------------------------------------------------------------------------
@pytest.mark.parametrize("length", [0, 1, 3, 5, 8, 12])
def test_wrong_list_length_is_rejected(length):
    with pytest.raises(SixdofCommanderError, match=f"6 elements .* or 7 .* got {length}"):
        pose_stamped_from_target([0.0] * length, "base_link")


@pytest.mark.parametrize(
    ("values", "message"),
    [
        ([0, 0, float("nan"), 0, 0, 0], r"element 2 \(z\) must be finite, got nan"),
        ([0, 0, 0, float("inf"), 0, 0], r"element 3 \(roll\) must be finite, got inf"),
        ([0, 0, 0, 0, 0, 0, float("-inf")], r"element 6 \(qw\) must be finite"),
        ([0, "1", 0, 0, 0, 0], r"element 1 \(y\) must be a number, got '1'"),
        ([0, 0, 0, 0, None, 0], r"element 4 \(pitch\) must be a number, got None"),
        ([True, 0, 0, 0, 0, 0], r"element 0 \(x\) must be a number, got True"),
        ([0, 0, 0, 0, 0, 0, 0], r"norm 0; a unit quaternion is required"),
        ([0, 0, 0, 0, 0, 0, 2], r"norm 2; a unit quaternion"),
        ([0, 0, 0, 0.5, 0, 0, 0.5], r"norm 0\.707107"),
        ([0, 0, 0, 0, 0, 0, 1.0011], r"norm 1\.0011"),
    ],
)
def test_bad_numbers_are_rejected_with_the_element_named(values, message):
    with pytest.raises(SixdofCommanderError, match=message):
        pose_stamped_from_target(values, "base_link")


@pytest.mark.parametrize("target", ["0 0 0 0 0 0", {"x": 0}, 3.0, None, np.zeros((2, 3))])
def test_non_list_targets_are_rejected(target):
    with pytest.raises(SixdofCommanderError, match="must be a list of numbers"):
        pose_stamped_from_target(target, "base_link")


def test_default_pose_message_has_a_zero_quaternion_and_is_rejected():
    with pytest.raises(SixdofCommanderError, match="orientation .* has norm 0"):
        pose_stamped_from_target(Pose(), "base_link")


def test_nan_in_pose_message_is_rejected():
    pose = Pose()
    pose.orientation.w = 1.0
    pose.position.y = float("nan")
    with pytest.raises(SixdofCommanderError, match=r"position\.y must be finite"):
        pose_stamped_from_target(pose, "base_link")


# Goals -> MotionPlanRequest --------------------------------------------------------------------------
def test_pose_target_becomes_position_and_orientation_constraints(builder):
    builder.set_goal_position_tolerance(0.002)
    builder.set_goal_orientation_tolerance(0.01)
    builder.set_pose_target([0.3, 0.1, 0.2, math.pi, 0.0, 0.5])
    request = builder.motion_plan_request()
    assert len(request.goal_constraints) == 1
    goal = request.goal_constraints[0]
    assert goal.joint_constraints == []
    (position,) = goal.position_constraints
    assert position.link_name == "link6"
    assert position.header.frame_id == "base_link"
    # MoveIt's goal region: a sphere of the tolerance's radius centred on the target position.
    (sphere,) = position.constraint_region.primitives
    assert (sphere.type, list(sphere.dimensions)) == (SolidPrimitive.SPHERE, [0.002])
    (centre,) = position.constraint_region.primitive_poses
    assert xyz(centre) == pytest.approx((0.3, 0.1, 0.2))
    assert quat(centre) == (0.0, 0.0, 0.0, 1.0)
    offset = position.target_point_offset
    assert (offset.x, offset.y, offset.z) == (0.0, 0.0, 0.0)
    assert position.weight == 1.0
    (orientation,) = goal.orientation_constraints
    assert orientation.link_name == "link6"
    assert orientation.header.frame_id == "base_link"
    o = orientation.orientation
    assert (o.x, o.y, o.z, o.w) == pytest.approx(quaternion_from_rpy(math.pi, 0.0, 0.5))
    tolerances = (
        orientation.absolute_x_axis_tolerance,
        orientation.absolute_y_axis_tolerance,
        orientation.absolute_z_axis_tolerance,
    )
    assert tolerances == (0.01, 0.01, 0.01)
    assert orientation.weight == 1.0


def test_request_carries_group_and_planning_parameters(builder):
    builder.set_pose_target([0.3, 0.1, 0.2, 0, 0, 0])
    builder.planner_id = "RRTstar"
    builder.set_planning_time(2.5)
    builder.set_num_planning_attempts(4)
    builder.set_max_velocity_scaling_factor(0.25)
    builder.set_max_acceleration_scaling_factor(1.0)
    request = builder.motion_plan_request()
    assert request.group_name == "arm"
    assert request.planner_id == "RRTstar"
    assert request.allowed_planning_time == 2.5
    assert request.num_planning_attempts == 4
    assert request.max_velocity_scaling_factor == 0.25
    assert request.max_acceleration_scaling_factor == 1.0
    assert request.start_state.is_diff is True
    assert request.start_state.joint_state.name == []


def test_moveit_default_parameters(builder):
    assert builder.planning_time == 5.0
    assert builder.num_planning_attempts == 1
    assert (builder.goal_joint_tolerance, builder.goal_position_tolerance, builder.goal_orientation_tolerance) == (
        1e-4,
        1e-4,
        1e-3,
    )


def test_position_target_has_no_orientation_constraint(builder):
    builder.set_position_target([0.3, -0.1, 0.25])
    goal = builder.goal_constraints()
    assert len(goal.position_constraints) == 1
    assert goal.orientation_constraints == []
    assert list(goal.position_constraints[0].constraint_region.primitives[0].dimensions) == [1e-4]


def test_position_target_keeps_previous_orientation(builder):
    builder.set_pose_target([0.3, 0.1, 0.2, 0.0, 0.0, 1.0])
    builder.set_position_target((0.1, 0.2, 0.3))
    assert quat(builder.pose_target.pose) == pytest.approx(quaternion_from_rpy(0.0, 0.0, 1.0))


@pytest.mark.parametrize("bad", [[0.1, 0.2], [0.1, 0.2, 0.3, 0.4], [0.1, float("nan"), 0.3]])
def test_bad_position_target_is_rejected(builder, bad):
    with pytest.raises(SixdofCommanderError, match="position target"):
        builder.set_position_target(bad)


def test_joint_target_becomes_joint_constraints_in_group_order(builder):
    values = [0.1, -0.2, 0.3, -0.4, 0.5, -0.6]
    builder.set_goal_joint_tolerance(0.01)
    builder.set_joint_value_target(values)
    goal = builder.goal_constraints()
    assert goal.position_constraints == [] and goal.orientation_constraints == []
    assert [c.joint_name for c in goal.joint_constraints] == [f"joint{i}" for i in range(1, 7)]
    assert [c.position for c in goal.joint_constraints] == values
    assert all(c.tolerance_above == 0.01 and c.tolerance_below == 0.01 for c in goal.joint_constraints)
    assert all(c.weight == 1.0 for c in goal.joint_constraints)


def test_joint_dict_target_partial_uses_current_values(builder):
    current = {f"joint{i}": 0.01 * i for i in range(1, 7)}
    builder.set_joint_value_target({"joint3": 1.0}, current)
    assert builder.joint_target == {**current, "joint3": 1.0}


def test_later_target_replaces_earlier_kind(builder):
    builder.set_pose_target([0.3, 0.1, 0.2, 0, 0, 0])
    builder.set_joint_value_target([0.0] * 6)
    assert builder.goal_constraints().position_constraints == []
    builder.set_pose_target([0.3, 0.1, 0.2, 0, 0, 0])
    assert builder.goal_constraints().joint_constraints == []


def test_clear_pose_targets_leaves_no_target(builder):
    builder.set_pose_target([0.3, 0.1, 0.2, 0, 0, 0])
    builder.clear_pose_targets()
    with pytest.raises(SixdofCommanderError, match="no target set for group 'arm'"):
        builder.motion_plan_request()


@pytest.mark.parametrize(
    ("values", "message"),
    [
        ([0.0] * 5, r"must have 6 values .*got 5"),
        ([0.0] * 7, r"must have 6 values .*got 7"),
        ([0.0, 2.0, 0.0, 0.0, 0.0, 0.0], r"joint target 2 of 'joint2' is outside its limits \[-1\.92, 1\.92\]"),
        ([0.0, 0.0, 0.0, 0.0, -2.2, 0.0], r"'joint5' is outside its limits"),
        ([0.0, 0.0, float("nan"), 0.0, 0.0, 0.0], r"joint target value of 'joint3' must be finite"),
        ({"joint7": 0.0}, r"joints \['joint7'\] are not in group 'arm'"),
        ({"finger1_joint": 0.0}, r"joints \['finger1_joint'\] are not in group 'arm'"),
        ({"joint1": 0.0}, r"lacks joints \['joint2'"),
        ("home pose", r"must be a list of numbers"),
    ],
)
def test_bad_joint_targets_are_rejected(builder, values, message):
    with pytest.raises(SixdofCommanderError, match=message):
        builder.set_joint_value_target(values)


def test_joint_target_within_tolerance_of_a_limit_is_accepted(builder):
    builder.set_joint_value_target([0.0, 1.92 + 5e-5, 0.0, 0.0, 0.0, 0.0])


def test_named_targets_come_from_the_srdf(builder):
    assert builder.named_targets() == ["home pose", "pick pose"]
    assert builder.named_target_values("home pose")["joint5"] == 1.5708
    builder.set_named_target("pick pose")
    assert [c.position for c in builder.goal_constraints().joint_constraints] == [-0.35, 0.6, 0.4, 0.0, 0.6, -0.35]


def test_unknown_named_target_is_rejected_with_the_known_ones(builder):
    with pytest.raises(SixdofCommanderError, match=r"unknown named target 'open' .* \['home pose', 'pick pose'\]"):
        builder.set_named_target("open")


def test_remembered_joint_values_are_named_targets(builder):
    builder.remember_joint_values("mine", [0.1] * 6)
    assert "mine" in builder.named_targets()
    builder.set_named_target("mine")
    assert builder.joint_target == {f"joint{i}": 0.1 for i in range(1, 7)}


# Parameter checks ------------------------------------------------------------------------------------
@pytest.mark.parametrize("value", [0.0, -0.1, 1.0001, 2, float("nan"), float("inf"), "0.5", None])
@pytest.mark.parametrize("setter", ["set_max_velocity_scaling_factor", "set_max_acceleration_scaling_factor"])
def test_scaling_factor_outside_zero_one_is_rejected(builder, setter, value):
    with pytest.raises(SixdofCommanderError, match="scaling factor"):
        getattr(builder, setter)(value)


@pytest.mark.parametrize("value", [1e-6, 0.5, 1.0, 1])
def test_scaling_factor_inside_zero_one_is_accepted(builder, value):
    builder.set_max_velocity_scaling_factor(value)
    builder.set_max_acceleration_scaling_factor(value)
    assert builder.max_velocity_scaling_factor == value == builder.max_acceleration_scaling_factor


@pytest.mark.parametrize(
    ("setter", "value", "message"),
    [
        ("set_planning_time", 0.0, "planning time must be > 0"),
        ("set_planning_time", float("nan"), "planning time must be finite"),
        ("set_num_planning_attempts", 0, "attempts must be an integer >= 1"),
        ("set_num_planning_attempts", 1.5, "attempts must be an integer >= 1"),
        ("set_goal_joint_tolerance", -1e-3, "goal joint tolerance must be > 0"),
        ("set_goal_position_tolerance", 0.0, "goal position tolerance must be > 0"),
        ("set_goal_orientation_tolerance", float("inf"), "goal orientation tolerance must be finite"),
    ],
)
def test_bad_parameters_are_rejected(builder, setter, value, message):
    with pytest.raises(SixdofCommanderError, match=message):
        getattr(builder, setter)(value)


def test_end_effector_link_must_exist(builder, urdf):
    builder.set_end_effector_link("tcp", urdf.links)
    builder.set_pose_target([0.3, 0.1, 0.2, 0, 0, 0])
    assert builder.goal_constraints().position_constraints[0].link_name == "tcp"
    with pytest.raises(SixdofCommanderError, match="end-effector link 'hand' is not a link"):
        builder.set_end_effector_link("hand", urdf.links)


def test_gripper_named_state_with_a_mimic_joint_targets_the_active_joint(urdf, srdf):
    gripper = GoalBuilder(resolve_group(urdf, srdf, "gripper"), "base_link")
    gripper.set_named_target("open")
    assert gripper.joint_target == {"finger1_joint": 0.04}
    (constraint,) = gripper.goal_constraints().joint_constraints
    assert (constraint.joint_name, constraint.position) == ("finger1_joint", 0.04)


def test_mimic_joint_in_a_dict_target_is_rejected(urdf, srdf):
    gripper = GoalBuilder(resolve_group(urdf, srdf, "gripper"), "base_link")
    with pytest.raises(SixdofCommanderError, match="'finger2_joint' mimics 'finger1_joint' .* set that one instead"):
        gripper.set_joint_value_target({"finger2_joint": 0.01})
